#pragma once
// Where each source point's noise shape (noise_model.hpp) comes from.
//
// The target is a sampling of a surface. A source point that hit the surface between two target
// samples lies about a sample spacing from the nearest one, along the surface, however well the
// clouds are aligned; a residual along the surface smaller than that says nothing about the pose.
// So the sampling model gives every source point the covariance
//   Sigma_j = sigma^2 n n^T + max(kappa sigma^2, sigma^2 + s_j^2)(I - n n^T)  (target normal n)
//   Sigma_j = (sigma^2 + s_j^2) I                                           (no normal known)
// where s_j^2 = sampling_scale * (the target's local sampling spread around the point, measured
// on its own candidate set: the mean squared distance of its candidates from their centroid)
// and kappa = surface_anisotropy. In the shape form Sigma_j = sigma^2 M_j, kappa_j grows as sigma
// shrinks (kappa_j >= 1 + s_j^2 / sigma^2): sigma settles on the noise across the surface without
// the weights starting to reward sample-to-sample coincidences (two scans of one lidar share its
// azimuth lattice, and a yaw of whole azimuth steps then fits the ground as well as the truth).
// Without a normal (a far ground ring, a pole, foliage) the sampling alone bounds the weights.
//
// sampling_scale = 0 keeps the constant model kappa_j = surface_anisotropy where a normal is
// known (1 elsewhere); surface_anisotropy = 1 is the paper's isotropic Sigma = sigma^2 I in both.

#include <vector>

#include "pda_registration/core/candidate_sets.hpp"
#include "pda_registration/core/point_list.hpp"
#include "pda_registration/core/registration_parameters.hpp"

namespace pda_registration {

/// One shape per source point of a candidate set; empty vectors mean the isotropic M = I.
struct NoiseShapes {
  PointList normal;                   ///< unit target normal, or zero where none is known
  std::vector<double> inverse_kappa;  ///< 1 / kappa_j
  bool sampling = false;              ///< kappa_j follows sigma (changes the sigma^2 update)

  Point normalAt(size_t j) const { return normal.empty() ? Point::Zero() : normal[j]; }
  double inverseKappaAt(size_t j) const { return inverse_kappa.empty() ? 1.0 : inverse_kappa[j]; }
};

/// The target's local sampling spread at every source point of `candidates`: the mean squared
/// distance of its candidates from their centroid (0 for fewer than two candidates).
std::vector<double> candidateSpread(const CandidateSets& candidates, int threads);

/// The target's thickness about its surface around the source points: the median, over source
/// points with a normal and at least three candidates, of the candidates' variance along that
/// normal (unbiased). 0 when fewer than ten points qualify. sigma^2 models the residual to one
/// target sample, and that sample carries its own noise about the surface, so sigma^2 cannot be
/// smaller than this: the sampling model uses it as sigma^2's floor, which keeps the t-weights
/// from settling on coincidences finer than the target's noise (two scans of one lidar sample
/// the same cones and beam lines, whose points fit each other far better than the surface).
double targetThickness(const CandidateSets& candidates, const PointList& normals);

/// True when the parameters ask for the sampling model.
bool usesSamplingModel(const RegistrationParameters& parameters);

/// The shapes for one E-step at the current sigma^2, into *shapes (reusing its memory: EM calls
/// this every iteration). `normals` (one per source point) may be empty when the model is
/// isotropic; `spread` (from candidateSpread) is only read by the sampling model. `normals` may
/// be shapes->normal itself (a run's EM loop keeps them there, so they are not copied each time).
void makeNoiseShapes(const PointList& normals, const std::vector<double>& spread,
                     double sigma_squared, const RegistrationParameters& parameters,
                     NoiseShapes* shapes);

}  // namespace pda_registration
