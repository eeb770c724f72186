#pragma once
// What the nodelet's diagnostics report: counters, the last result, the last problem and the
// dense map in use. Written by the callbacks and the worker threads, read by the 1 Hz
// diagnostics; every access goes through one mutex.

#include <diagnostic_updater/DiagnosticStatusWrapper.h>
#include <ros/time.h>

#include <map>
#include <mutex>
#include <string>

#include "pda_registration/core/pose_covariance.hpp"
#include "pda_registration/core/registration_result.hpp"
#include "pda_registration/ros/seed_lookup.hpp"

namespace pda_registration {

struct AlignmentStatusValues {
  size_t sparse_received = 0, dense_received = 0, dense_unchanged = 0;
  size_t dropped_stale = 0, dropped_throttled = 0;
  size_t input_errors = 0, missing_seed = 0;
  size_t aligned = 0, accepted = 0, rejected = 0;
  bool have_result = false, last_accepted = false;
  RegistrationResult last_result;
  ExpectedError expected_error;  ///< of the last result, as published (dense frame)
  SeedSource last_seed = SeedSource::kNone;
  // Tf edges composed with the latest tf because tf had nothing at the cloud's stamp (TfEdge).
  size_t edges_from_latest_tf = 0;
  bool last_edge_at_stamp = true;
  std::string last_problem;  // the latest rejection or input error, for the WARN status
  double last_latency_ms = 0.0;
  ros::Time last_problem_time;
  // The dense map in use: its size, when it arrived (wall clock: sim time may jump back or
  // stand still), and the size of the current (possibly cropped) index.
  size_t dense_points = 0, indexed_points = 0;
  bool target_cropped = false;
  bool roles_swapped = false;   ///< the source was the denser cloud: EM ran the other way round
  bool search_widened = false;  ///< came to rest unresolved: aligned again with the radius doubled
  bool local_start = false;     ///< did not converge: aligned again from the seed, outlier class
  bool near_search = false;     ///< questionable: aligned again from the seed, searching near
  bool warp_polished = false;   ///< the overlap's halves disagreed: refined to least squares
  ros::WallTime dense_arrival;
  // Index keeping (its own thread): when the index in use became ready, what its last update
  // cost and how it went ("extended", "indexed", ...).
  ros::WallTime index_ready;
  double index_update_ms = 0.0, index_update_cpu_ms = 0.0;
  std::string index_update;
  size_t index_updates = 0;
  // The sparse clouds' sample spacing, and the voxel of the dense map's indexed subset (0: the
  // whole map is indexed; core/representative_subset.hpp).
  double sparse_spacing = 0.0, dense_subset_voxel = 0.0;
  // Folds of an extended index's trees into one (background, dense_map_keeper.hpp).
  double index_fold_ms = 0.0;
  size_t index_folds = 0;
  // Source points of the last alignment: as received, and used (after the budget and filters).
  size_t source_points_received = 0, source_points_used = 0;
  // The source budget that keeps up with the sparse clouds (ros/rate_budget.hpp) and the
  // period it was fitted to (0: not measured yet).
  size_t source_budget = 0;
  double sparse_period_s = 0.0;
  int threads_used = 0;  ///< by the last alignment: at most `threads`, no more than idle cores
  // Whether the last alignment started from the seed corrected by the last accepted correction
  // (core/warm_start.hpp), or why not; and how often such a start was rejected and retried.
  std::string warm_start = "no alignment yet";
  size_t warm_start_retries = 0;
  size_t out_of_time = 0;  ///< warm alignments abandoned at their deadline (deadline_periods)
};

class AlignmentStatus {
 public:
  /// Runs `change` on the values under the lock.
  template <class Change>
  void update(Change&& change) {
    std::lock_guard<std::mutex> lock(mutex_);
    change(values_);
  }

  /// Records a problem (counted as an input error when `input_error`). Returns true when it
  /// should be logged: at most one WARN per `kind` every few seconds, so a bad stream cannot
  /// flood the log while different problems still each get their line.
  bool recordProblem(const std::string& kind, const std::string& problem, bool input_error);

  /// Fills the diagnostic status; `dense_publishers` is the dense topic's publisher count.
  void fill(diagnostic_updater::DiagnosticStatusWrapper& status, uint32_t dense_publishers);

 private:
  bool shouldLog(const std::string& kind);

  std::mutex mutex_;
  AlignmentStatusValues values_;
  std::mutex log_mutex_;
  std::map<std::string, ros::WallTime> last_logged_;
};

}  // namespace pda_registration
