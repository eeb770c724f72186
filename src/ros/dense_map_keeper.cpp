#include "pda_registration/ros/dense_map_keeper.hpp"

#include <chrono>
#include <cstdio>

#include "pda_registration/ros/input_checks.hpp"
#include "pda_registration/ros/point_cloud_conversion.hpp"

namespace pda_registration {

void DenseMapKeeper::update(const sensor_msgs::PointCloud2ConstPtr& cloud,
                            const RegistrationParameters& parameters) {
  const std::string frame_problem = frameProblem(*cloud, expected_frame_, "dense");
  if (!frame_problem.empty()) {
    log_.problem("frame", frame_problem, true);
    return;
  }
  const uint64_t fingerprint = cloudFingerprint(*cloud);
  if (have_dense_ && fingerprint == fingerprint_) {
    status_->update([](AlignmentStatusValues& s) {
      ++s.dense_unchanged;
      s.dense_arrival = ros::WallTime::now();  // the map is alive, just not new
    });
    return;
  }
  CloudConversion converted = fromPointCloud2(*cloud);
  if (!converted.ok()) {
    log_.problem("dense " + converted.error.substr(0, 12),
                 "dense cloud " + describeCloud(*cloud, topic_) + " refused: " + converted.error +
                     "; keeping the previous map",
                 true);
    return;
  }
  const auto start = std::chrono::steady_clock::now();
  if (dense_is_target_) {
    registration_.setParameters(parameters);
    if (!registration_.setTarget(std::move(converted.points))) {
      // The previous map is gone with it: forget it, so a re-publication is indexed afresh
      // rather than skipped as unchanged.
      have_dense_ = false;
      fingerprint_ = 0;
      log_.problem("dense index",
                   "dense cloud " + describeCloud(*cloud, topic_) +
                       " could not be indexed; no map until the next one",
                   true);
      return;
    }
  } else {
    dense_points_ = std::move(converted.points);
  }
  dense_frame_ = cloud->header.frame_id;
  have_dense_ = true;
  fingerprint_ = fingerprint;
  const size_t points = dense_is_target_ ? registration_.targetCloudSize() : dense_points_.size();
  status_->update([&](AlignmentStatusValues& s) {
    s.dense_points = points;
    s.dense_arrival = ros::WallTime::now();
  });
  const double ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  char line[256];
  std::snprintf(line, sizeof(line),
                "dense map from %s: %zu points (%zu non-finite dropped), ready in %.0f ms",
                topic_.c_str(), points, converted.non_finite, ms);
  log_.info(line);
}

}  // namespace pda_registration
