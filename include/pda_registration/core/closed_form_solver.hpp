#pragma once
// M-step, closed form: the rigid transform minimising sum_j W_j ||y_bar_j - (R x_j + T)||^2
// (weighted Kabsch/Umeyama, no scale). Exact in one SVD, so EM needs no inner iterations.

#include <Eigen/Geometry>

#include "pda_registration/core/association_weights.hpp"

namespace pda_registration {

/// Returns false (and leaves *T_target_source untouched) when fewer than 3 weighted points exist.
bool solveClosedForm(const WeightedCorrespondences& correspondences,
                     Eigen::Isometry3d* T_target_source);

}  // namespace pda_registration
