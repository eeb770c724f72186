#pragma once
// What a registration result reports besides the estimate, computed once at the final estimate:
// sigma's inliers and their mean residual, the overlap and the inliers' share of it, the
// covariance, the degeneracy ratio, and on request the weighted associations.

#include "pda_registration/core/associations.hpp"
#include "pda_registration/core/em_run.hpp"
#include "pda_registration/core/registration_result.hpp"
#include "pda_registration/core/target_index.hpp"

namespace pda_registration {

/// Uses the workspace's candidate sets (for every source point) and its memory; `index` finds the
/// overlap of the source points without candidates.
void fillFinalStatistics(const PointList& source, const TargetIndex& index,
                         const SurfaceNormalMap& normal_map, const RegistrationParameters& p,
                         const EmState& state, RegistrationWorkspace* workspace,
                         RegistrationResult* result, Associations* associations);

/// support_fraction of the pose T measured with a yardstick of one's choice: the share of the
/// overlap (source points with a target point within `overlap_radius`) whose nearest target point
/// lies within `inlier_distance`. Two poses compared with one yardstick: a result's own
/// (inlier_sigmas times its sigma) favours the one whose residuals are wider.
double supportFractionAt(const TargetIndex& index, const PointList& source,
                         const Eigen::Isometry3d& T, double inlier_distance, double overlap_radius,
                         int threads);

}  // namespace pda_registration
