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

}  // namespace pda_registration
