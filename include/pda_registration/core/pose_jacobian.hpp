#pragma once
// The Jacobian of a moved point p = R x + t with respect to the pose increment
// delta = (dx, dy, dz, droll, dpitch, dyaw) applied as R <- exp(w) R, t <- t + dt: rotations
// about the target frame's axes at the source origin, the convention of
// geometry_msgs/PoseWithCovariance. Shared by the Gauss-Newton M-step and the covariance.

#include <Eigen/Geometry>

namespace pda_registration {

using PoseJacobian = Eigen::Matrix<double, 3, 6>;
using Matrix6d = Eigen::Matrix<double, 6, 6>;
using Vector6d = Eigen::Matrix<double, 6, 1>;

/// `rotated` = R x (the source point rotated, not translated).
inline PoseJacobian poseJacobian(const Eigen::Vector3d& rotated) {
  PoseJacobian jacobian;
  jacobian.leftCols<3>().setIdentity();
  jacobian.rightCols<3>() << 0.0, rotated.z(), -rotated.y(),  //
      -rotated.z(), 0.0, rotated.x(),                         //
      rotated.y(), -rotated.x(), 0.0;
  return jacobian;
}

/// Applies an increment: R <- exp(w) R, t <- t + dt.
inline Eigen::Isometry3d applyIncrement(const Eigen::Isometry3d& T, const Vector6d& delta) {
  Eigen::Isometry3d out = T;
  const Eigen::Vector3d w = delta.tail<3>();
  const double angle = w.norm();
  if (angle > 0.0) {
    out.linear() = Eigen::AngleAxisd(angle, w / angle).toRotationMatrix() * T.linear();
  }
  out.translation() = T.translation() + delta.head<3>();
  return out;
}

}  // namespace pda_registration
