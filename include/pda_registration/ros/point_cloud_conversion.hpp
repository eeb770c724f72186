#pragma once
// sensor_msgs/PointCloud2 <-> the core's point list, without PCL: every field and size is checked
// first, so a malformed message (truncated data, missing x/y/z, odd types, wrong endianness)
// gives a reason instead of a read past the buffer.

#include <sensor_msgs/PointCloud2.h>

#include <cstdint>
#include <string>

#include "pda_registration/core/point_list.hpp"

namespace pda_registration {

struct CloudConversion {
  PointList points;       ///< finite points only
  size_t non_finite = 0;  ///< points dropped for a NaN/Inf coordinate
  std::string error;      ///< empty when the message could be read
  bool ok() const { return error.empty(); }
};

/// Reads x, y, z (FLOAT32 or FLOAT64) of every point. Fails (error set) on an empty cloud, a
/// malformed layout, or a cloud without a single finite point.
CloudConversion fromPointCloud2(const sensor_msgs::PointCloud2& message);

/// A 64-bit fingerprint of the cloud's frame, layout and bytes (not its stamp): a map that is
/// re-published unchanged (a latched or periodic map topic) is recognised and not re-indexed.
uint64_t cloudFingerprint(const sensor_msgs::PointCloud2& message);

/// A dense, unorganised FLOAT32 x/y/z cloud.
sensor_msgs::PointCloud2 toPointCloud2(const PointList& points, const std_msgs::Header& header);

}  // namespace pda_registration
