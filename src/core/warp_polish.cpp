#include "pda_registration/core/warp_polish.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "pda_registration/core/candidate_sets.hpp"
#include "pda_registration/core/degrees_of_freedom.hpp"
#include "pda_registration/core/run_rest.hpp"

namespace pda_registration {

bool warpPolishWarranted(const RegistrationResult& result, const RegistrationParameters& p,
                         double nu) {
  return result.converged && p.max_runs > 1 && result.disagreeing_halves > 0 && std::isfinite(nu) &&
         nu > kMinDegreesOfFreedom;
}

double polishRadius(const RegistrationParameters& p, double sigma_squared, double surface_scale) {
  if (p.min_radius >= p.radius) return p.radius;  // a radius the user fixed
  const double lowest = surface_scale > 0.0 ? std::min(p.min_radius, surface_scale) : p.min_radius;
  return std::min(p.radius, std::max(lowest, kPolishRadiusSigmas * std::sqrt(sigma_squared)));
}

bool polishOverAWarp(const TargetIndex& index, const PointList& source,
                     const SurfaceNormalMap& normal_map, double surface_scale,
                     const RegistrationParameters& p, const PoseStep& step_metric,
                     const std::function<bool()>& out_of_time, RegistrationWorkspace* workspace,
                     EmState* state, int* runs, int* em_iterations) {
  RegistrationParameters gaussian = p;
  gaussian.nu = std::numeric_limits<double>::infinity();
  gaussian.nu_mode = NuMode::kFixed;
  EmState polished = *state;
  polished.nu = gaussian.nu;
  RunRest rest(step_metric);
  for (int run = 0; run < kMaxWarpPolishRuns; ++run) {
    if (out_of_time()) return false;
    findCandidateSets(index, source, polished.T, p.k,
                      polishRadius(p, polished.sigma_squared, surface_scale), p.threads,
                      &workspace->search, &workspace->candidates);
    const Eigen::Isometry3d T_run_start = polished.T;
    bool settled = false;
    ++*runs;
    if (!runEm(source, normal_map, NormalLookup::kAtCandidate, gaussian, &step_metric, workspace,
               &polished, &settled, em_iterations)) {
      return false;
    }
    if (isSmall(incrementBetween(T_run_start, polished.T), p) ||
        rest.cameBack(T_run_start, polished.T)) {
      *state = polished;
      return true;
    }
  }
  return false;
}

}  // namespace pda_registration
