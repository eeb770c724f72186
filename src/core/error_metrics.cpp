#include "pda_registration/core/error_metrics.hpp"

#include <cmath>

namespace pda_registration {

PoseError poseError(const PointList& source, const Eigen::Isometry3d& T_estimate,
                    const Eigen::Isometry3d& T_ground_truth) {
  PoseError error;
  double sum = 0.0;
  size_t count = 0;
  for (const Point& x : source) {
    if (!x.allFinite()) continue;
    sum += (T_estimate * x - T_ground_truth * x).norm();
    ++count;
  }
  error.mean_distance = count == 0 ? 0.0 : sum / static_cast<double>(count);
  const Eigen::AngleAxisd rotation(T_estimate.linear() * T_ground_truth.linear().transpose());
  error.rotation_deg = std::abs(rotation.angle()) * 180.0 / M_PI;
  error.translation = (T_estimate.translation() - T_ground_truth.translation()).norm();
  return error;
}

}  // namespace pda_registration
