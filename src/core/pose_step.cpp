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

StepSuccession succession(const PoseStep::Vector& previous, const PoseStep::Vector& step) {
  const double size = step.norm(), previous_size = previous.norm();
  StepSuccession s;
  s.cosine = step.dot(previous) / (size * previous_size);
  s.ratio = size / previous_size;
  return s;
}

}  // namespace pda_registration
