#pragma once
// M-step, closed form: the rigid transform minimising sum_j W_j ||y_bar_j - (R x_j + T)||^2
// (weighted Kabsch/Umeyama, no scale). Exact in one SVD for the isotropic noise model
// (surface_anisotropy = 1); it ignores surface normals, so it cannot serve the surface model.

#include <Eigen/Geometry>

#include "pda_registration/core/association_weights.hpp"

namespace pda_registration {

/// Returns false (and leaves *T_target_source untouched) when fewer than 3 weighted points exist.
bool solveClosedForm(const WeightedCorrespondences& correspondences,
                     Eigen::Isometry3d* T_target_source);

}  // namespace pda_registration
