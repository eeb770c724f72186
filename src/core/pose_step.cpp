#include "pda_registration/core/pose_step.hpp"

#include <cmath>

namespace pda_registration {

PoseStep PoseStep::over(const PointList& cloud) {
  if (cloud.empty()) return PoseStep(Point::Zero(), 1.0);
  Point centroid = Point::Zero();
  for (const Point& x : cloud) centroid += x;
  centroid /= static_cast<double>(cloud.size());
  double spread = 0.0;
  for (const Point& x : cloud) spread += (x - centroid).squaredNorm();
  return PoseStep(centroid, std::sqrt(spread / static_cast<double>(cloud.size())));
}

PoseStep::Vector PoseStep::between(const Eigen::Isometry3d& before,
                                   const Eigen::Isometry3d& after) const {
  const Eigen::AngleAxisd rotation(after.linear() * before.linear().transpose());
  Vector step;
  step.head<3>() = rotation.angle() * rotation.axis() * length_;
  step.tail<3>() = after * centroid_ - before * centroid_;
  return step;
}

}  // namespace pda_registration
