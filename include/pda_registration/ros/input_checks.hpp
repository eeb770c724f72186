#pragma once
// Small checks and descriptions of incoming clouds, shared by the nodelet's dense and sparse
// paths.

#include <sensor_msgs/PointCloud2.h>

#include <sstream>
#include <string>

namespace pda_registration {

/// "<topic> (frame 'f', stamp s, WxH)", for log lines and diagnostics.
inline std::string describeCloud(const sensor_msgs::PointCloud2& cloud, const std::string& topic) {
  std::ostringstream out;
  out << topic << " (frame '" << cloud.header.frame_id << "', stamp " << cloud.header.stamp << ", "
      << cloud.width << "x" << cloud.height << ")";
  return out.str();
}

/// Empty when the cloud's frame is acceptable (non-empty, and `expected` unless that is empty);
/// otherwise why not. `kind` is "dense" or "sparse".
inline std::string frameProblem(const sensor_msgs::PointCloud2& cloud, const std::string& expected,
                                const std::string& kind) {
  if (cloud.header.frame_id.empty()) return kind + " cloud has an empty frame_id";
  if (!expected.empty() && cloud.header.frame_id != expected) {
    return kind + " cloud is in frame '" + cloud.header.frame_id + "' but ~expected_" + kind +
           "_frame is '" + expected + "'";
  }
  return std::string();
}

}  // namespace pda_registration
