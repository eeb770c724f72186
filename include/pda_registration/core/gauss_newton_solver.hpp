#pragma once
// M-step, Gauss-Newton on SE(3): minimises sum_j W_j |y_bar_j - (R x_j + t)|^2_{M_j} with the
// point's noise shape M_j (noise_model.hpp), solving 6x6 normal equations per iteration. Exact for
// both noise models and ~50x cheaper per M-step than building a Ceres problem, which matters
// because EM runs an M-step in every iteration.

#include <Eigen/Geometry>

#include "pda_registration/core/association_weights.hpp"

namespace pda_registration {

/// Iterates from *T_target_source until the step is below the epsilons or max_iterations.
/// Returns false (leaving *T unchanged) when the system is singular or has < 3 points.
bool solveGaussNewton(const WeightedCorrespondences& correspondences, int max_iterations,
                      double translation_epsilon, double rotation_epsilon,
                      Eigen::Isometry3d* T_target_source);

}  // namespace pda_registration
