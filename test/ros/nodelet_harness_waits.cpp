// NodeletHarness's waits. Each polls what the harness has recorded (or tf, or the connection
// counts) until it holds or its timeout passes: no wait is unbounded, so a test fails rather than
// hangs when the nodelet never answers.
#include <algorithm>
#include <string>
#include <vector>

#include "nodelet_harness.hpp"

namespace pda_registration {
namespace testing_support {

namespace {
bool anyContains(const std::vector<std::string>& lines, const std::string& text) {
  return std::any_of(lines.begin(), lines.end(), [&text](const std::string& line) {
    return line.find(text) != std::string::npos;
  });
}
}  // namespace

bool NodeletHarness::waitFor(const std::function<bool()>& condition, double timeout_s) {
  const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(timeout_s);
  while (ros::ok() && ros::WallTime::now() < end) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      if (condition()) return true;
    }
    ros::WallDuration(0.02).sleep();
  }
  std::lock_guard<std::mutex> lock(mutex_);
  return condition();
}

bool NodeletHarness::waitForNextTransform(double timeout_s) {
  return waitForTransformsBeyond(transformCount(), timeout_s);
}

bool NodeletHarness::waitForTransformsBeyond(size_t count, double timeout_s) {
  return waitFor([this, count] { return transforms_.size() > count; }, timeout_s);
}

bool NodeletHarness::waitForWarnContaining(const std::string& text, double timeout_s) {
  return waitFor([this, &text] { return anyContains(warnings_, text); }, timeout_s);
}

bool NodeletHarness::waitForLogContaining(const std::string& text, double timeout_s) {
  return waitFor([this, &text] { return anyContains(logs_, text); }, timeout_s);
}

bool NodeletHarness::waitForOutputConnections(double timeout_s) {
  const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(timeout_s);
  while (ros::ok() && ros::WallTime::now() < end) {
    if (transform_.getNumPublishers() > 0 && diagnostics_.getNumPublishers() > 0) return true;
    ros::WallDuration(0.05).sleep();
  }
  return false;
}

bool NodeletHarness::waitForConnections(double timeout_s) {
  const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(timeout_s);
  while (ros::ok() && ros::WallTime::now() < end) {
    // /rosout counts this test process itself as one publisher: wait for a second one.
    if (dense_.getNumSubscribers() > 0 && sparse_.getNumSubscribers() > 0 &&
        transform_.getNumPublishers() > 0 && rosout_.getNumPublishers() > 1) {
      return true;
    }
    ros::WallDuration(0.05).sleep();
  }
  ROS_ERROR("connections: dense %u, sparse %u subscribers; ~transform %u, /rosout %u publishers",
            dense_.getNumSubscribers(), sparse_.getNumSubscribers(), transform_.getNumPublishers(),
            rosout_.getNumPublishers());
  return false;
}

bool NodeletHarness::waitForTransformStamped(const ros::Time& stamp, double timeout_s,
                                             geometry_msgs::TransformStamped* found) {
  return waitFor(
      [&] {
        for (auto it = transforms_.rbegin(); it != transforms_.rend(); ++it) {
          if (it->header.stamp == stamp) return *found = *it, true;
        }
        return false;
      },
      timeout_s);
}

bool NodeletHarness::waitForMarkersStamped(const ros::Time& stamp, double timeout_s,
                                           visualization_msgs::MarkerArray* found) {
  return waitFor(
      [&] {
        for (auto it = markers_received_.rbegin(); it != markers_received_.rend(); ++it) {
          if (!it->markers.empty() && it->markers.front().header.stamp == stamp) {
            return *found = *it, true;
          }
        }
        return false;
      },
      timeout_s);
}

bool NodeletHarness::waitForMarkersBeyond(size_t count, double timeout_s) {
  return waitFor([this, count] { return markers_received_.size() > count; }, timeout_s);
}

bool NodeletHarness::waitForPosesBeyond(size_t count, double timeout_s) {
  return waitFor([this, count] { return poses_.size() > count; }, timeout_s);
}

bool NodeletHarness::waitForFreshDiagnostics(double timeout_s) {
  const size_t before = diagnosticsCount();
  return waitFor([this, before] { return diagnostics_received_.size() > before; }, timeout_s);
}

bool NodeletHarness::waitForAcceptedToMatchTransforms(double timeout_s, std::string* detail) {
  const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(timeout_s);
  std::string accepted;
  size_t before = 0, after = 0;
  while (ros::ok() && ros::WallTime::now() < end) {
    before = transformCount();
    if (!waitForFreshDiagnostics((end - ros::WallTime::now()).toSec())) break;
    accepted = diagnosticValue("accepted");
    after = transformCount();
    if (before == after && accepted == std::to_string(after)) return true;
  }
  *detail = "diagnostics last said accepted = \"" + accepted + "\" while " +
            std::to_string(before) + ".." + std::to_string(after) + " transforms had arrived";
  return false;
}

bool NodeletHarness::lastTransformOnTf(double timeout_s, Eigen::Isometry3d* last) {
  const std::vector<geometry_msgs::TransformStamped> all = transforms();
  if (all.empty()) return false;
  *last = toEigen(all.back().transform);
  const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(timeout_s);
  while (ros::ok() && ros::WallTime::now() < end) {
    try {
      const Eigen::Isometry3d edge = lookup("dense_map", "sparse_map_aligned", 0.1);
      if ((edge.translation() - last->translation()).norm() < 1e-9) return true;
    } catch (const tf2::TransformException&) {
      // the edge is not on tf yet: keep waiting, within timeout_s
    }
    ros::WallDuration(0.05).sleep();
  }
  return false;
}

}  // namespace testing_support
}  // namespace pda_registration
