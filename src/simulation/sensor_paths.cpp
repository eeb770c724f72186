#include "pda_registration/simulation/sensor_paths.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace pda_registration {
namespace simulation {
namespace {
constexpr double kDegrees = M_PI / 180.0;
}  // namespace

LoopPoint walkwayPoint(const OfficeScene& office, double fraction) {
  const Eigen::Vector2d low = office.office.min() + Eigen::Vector2d::Constant(office.walkway_inset);
  const Eigen::Vector2d high =
      office.office.max() - Eigen::Vector2d::Constant(office.walkway_inset);
  const std::array<Eigen::Vector2d, 4> corners = {low, Eigen::Vector2d(high.x(), low.y()), high,
                                                  Eigen::Vector2d(low.x(), high.y())};
  const Eigen::Vector2d size = high - low;
  const double perimeter = 2.0 * (size.x() + size.y());
  double remaining = (fraction - std::floor(fraction)) * perimeter;
  for (int side = 0; side < 4; ++side) {
    const Eigen::Vector2d from = corners[side], to = corners[(side + 1) % 4];
    const double side_length = (to - from).norm();
    if (remaining <= side_length || side == 3) {
      const Eigen::Vector2d direction = (to - from) / side_length;
      return LoopPoint{from + std::min(remaining, side_length) * direction,
                       std::atan2(direction.y(), direction.x())};
    }
    remaining -= side_length;
  }
  return LoopPoint{};  // not reached: the last side takes whatever remains
}

Eigen::Isometry3d sensorPose(const Eigen::Vector3d& position, double yaw, double pitch) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = (Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) *
                   Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()))
                      .toRotationMatrix();
  pose.translation() = position;
  return pose;
}

std::vector<Eigen::Isometry3d> kinectTrajectory(const OfficeScene& office, int frames,
                                                double begin, double end) {
  // Right of the travel direction is the outer wall on a counter-clockwise loop.
  const std::array<double, 3> yaw_offsets = {-65.0 * kDegrees, 65.0 * kDegrees, 0.0};
  const std::array<double, 3> pitches = {20.0 * kDegrees, 15.0 * kDegrees, 25.0 * kDegrees};
  std::vector<Eigen::Isometry3d> poses;
  for (int i = 0; i < frames; ++i) {
    const LoopPoint point = walkwayPoint(office, begin + (end - begin) * (i + 0.5) / frames);
    poses.push_back(sensorPose(Eigen::Vector3d(point.position.x(), point.position.y(), 1.3),
                               point.heading + yaw_offsets[i % 3], pitches[i % 3]));
  }
  return poses;
}

std::vector<Eigen::Isometry3d> velodynePoses(const OfficeScene& office, int poses) {
  std::vector<Eigen::Isometry3d> result;
  for (int i = 0; i < poses; ++i) {
    const LoopPoint point = walkwayPoint(office, (i + 0.3) / poses);
    result.push_back(sensorPose(Eigen::Vector3d(point.position.x(), point.position.y(), 0.8),
                                point.heading, 0.0));
  }
  return result;
}

}  // namespace simulation
}  // namespace pda_registration
