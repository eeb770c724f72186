#include "pda_registration/ros/alignment_status.hpp"

#include <cmath>

#include "pda_registration/core/process_memory.hpp"

namespace pda_registration {

bool AlignmentStatus::shouldLog(const std::string& kind) {
  std::lock_guard<std::mutex> lock(log_mutex_);
  // Kinds carry frame names: a stream of ever-new frames must not grow this without bound.
  if (last_logged_.size() > 256) last_logged_.clear();
  const ros::WallTime now = ros::WallTime::now();
  auto it = last_logged_.find(kind);
  if (it != last_logged_.end() && (now - it->second).toSec() < 5.0) return false;
  last_logged_[kind] = now;
  return true;
}

bool AlignmentStatus::recordProblem(const std::string& kind, const std::string& problem,
                                    bool input_error) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (input_error) ++values_.input_errors;
    values_.last_problem = problem;
    values_.last_problem_time = ros::Time::now();
    values_.last_accepted = false;
  }
  return shouldLog(kind);
}

void AlignmentStatus::fill(diagnostic_updater::DiagnosticStatusWrapper& status,
                           uint32_t dense_publishers) {
  std::lock_guard<std::mutex> lock(mutex_);
  const AlignmentStatusValues& s = values_;
  // A map whose publisher is gone still serves (a prior map need not be re-sent), but an
  // operator should know it will not be updated.
  const bool dense_gone = s.dense_points > 0 && dense_publishers == 0;
  if (s.last_accepted && dense_gone) {
    status.summary(diagnostic_msgs::DiagnosticStatus::WARN,
                   "aligned against the last dense map: its publisher is gone");
  } else if (s.last_accepted) {
    status.summary(diagnostic_msgs::DiagnosticStatus::OK, "aligned");
  } else if (!s.last_problem.empty()) {
    status.summary(diagnostic_msgs::DiagnosticStatus::WARN, s.last_problem);
  } else {
    status.summary(diagnostic_msgs::DiagnosticStatus::WARN, "waiting for dense and sparse clouds");
  }
  const RegistrationResult& r = s.last_result;
  status.add("converged", s.have_result && r.converged);
  status.add("sigma [m]", r.sigma);
  // The Student-t's nu at the end: `nu` itself, or what the refine runs estimated (nu_mode).
  status.add("nu", r.nu);
  // What ~pose's covariance expects (1 sigma): how far off the estimate probably is.
  status.add("expected error [cm]", 100.0 * s.expected_error.translation);
  status.add("expected error [deg]", s.expected_error.rotation * 180.0 / M_PI);
  // A second pose that fits as many of the points fixing the least certain direction, this far
  // from the estimate (0: none; core/competing_shift.hpp); the expected error includes it.
  status.add("competing pose [cm]", 100.0 * r.competing_shift);
  status.add("inlier fraction", r.inlier_fraction);
  status.add("support fraction", r.support_fraction);  // inliers among the overlapping points
  // The normal map's finest voxel: normal_voxel_size, or the map's scan-line scale if larger.
  status.add("normal voxel [m]", r.normal_voxel_size);
  status.add("runs", r.runs);
  status.add("alignment time [ms]", r.time_ms);
  status.add("latency [ms]", s.last_latency_ms);
  status.add("seed source", toString(s.last_seed));
  status.add("tf edges from the latest tf (none at the stamp)", s.edges_from_latest_tf);
  status.add("warm start", s.warm_start);
  status.add("warm starts retried from the seed", s.warm_start_retries);
  status.add("warm alignments out of time", s.out_of_time);
  status.add("dense clouds received", s.dense_received);
  status.add("dense clouds unchanged (not re-indexed)", s.dense_unchanged);
  status.add("dense map points", s.dense_points);
  status.add("dense map age [s]",
             s.dense_arrival.isZero() ? -1.0 : (ros::WallTime::now() - s.dense_arrival).toSec());
  status.add("dense map publishers", dense_publishers);
  status.add("indexed target points", s.indexed_points);
  status.add("sparse cloud spacing [cm]", 100.0 * s.sparse_spacing);
  status.add("dense map subset voxel [cm]", 100.0 * s.dense_subset_voxel);
  status.add("index age [s]",
             s.index_ready.isZero() ? -1.0 : (ros::WallTime::now() - s.index_ready).toSec());
  status.add("index update time [ms]", s.index_update_ms);
  status.add("index update CPU time [ms]", s.index_update_cpu_ms);
  status.add("index update", s.index_update);
  status.add("index updates", s.index_updates);
  status.add("index folds", s.index_folds);
  status.add("index fold time [ms]", s.index_fold_ms);
  status.add("source points received", s.source_points_received);
  status.add("source points used", s.source_points_used);
  status.add("source budget", s.source_budget);
  status.add("sparse cloud period [ms]", 1e3 * s.sparse_period_s);
  status.add("threads used", s.threads_used);
  status.add("target cropped", s.target_cropped);
  status.add("roles swapped", s.roles_swapped);
  status.add("search widened", s.search_widened);
  status.add("local start", s.local_start);
  status.add("near search", s.near_search);
  status.add("warp polished", s.warp_polished);
  status.add("resident memory [MB]", processMemory().resident_mb);
  status.add("sparse clouds received", s.sparse_received);
  status.add("alignments", s.aligned);
  status.add("accepted", s.accepted);
  status.add("rejected results", s.rejected);
  status.add("dropped stale inputs", s.dropped_stale);
  status.add("dropped by min_interval", s.dropped_throttled);
  status.add("input errors", s.input_errors);
  status.add("missing seed", s.missing_seed);
  status.add("last problem", s.last_problem);
}

}  // namespace pda_registration
