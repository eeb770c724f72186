#pragma once
// M-step with Ceres: Levenberg-Marquardt over SE(3), parameterised as a unit quaternion on
// Ceres' EigenQuaternionManifold plus a translation in R^3, with autodiff Jacobians. Minimises the
// same objective as the Gauss-Newton solver; it is the place to add pose priors or robust losses.

#include <Eigen/Geometry>

#include "pda_registration/core/association_weights.hpp"

namespace pda_registration {

/// Starts from *T_target_source and overwrites it with the LM solution. Returns false when the
/// problem is empty or Ceres reports a failure (the estimate is then left unchanged).
bool solveWithCeres(const WeightedCorrespondences& correspondences, int max_iterations, int threads,
                    Eigen::Isometry3d* T_target_source);

}  // namespace pda_registration
