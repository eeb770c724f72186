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
#include "pda_registration/core/point_list.hpp"

namespace pda_registration {

/// Weights for one source point. squared_residuals[i] = |y_i - (R x + T)|^2_M in length units.
/// Writes posterior[i] = P(a_i) (sums to 1) and weight[i] = P(a_i) * E[w_i].
void computeCandidateWeights(const double* squared_residuals, size_t count, double nu,
                             double sigma_squared, double* posterior, double* weight);

/// The E-step's output, reduced to one weighted correspondence per source point with candidates.
struct WeightedCorrespondences {
  std::vector<size_t> source_index;  ///< which source point
  PointList source;                  ///< x_j (in the source frame)
  PointList target_mean;             ///< y_bar_j (in the target frame)
  std::vector<double> weight;        ///< W_j = sum_k rho_jk
  PointList normal;                  ///< n_j of the noise shape (zero: isotropic)
  double inverse_kappa = 1.0;        ///< 1 / surface anisotropy, shared by all
  double spread = 0.0;               ///< sum_j S_j, the part of the objective no pose can remove

  size_t size() const { return source.size(); }
};

/// Runs the E-step at the current estimate for every source point with candidates.
/// `normals` holds one target-surface normal per source point (zero where unknown) or is empty
/// for the isotropic model; `inverse_kappa` = 1 / surface anisotropy.
WeightedCorrespondences computeWeightedCorrespondences(
    const PointList& source, const CandidateSets& candidates, const PointList& normals,
    double inverse_kappa, const Eigen::Isometry3d& T_target_source, double nu, double sigma_squared,
    int threads);

/// The per-candidate posteriors at T, for inspection (same model as the E-step).
Associations computeAssociations(const PointList& source, const CandidateSets& candidates,
                                 const PointList& normals, double inverse_kappa,
                                 const Eigen::Isometry3d& T_target_source, double nu,
                                 double sigma_squared);

/// The weighted objective sum_jk rho_jk |y_k - T x_j|^2_M at T, from the reduced form.
double weightedObjective(const WeightedCorrespondences& correspondences,
                         const Eigen::Isometry3d& T_target_source);

/// EM update of sigma^2 for Sigma = sigma^2 I_d: the weighted objective at T divided by
/// d times the number of source points with candidates.
double estimateSigmaSquared(const WeightedCorrespondences& correspondences,
                            const Eigen::Isometry3d& T_target_source);

/// The mean squared distance from each source point to its candidates divided by d: a wide
/// first sigma^2 under which all candidates weigh almost alike, before EM narrows it.
double initialSigmaSquared(const PointList& source, const CandidateSets& candidates,
                           const Eigen::Isometry3d& T_target_source);

}  // namespace pda_registration
