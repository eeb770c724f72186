#include "pda_registration/core/alignment_verdict.hpp"

#include <sstream>

namespace pda_registration {

bool residualsSpanTheSearch(const RegistrationParameters& p, double sigma) {
  return p.sigma_mode == SigmaMode::kEstimated && 6.0 * sigma >= p.radius;
}

void judgeConvergence(const RegistrationParameters& p, bool came_to_rest,
                    const Increment& last_run_step, RegistrationResult* result,
                    const char* search_name) {
  RegistrationResult& r = *result;
  std::ostringstream reason;
  r.converged = false;
  if (!came_to_rest) {
    if (p.max_runs == 1) {
      reason << "EM did not settle in " << p.max_em_iterations << " iterations";
    } else if (r.out_of_time) {
      reason << "out of time: still moving after " << r.runs << " runs at the time limit of "
             << p.time_limit_ms << " ms (the last run moved " << last_run_step.translation
             << " and rotated " << last_run_step.rotation << " rad)";
    } else {
      reason << "not converged after " << r.runs << " runs (the work of " << p.max_runs
             << " over the whole source; the last moved " << last_run_step.translation
             << " and rotated " << last_run_step.rotation << " rad)";
    }
  } else if (r.degeneracy_ratio >= 0.0 && r.degeneracy_ratio < p.degeneracy_threshold) {
    reason << "degenerate geometry: the overlap constrains some direction weakly (eigenvalue "
           << "ratio " << r.degeneracy_ratio << " < " << p.degeneracy_threshold
           << ", e.g. a single plane or a corridor)";
  } else if (residualsSpanTheSearch(p, r.sigma)) {
    // The clouds were never brought onto each other, however still the estimate came to rest.
    reason << "unresolved: the residual scale sigma " << r.sigma << " is not below "
           << search_name << " / 6 (" << p.radius / 6.0
           << "): the estimate is not at a fit of the two clouds";
  } else if (r.support_fraction < p.min_support_fraction) {
    // sigma has settled on a small subset that fits almost exactly (a lattice alias of two scans
    // of one lidar, only the ground rings): the rest of the overlap says the pose is wrong. Source
    // points with no target point within radius (what only the source saw) do not count.
    reason << "unsupported: only " << 100.0 * r.support_fraction << " % of the " << r.overlap_points
           << " source points that overlap the target lie within " << p.inlier_sigmas
           << " sigma (sigma " << r.sigma << ") of it; the estimate rests on a subset (need "
           << 100.0 * p.min_support_fraction << " %)";
  } else {
    r.converged = true;
  }
  r.reason = reason.str();
}

}  // namespace pda_registration
