#pragma once
// The core's cloud type: plain 3-D points. Conversions from PCL and ROS messages live in the
// tools and ROS layers, so the core compiles without PCL's point-type templates.

#include <Eigen/Core>
#include <vector>

namespace pda_registration {

using Point = Eigen::Vector3d;
using PointList = std::vector<Point>;

}  // namespace pda_registration
