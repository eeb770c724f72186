#include "pda_registration/ros/map_alignment_nodelet.hpp"

#include <malloc.h>
#include <tf2_eigen/tf2_eigen.h>

#include <chrono>
#include <map>
#include <pluginlib/class_list_macros.hpp>
#include <sstream>

#include "pda_registration/core/alignment_gate.hpp"
#include "pda_registration/core/pose_covariance.hpp"
#include "pda_registration/core/process_memory.hpp"
#include "pda_registration/ros/point_cloud_conversion.hpp"

namespace pda_registration {
namespace {

// A WARN per kind of problem at most every few seconds, so a bad stream cannot flood the log
// while different problems still each get their line.
bool shouldLog(const std::string& kind) {
  static std::mutex mutex;
  static std::map<std::string, ros::WallTime> last_logged;
  std::lock_guard<std::mutex> lock(mutex);
  // Kinds carry frame names: a stream of ever-new frames must not grow this without bound.
  if (last_logged.size() > 256) last_logged.clear();
  const ros::WallTime now = ros::WallTime::now();
  auto it = last_logged.find(kind);
  if (it != last_logged.end() && (now - it->second).toSec() < 5.0) return false;
  last_logged[kind] = now;
  return true;
}

std::string describe(const sensor_msgs::PointCloud2& cloud, const std::string& topic) {
  std::ostringstream out;
  out << topic << " (frame '" << cloud.header.frame_id << "', stamp " << cloud.header.stamp << ", "
      << cloud.width << "x" << cloud.height << ")";
  return out.str();
}

}  // namespace

MapAlignmentNodelet::~MapAlignmentNodelet() {
  queue_.stop();
  if (worker_.joinable()) worker_.join();
}

void MapAlignmentNodelet::onInit() {
  ros::NodeHandle& node = getNodeHandle();
  ros::NodeHandle& private_node = getPrivateNodeHandle();

  // Named after the nodelet, not the manager it shares: "<nodelet name>: alignment".
  diagnostics_ = std::make_unique<diagnostic_updater::Updater>(node, private_node, getName());
  diagnostics_->setHardwareID(getName());
  diagnostics_->add("alignment", this, &MapAlignmentNodelet::diagnose);
  // force_update on our own wall-clock timer: Updater::update() compares against ROS time and
  // would fall silent for the length of a bag after a loop jumps simulated time back.
  diagnostics_timer_ = node.createWallTimer(
      ros::WallDuration(1.0), [this](const ros::WallTimerEvent&) { diagnostics_->force_update(); });

  settings_ok_ = readNodeSettings(private_node, &settings_, &settings_error_);
  if (!settings_ok_) {
    // A bad static parameter disables this nodelet, never the manager it shares.
    NODELET_ERROR("not started: %s", settings_error_.c_str());
    return;
  }

  tf_buffer_ = std::make_unique<tf2_ros::Buffer>();
  tf_listener_ = std::make_unique<tf2_ros::TransformListener>(*tf_buffer_, node);
  publisher_ = std::make_unique<AlignmentPublisher>(private_node);
  reconfigure_server_ = std::make_unique<dynamic_reconfigure::Server<PdaRegistrationConfig>>(
      reconfigure_mutex_, private_node);
  reconfigure_server_->setCallback(boost::bind(&MapAlignmentNodelet::reconfigure, this,
                                               boost::placeholders::_1, boost::placeholders::_2));

  worker_ = std::thread(&MapAlignmentNodelet::workerLoop, this);
  dense_subscriber_ = node.subscribe("dense_cloud", 2, &MapAlignmentNodelet::denseCallback, this);
  sparse_subscriber_ =
      node.subscribe("sparse_cloud", 5, &MapAlignmentNodelet::sparseCallback, this);
  if (settings_.publish_tf && settings_.tf_publish_rate > 0.0) {
    tf_timer_ = node.createTimer(ros::Duration(1.0 / settings_.tf_publish_rate),
                                 &MapAlignmentNodelet::republishTf, this);
  }
  NODELET_INFO("aligning %s (target: %s cloud) with seeds from tf%s",
               sparse_subscriber_.getTopic().c_str(),
               settings_.dense_is_target ? "dense" : "sparse",
               settings_.has_initial_transform ? " or ~initial_transform" : "");
}

void MapAlignmentNodelet::reconfigure(PdaRegistrationConfig& config, uint32_t) {
  const LiveParameters live = liveParametersFrom(config);
  const std::string problem = validateParameters(live.registration);
  if (!problem.empty()) {
    // The .cfg limits make this rare (e.g. closed_form with surface_anisotropy > 1): keep the
    // previous parameters, say why, and hand them back, so that what dynamic_reconfigure
    // publishes (rqt_reconfigure, dynparam) is what runs.
    NODELET_WARN("reconfigure refused: %s; keeping the previous parameters", problem.c_str());
    if (have_accepted_config_) config = accepted_config_;
    return;
  }
  accepted_config_ = config;
  have_accepted_config_ = true;
  std::lock_guard<std::mutex> lock(live_mutex_);
  live_ = live;
}

void MapAlignmentNodelet::denseCallback(const sensor_msgs::PointCloud2ConstPtr& cloud) {
  {
    std::lock_guard<std::mutex> lock(status_mutex_);
    ++status_.dense_received;
  }
  queue_.putDense(cloud);  // maps are slow; a replaced pending map needs no counting
}

void MapAlignmentNodelet::sparseCallback(const sensor_msgs::PointCloud2ConstPtr& cloud) {
  double min_interval;
  {
    std::lock_guard<std::mutex> lock(live_mutex_);
    min_interval = live_.min_interval;
  }
  const ros::Time now = ros::Time::now();
  std::lock_guard<std::mutex> lock(status_mutex_);
  ++status_.sparse_received;
  if (now < last_sparse_accepted_) last_sparse_accepted_ = ros::Time();  // clock jumped back
  if (min_interval > 0.0 && !last_sparse_accepted_.isZero() &&
      (now - last_sparse_accepted_).toSec() < min_interval) {
    ++status_.dropped_throttled;
    return;
  }
  last_sparse_accepted_ = now;
  if (queue_.putSparse({cloud, ros::WallTime::now()})) ++status_.dropped_stale;
}

void MapAlignmentNodelet::workerLoop() {
  sensor_msgs::PointCloud2ConstPtr dense;
  SparseJob sparse;
  bool has_dense = false, has_sparse = false;
  while (queue_.waitAndTake(&dense, &has_dense, &sparse, &has_sparse)) {
    try {
      if (has_dense) updateDenseCloud(dense);
      if (has_sparse) alignSparseCloud(sparse);
    } catch (const std::exception& error) {
      reportProblem("internal", std::string("internal error: ") + error.what(), false);
    }
    // Let go of the messages now rather than when the next ones arrive, and hand the freed
    // megabytes back to the system: glibc otherwise keeps them in its per-thread arenas, and a
    // stream of large maps (freed by one thread, allocated by another) ratchets the manager's
    // RSS up by tens of MB a minute (measured by the stress rostest; flat with the trim).
    dense.reset();
    sparse = SparseJob();
    malloc_trim(0);
  }
}

bool MapAlignmentNodelet::checkFrame(const sensor_msgs::PointCloud2& cloud,
                                     const std::string& expected, const char* kind) {
  if (cloud.header.frame_id.empty()) {
    reportProblem("frame", std::string(kind) + " cloud has an empty frame_id", true);
    return false;
  }
  if (!expected.empty() && cloud.header.frame_id != expected) {
    reportProblem("frame",
                  std::string(kind) + " cloud is in frame '" + cloud.header.frame_id +
                      "' but ~expected_" + kind + "_frame is '" + expected + "'",
                  true);
    return false;
  }
  return true;
}

void MapAlignmentNodelet::updateDenseCloud(const sensor_msgs::PointCloud2ConstPtr& cloud) {
  if (!checkFrame(*cloud, settings_.expected_dense_frame, "dense")) return;
  const uint64_t fingerprint = cloudFingerprint(*cloud);
  if (have_dense_ && fingerprint == dense_fingerprint_) {
    std::lock_guard<std::mutex> lock(status_mutex_);
    ++status_.dense_unchanged;
    status_.dense_arrival = ros::WallTime::now();  // the map is alive, just not new
    return;
  }
  CloudConversion converted = fromPointCloud2(*cloud);
  if (!converted.ok()) {
    reportProblem("dense " + converted.error.substr(0, 12),
                  "dense cloud " + describe(*cloud, dense_subscriber_.getTopic()) +
                      " refused: " + converted.error + "; keeping the previous map",
                  true);
    return;
  }
  const auto start = std::chrono::steady_clock::now();
  if (settings_.dense_is_target) {
    {
      std::lock_guard<std::mutex> lock(live_mutex_);
      registration_.setParameters(live_.registration);
    }
    if (!registration_.setTarget(std::move(converted.points))) {
      // The previous map is gone with it: forget it, so a re-publication is indexed afresh
      // rather than skipped as unchanged.
      have_dense_ = false;
      dense_fingerprint_ = 0;
      reportProblem("dense index",
                    "dense cloud " + describe(*cloud, dense_subscriber_.getTopic()) +
                        " could not be indexed; no map until the next one",
                    true);
      return;
    }
  } else {
    dense_points_ = std::move(converted.points);
  }
  dense_frame_ = cloud->header.frame_id;
  have_dense_ = true;
  dense_fingerprint_ = fingerprint;
  {
    std::lock_guard<std::mutex> lock(status_mutex_);
    status_.dense_points =
        settings_.dense_is_target ? registration_.targetCloudSize() : dense_points_.size();
    status_.dense_arrival = ros::WallTime::now();
  }
  NODELET_INFO(
      "dense map from %s: %zu points (%zu non-finite dropped), ready in %.0f ms",
      dense_subscriber_.getTopic().c_str(),
      settings_.dense_is_target ? registration_.targetCloudSize() : dense_points_.size(),
      converted.non_finite,
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
}

void MapAlignmentNodelet::alignSparseCloud(const SparseJob& job) {
  const sensor_msgs::PointCloud2& cloud = *job.cloud;
  if (!checkFrame(cloud, settings_.expected_sparse_frame, "sparse")) return;
  CloudConversion sparse = fromPointCloud2(cloud);
  if (!sparse.ok()) {
    reportProblem("sparse " + sparse.error.substr(0, 12),
                  "sparse cloud " + describe(cloud, sparse_subscriber_.getTopic()) +
                      " refused: " + sparse.error,
                  true);
    return;
  }
  if (!have_dense_) {
    reportProblem(
        "no dense",
        "no dense cloud received yet on " + dense_subscriber_.getTopic() + "; sparse cloud skipped",
        false);
    return;
  }
  LiveParameters live;
  {
    std::lock_guard<std::mutex> lock(live_mutex_);
    live = live_;
  }
  const std::string& sparse_frame = cloud.header.frame_id;
  const Seed seed =
      lookupSeed(*tf_buffer_, dense_frame_, sparse_frame, cloud.header.stamp,
                 ros::Duration(settings_.tf_timeout),
                 settings_.has_initial_transform ? &settings_.initial_transform : nullptr);
  if (seed.source == SeedSource::kNone) {
    {
      std::lock_guard<std::mutex> lock(status_mutex_);
      ++status_.missing_seed;
    }
    reportProblem("no seed " + sparse_frame,
                  "no seed for " + describe(cloud, sparse_subscriber_.getTopic()) +
                      ": tf has no transform from '" + sparse_frame + "' to '" + dense_frame_ +
                      "' (" + seed.detail + ") and ~initial_transform is not set",
                  true);
    return;
  }
  {
    std::lock_guard<std::mutex> lock(status_mutex_);
    if (seed.source != status_.last_seed) {
      NODELET_INFO("seeding from %s", toString(seed.source));
    }
    status_.last_seed = seed.source;
  }

  // The core aligns source to target; the output is always dense <- sparse.
  registration_.setParameters(live.registration);
  const bool want_markers = publisher_->hasAssociationSubscribers() && live.max_markers > 0;
  Associations associations;
  RegistrationResult result;
  Eigen::Isometry3d seed_target_source;
  const PointList* source_points;
  if (settings_.dense_is_target) {
    seed_target_source = seed.T_dense_sparse;
    source_points = &sparse.points;
  } else {
    registration_.setTarget(sparse.points);
    seed_target_source = seed.T_dense_sparse.inverse();
    source_points = &dense_points_;
  }
  result = registration_.align(*source_points, seed_target_source,
                               want_markers ? &associations : nullptr);
  const Verdict verdict = judgeAlignment(result, seed_target_source, live.acceptance);
  {
    std::lock_guard<std::mutex> lock(status_mutex_);
    ++status_.aligned;
    status_.have_result = true;
    status_.last_result = result;
    status_.last_accepted = verdict.accepted;
    status_.indexed_points = result.target_points_used;
    status_.target_cropped = result.target_cropped;
    if (verdict.accepted)
      ++status_.accepted;
    else
      ++status_.rejected;
  }
  if (!verdict.accepted) {
    reportProblem("rejected",
                  "alignment rejected, keeping the last good estimate: " + verdict.reason, false);
    return;
  }

  AlignmentOutput output;
  output.stamp = cloud.header.stamp;
  output.dense_frame = dense_frame_;
  output.sparse_frame = sparse_frame;
  output.T_dense_sparse =
      settings_.dense_is_target ? result.T_target_source : result.T_target_source.inverse();
  output.covariance = settings_.dense_is_target
                          ? result.covariance
                          : invertedPoseCovariance(result.T_target_source, result.covariance);
  output.target_frame = settings_.dense_is_target ? dense_frame_ : sparse_frame;
  PointList aligned;
  if (publisher_->hasAlignedCloudSubscribers()) {
    aligned.reserve(source_points->size());
    for (const Point& p : *source_points) aligned.push_back(result.T_target_source * p);
    output.aligned = &aligned;
  }
  output.associations = want_markers ? &associations : nullptr;
  output.max_markers = live.max_markers;
  output.marker_line_width = settings_.marker_line_width;
  publisher_->publish(output);
  if (settings_.publish_tf) {
    TfEdge edge;
    std::string error;
    if (expressOnTfEdge(*tf_buffer_, output.T_dense_sparse, dense_frame_, sparse_frame,
                        settings_.tf_parent_frame, settings_.tf_child_frame, cloud.header.stamp,
                        ros::Duration(settings_.tf_timeout), &edge, &error)) {
      broadcastEdge(&edge, cloud.header.stamp);
    } else {
      reportProblem(
          "tf edge",
          "cannot express the estimate as " + edge.parent + " -> " + edge.child + ": " + error,
          false);
    }
  }
  const double latency_ms = (ros::WallTime::now() - job.received).toSec() * 1000.0;
  {
    std::lock_guard<std::mutex> lock(status_mutex_);
    status_.last_latency_ms = latency_ms;
  }
  NODELET_DEBUG("aligned in %.0f ms (%d runs, sigma %.4f, inliers %.2f), latency %.0f ms",
                result.time_ms, result.runs, result.sigma, result.inlier_fraction, latency_ms);
}

void MapAlignmentNodelet::broadcastEdge(const TfEdge* fresh, const ros::Time& requested_stamp) {
  TfEdge edge;
  ros::Time stamp = requested_stamp;
  {
    // The edge and its stamp are taken together, so a re-broadcast never sends an older edge at
    // a newer stamp than a fresh one.
    std::lock_guard<std::mutex> lock(edge_mutex_);
    if (fresh) {
      edge_ = *fresh;
      have_edge_ = true;
    } else if (!have_edge_) {
      return;
    }
    edge = edge_;
    // tf listeners drop data older than what they hold (TF_OLD_DATA) or at a stamp they already
    // have (TF_REPEATED_DATA), each with a warning: stamps on our edge only move forward. A late
    // cloud's estimate goes out stamped now; a re-broadcast while simulated time stands still
    // is skipped; a clock that jumped back (a looping bag) starts the edge afresh.
    const ros::Time now = ros::Time::now();
    if (now + ros::Duration(1.0) < last_tf_stamp_) last_tf_stamp_ = ros::Time();
    if (stamp <= last_tf_stamp_) {
      if (!fresh) return;
      stamp = std::max(now, last_tf_stamp_ + ros::Duration(0, 1000));
    }
    last_tf_stamp_ = stamp;
  }
  geometry_msgs::TransformStamped transform = tf2::eigenToTransform(edge.T_parent_child);
  transform.header.stamp = stamp;
  transform.header.frame_id = edge.parent;
  transform.child_frame_id = edge.child;
  publisher_->broadcast(transform);
}

void MapAlignmentNodelet::republishTf(const ros::TimerEvent&) {
  const ros::Time now = ros::Time::now();
  if (!now.isZero()) broadcastEdge(nullptr, now);
}

void MapAlignmentNodelet::reportProblem(const std::string& kind, const std::string& problem,
                                        bool input_error) {
  {
    std::lock_guard<std::mutex> lock(status_mutex_);
    if (input_error) ++status_.input_errors;
    status_.last_problem = problem;
    status_.last_problem_time = ros::Time::now();
    status_.last_accepted = false;
  }
  if (shouldLog(kind)) NODELET_WARN("%s", problem.c_str());
}

void MapAlignmentNodelet::diagnose(diagnostic_updater::DiagnosticStatusWrapper& status) {
  if (!settings_ok_) {
    status.summary(diagnostic_msgs::DiagnosticStatus::ERROR, "not started: " + settings_error_);
    return;
  }
  std::lock_guard<std::mutex> lock(status_mutex_);
  const Status& s = status_;
  // A map whose publisher is gone still serves (a prior map need not be re-sent), but an
  // operator should know it will not be updated.
  const bool dense_gone = s.dense_points > 0 && dense_subscriber_.getNumPublishers() == 0;
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
  status.add("inlier fraction", r.inlier_fraction);
  status.add("runs", r.runs);
  status.add("alignment time [ms]", r.time_ms);
  status.add("latency [ms]", s.last_latency_ms);
  status.add("seed source", toString(s.last_seed));
  status.add("dense clouds received", s.dense_received);
  status.add("dense clouds unchanged (not re-indexed)", s.dense_unchanged);
  status.add("dense map points", s.dense_points);
  status.add("dense map age [s]",
             s.dense_arrival.isZero() ? -1.0 : (ros::WallTime::now() - s.dense_arrival).toSec());
  status.add("dense map publishers", dense_subscriber_.getNumPublishers());
  status.add("indexed target points", s.indexed_points);
  status.add("target cropped", s.target_cropped);
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

PLUGINLIB_EXPORT_CLASS(pda_registration::MapAlignmentNodelet, nodelet::Nodelet)
