#pragma once
// The E-step (paper eqs. 14-16, 19-21): every candidate of a source point gets a posterior
// association probability P(a_jk) (normalised over the point's candidate set) times the
// expected Student-t precision E[w] = (nu + d) / (nu + r^2 / sigma^2), where r^2 is the residual
// in the point's noise shape (noise_model.hpp; plain ||r||^2 in the paper's isotropic model).
// nu = +inf is the Gaussian of eq. 19 (E[w] = 1).
//
// The weighted objective sum_k rho_k |y_k - z|^2_M of one source point equals
// W |y_bar - z|^2_M + S with W = sum rho_k, y_bar the rho-weighted mean of its candidates and S
// their weighted spread, so the M-step only needs one weighted correspondence per source point.

#include <Eigen/Geometry>
#include <vector>

#include "pda_registration/core/associations.hpp"
#include "pda_registration/core/candidate_sets.hpp"
#include "pda_registration/core/noise_shapes.hpp"
#include "pda_registration/core/outlier_class.hpp"
#include "pda_registration/core/point_list.hpp"

namespace pda_registration {

/// Weights for one source point. squared_residuals[i] = |y_i - (R x + T)|^2_M in length units.
/// Writes posterior[i] = P(a_i) (sums to 1) and weight[i] = P(a_i) * E[w_i]; and, if
/// log_precision is given and nu finite, log_precision[i] = log E[w_i] (for nu's statistic).
void computeCandidateWeights(const double* squared_residuals, size_t count, double nu,
                             double sigma_squared, double* posterior, double* weight,
                             double* log_precision = nullptr);

/// The E-step's output, reduced to one weighted correspondence per source point with candidates.
struct WeightedCorrespondences {
  std::vector<size_t> source_index;   ///< which source point
  PointList source;                   ///< x_j (in the source frame)
  PointList target_mean;              ///< y_bar_j (in the target frame)
  std::vector<double> weight;         ///< W_j = sum_k rho_jk
  PointList normal;                   ///< n_j of the noise shape (zero: no normal)
  std::vector<double> inverse_kappa;  ///< 1 / kappa_j of the noise shape
  /// S_j split across / along the surface (splitSquaredResidual): the part of the objective no
  /// pose can remove; the shaped spread is spread_across + inverse_kappa * spread_along.
  std::vector<double> spread_across, spread_along;
  bool sampling = false;  ///< the shapes follow sigma (noise_shapes.hpp): sigma^2 updates differ
  /// mean_j sum_i P(a_i) (log u_i - u_i), u_i = E[w | a_i]: the E-step's statistic for nu's
  /// update (degrees_of_freedom.hpp); only when the buffers ask for it, 0 for the Gaussian.
  double mean_log_u_minus_u = 0.0;
  /// sum_i P(a_i) u_i^2 (y_i - T x)(y_i - T x)^T per correspondence, only when the buffers ask
  /// for it (the covariance's observed information, pose_covariance.hpp); empty otherwise.
  std::vector<Eigen::Matrix3d> second_moment;
  /// The sum of the correspondences' inlier responsibilities gamma_j (outlier_class.hpp), over all
  /// and over those with a normal: the counts themselves without an outlier class. The weights and
  /// spreads above already carry gamma_j; sigma's update divides by these.
  double inlier_total = 0.0, inlier_total_with_normal = 0.0;

  size_t size() const { return source.size(); }
};

/// The E-step's per-source-point slots, kept between calls (see registration_workspace.hpp).
struct EStepBuffers {
  PointList means;
  std::vector<double> weights, across, along, log_u_minus_u;
  bool nu_statistic = false;    ///< also compute mean_log_u_minus_u (a log per candidate)
  bool second_moments = false;  ///< also fill WeightedCorrespondences::second_moment
  std::vector<Eigen::Matrix3d> moments;
  OutlierClass outliers;       ///< off unless the alignment asks for it (local_start.hpp)
  std::vector<double> inlier;  ///< gamma_j per source point
};

/// Runs the E-step at the current estimate for every source point with candidates, each in its
/// noise shape (one per source point; isotropic when `shapes` is), into *out. Reuses the memory
/// of *out and of the buffers (EM calls this every iteration); overwrites all of it.
void computeWeightedCorrespondences(const PointList& source, const CandidateSets& candidates,
                                    const NoiseShapes& shapes,
                                    const Eigen::Isometry3d& T_target_source, double nu,
                                    double sigma_squared, int threads, EStepBuffers* buffers,
                                    WeightedCorrespondences* out);

/// The per-candidate posteriors at T, for inspection (same model as the E-step).
Associations computeAssociations(const PointList& source, const CandidateSets& candidates,
                                 const NoiseShapes& shapes,
                                 const Eigen::Isometry3d& T_target_source, double nu,
                                 double sigma_squared);

/// The weighted objective sum_jk rho_jk |y_k - T x_j|^2_M at T, from the reduced form.
double weightedObjective(const WeightedCorrespondences& correspondences,
                         const Eigen::Isometry3d& T_target_source);

/// EM update of sigma^2. Fixed shapes (Sigma_j = sigma^2 M_j): the weighted objective at T divided
/// by d times the number of source points with candidates. Sampling shapes (noise_shapes.hpp):
/// sigma^2 is the noise across the surface, so the update is the weighted mean squared residual
/// along the normal over the points that have one (the objective's form when fewer than 10, or
/// fewer than a tenth of the correspondences, do).
double estimateSigmaSquared(const WeightedCorrespondences& correspondences,
                            const Eigen::Isometry3d& T_target_source);

/// The mean squared distance from each source point to its candidates divided by d: a wide
/// first sigma^2 under which all candidates weigh almost alike, before EM narrows it.
double initialSigmaSquared(const PointList& source, const CandidateSets& candidates,
                           const Eigen::Isometry3d& T_target_source);

}  // namespace pda_registration
