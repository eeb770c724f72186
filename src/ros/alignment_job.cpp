#include "pda_registration/ros/alignment_job.hpp"

#include <algorithm>

#include "pda_registration/core/alignment_gate.hpp"
#include "pda_registration/core/pose_covariance.hpp"
#include "pda_registration/core/representative_subset.hpp"
#include "pda_registration/ros/input_checks.hpp"
#include "pda_registration/ros/point_cloud_conversion.hpp"
#include "pda_registration/ros/seed_lookup.hpp"
#include "pda_registration/ros/tf_edge.hpp"

namespace pda_registration {
namespace {
// How long an alignment waits for the very first dense map to be indexed (a 5M-point map takes a
// few seconds); later alignments take the newest ready map at once.
constexpr double kFirstMapTimeout = 30.0;
// How often the sparse clouds' spacing is measured again (a kd-tree over one cloud: ~3 ms for
// 30k points); the keeper re-indexes only when it changes by more than a factor of sqrt(2).
constexpr double kSpacingPeriod = 10.0;
// Warm alignments cut by the deadline in a row before one runs its course: at worst every sixth
// scan is answered on a machine that cannot align one within the deadline even at the budget's
// floor (rather than none), while a map's first coverage (its slides come 20-35 in a row on the
// growing office) still loses most of its slow, wrong answers.
constexpr int kMaxAbandonedInARow = 5;
}  // namespace

void AlignmentJob::reportSpacing(const PointList& sparse) {
  const ros::WallTime now = ros::WallTime::now();
  if (!last_spacing_.isZero() && (now - last_spacing_).toSec() < kSpacingPeriod) return;
  last_spacing_ = now;
  // The cloud as received (before source_voxel_size): a sensor's own spacing. Thinning the map to
  // a source voxel as well cost 2 mm on the dense-dense Kinect pair (both ~2 cm apart).
  c_.keeper->noteSparseSpacing(sampleSpacing(sparse));
}

const char* const AlignmentJob::kWarmStartUsed = "used";

std::string AlignmentJob::warmStartUse(const Seed& seed, const std::string& dense_frame,
                                       const std::string& sparse_frame,
                                       const LiveParameters& live) const {
  if (!live.warm_start) return "off";
  if (!warm_start_.holds(dense_frame, sparse_frame)) return "no accepted estimate yet";
  // The node's own edge on the seed's chain (own edge, correction edge): the seed already holds
  // the correction, and applying it again would count it twice.
  const NodeSettings& settings = *c_.settings;
  if (seed.source != SeedSource::kInitialTransform && settings.publish_tf &&
      frameInSeedChain(*c_.tf_buffer, dense_frame, sparse_frame,
                       edgeChildFrame(sparse_frame, settings.tf_child_frame))) {
    return "not applied: the node's own tf edge is part of the seed";
  }
  return kWarmStartUsed;
}

void AlignmentJob::run(const SparseJob& job, const LiveParameters& live) {
  const NodeSettings& settings = *c_.settings;
  const sensor_msgs::PointCloud2& cloud = *job.cloud;
  const std::string frame_problem = frameProblem(cloud, settings.expected_sparse_frame, "sparse");
  if (!frame_problem.empty()) {
    c_.log.problem("frame", frame_problem, true);
    return;
  }
  CloudConversion sparse = fromPointCloud2(cloud);
  if (!sparse.ok()) {
    c_.log.problem(
        "sparse " + sparse.error.substr(0, 12),
        "sparse cloud " + describeCloud(cloud, c_.sparse_topic) + " refused: " + sparse.error,
        true);
    return;
  }
  // The newest ready map; only while the first one is being indexed does this wait.
  const DenseMapKeeper::Borrowed map = c_.keeper->borrow(kFirstMapTimeout);
  if (!map) {
    c_.log.problem("no dense",
                   "no dense map ready yet (none received on " + c_.dense_topic +
                       ", or it could not be indexed); sparse cloud skipped",
                   false);
    return;
  }
  const std::string& dense_frame = map->frame;
  const std::string& sparse_frame = cloud.header.frame_id;
  const Seed seed =
      lookupSeed(*c_.tf_buffer, dense_frame, sparse_frame, cloud.header.stamp,
                 ros::Duration(settings.tf_timeout),
                 settings.has_initial_transform ? &settings.initial_transform : nullptr);
  if (seed.source == SeedSource::kNone) {
    c_.status->update([](AlignmentStatusValues& s) { ++s.missing_seed; });
    c_.log.problem("no seed " + sparse_frame,
                   "no seed for " + describeCloud(cloud, c_.sparse_topic) +
                       ": tf has no transform from '" + sparse_frame + "' to '" + dense_frame +
                       "' (" + seed.detail + ") and ~initial_transform is not set",
                   true);
    return;
  }
  SeedSource previous_seed = SeedSource::kNone;
  c_.status->update([&](AlignmentStatusValues& s) {
    previous_seed = s.last_seed;
    s.last_seed = seed.source;
  });
  if (seed.source != previous_seed)
    c_.log.info(std::string("seeding from ") + toString(seed.source));

  // The core aligns source to target; the output is always dense <- sparse.
  const bool want_markers = c_.publisher->hasAssociationSubscribers() && live.max_markers > 0;
  Associations associations;
  const PointList* source_points;
  PdaRegistration* registration;
  if (settings.dense_is_target) {
    registration = &map->registration;
    source_points = &sparse.points;
  } else {
    registration = &sparse_target_;
    registration->setParameters(live.registration);
    registration->setTarget(sparse.points);
    source_points = &map->points;
  }
  const auto targetSource = [&](const Eigen::Isometry3d& T_dense_sparse) {
    return settings.dense_is_target ? T_dense_sparse : T_dense_sparse.inverse();
  };
  // No more threads than the cores other processes leave idle (idle_cores.hpp).
  RegistrationParameters parameters = live.registration;
  parameters.threads = c_.idle_cores->threadsFor(parameters.threads);
  // Beyond what fits the sparse clouds' period, fewer source points (rate_budget.hpp).
  const size_t budget_cap = static_cast<size_t>(std::max(live.registration.max_source_points, 0));
  parameters.max_source_points =
      static_cast<int>(c_.rate_budget->budget(budget_cap, live.alignment_share));
  // A warm alignment still moving after deadline_periods sparse-cloud periods is abandoned: the
  // next scan is waiting, and an alignment that slow is sliding on a map that changed under it.
  // One from the seed (the first, or a retry) is never cut: it is what starts the track. Nor is
  // the one after kMaxAbandonedInARow cut ones: a machine too slow for the sensor still answers.
  const double period_s = c_.rate_budget->period();
  const bool deadline =
      live.deadline_periods > 0.0 && period_s > 0.0 && abandoned_in_a_row_ < kMaxAbandonedInARow;
  const double warm_time_limit_ms = deadline ? 1000.0 * live.deadline_periods * period_s : 0.0;

  // Beyond max_source_points the core aligns a subsample (source_budget.hpp: at random, or spread
  // over space with spread_source_budget); a
  // swapped alignment still indexes the whole dense source as its target. Every result is judged
  // against the seed itself, wherever the alignment started.
  const Eigen::Isometry3d seed_target_source = targetSource(seed.T_dense_sparse);
  RegistrationResult result;
  Verdict verdict;
  double attempts_ms = 0.0;
  std::string warm_start = warmStartUse(seed, dense_frame, sparse_frame, live);
  const bool retried = alignFromWarmStart(
      warm_start_, warm_start == kWarmStartUsed, seed.T_dense_sparse,
      [&](const Eigen::Isometry3d& T_dense_sparse_initial, bool warm_attempt) {
        parameters.time_limit_ms = warm_attempt ? warm_time_limit_ms : 0.0;
        registration->setParameters(parameters);
        result = registration->align(*source_points, targetSource(T_dense_sparse_initial),
                                     want_markers ? &associations : nullptr);
        verdict = judgeAlignment(result, seed_target_source, live.acceptance);
        attempts_ms += result.time_ms;
        if (verdict.accepted) return AttemptOutcome::kAccepted;
        return result.out_of_time ? AttemptOutcome::kOutOfTime : AttemptOutcome::kRejected;
      });
  result.time_ms = attempts_ms;  // both attempts, when the warm one was retried
  abandoned_in_a_row_ = result.out_of_time ? abandoned_in_a_row_ + 1 : 0;
  c_.rate_budget->noteAlignment(result.time_ms, result.source_points_used, budget_cap,
                                live.alignment_share);
  if (retried) warm_start = "used, rejected; retried from the seed";
  if (verdict.accepted) {
    const Eigen::Isometry3d T_dense_sparse =
        settings.dense_is_target ? result.T_target_source : result.T_target_source.inverse();
    warm_start_.remember(seed.T_dense_sparse, T_dense_sparse, dense_frame, sparse_frame);
  }
  c_.status->update([&](AlignmentStatusValues& s) {
    ++s.aligned;
    s.have_result = true;
    s.last_result = result;
    s.expected_error = expectedError(publishedCovariance(result));
    s.last_accepted = verdict.accepted;
    s.indexed_points = result.target_points_used;
    s.target_cropped = result.target_cropped;
    s.roles_swapped = result.roles_swapped;
    s.search_widened = result.search_widened;
    s.local_start = result.local_start;
    s.near_search = result.near_search;
    s.warp_polished = result.warp_polished;
    s.source_points_used = result.source_points_used;
    s.source_points_received = source_points->size();
    s.source_budget = static_cast<size_t>(parameters.max_source_points);
    s.sparse_period_s = c_.rate_budget->period();
    s.threads_used = parameters.threads;
    s.warm_start = warm_start;
    if (retried) ++s.warm_start_retries;
    if (result.out_of_time) ++s.out_of_time;
    if (verdict.accepted)
      ++s.accepted;
    else
      ++s.rejected;
  });
  if (!verdict.accepted) {
    c_.log.problem("rejected",
                   "alignment rejected, keeping the last good estimate: " + verdict.reason, false);
    if (settings.dense_is_target) reportSpacing(sparse.points);
    return;
  }
  publish({&cloud, &dense_frame, &result, source_points, want_markers ? &associations : nullptr,
           &live});
  const double latency_ms = (ros::WallTime::now() - job.received).toSec() * 1000.0;
  c_.status->update([&](AlignmentStatusValues& s) { s.last_latency_ms = latency_ms; });
  if (settings.dense_is_target) reportSpacing(sparse.points);
  ROS_DEBUG("aligned in %.0f ms (%d runs, sigma %.4f, inliers %.2f), latency %.0f ms",
            result.time_ms, result.runs, result.sigma, result.inlier_fraction, latency_ms);
}

}  // namespace pda_registration
