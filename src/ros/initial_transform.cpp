#include "pda_registration/ros/initial_transform.hpp"

#include <cmath>

#include "pda_registration/core/nearest_rotation.hpp"

namespace pda_registration {

bool initialTransformFromList(const std::vector<double>& v, Eigen::Isometry3d* T,
                              std::string* error) {
  for (double x : v) {
    if (!std::isfinite(x)) {
      *error = "~initial_transform contains NaN or Inf";
      return false;
    }
  }
  *T = Eigen::Isometry3d::Identity();
  if (v.size() == 16) {
    Eigen::Matrix4d m;
    for (int i = 0; i < 16; ++i) m(i / 4, i % 4) = v[i];
    Eigen::Matrix3d rotation;
    if (!nearestRotation(m.topLeftCorner<3, 3>(), &rotation)) {
      *error = "~initial_transform: the 3x3 block is not a rotation";
      return false;
    }
    T->linear() = rotation;
    T->translation() = m.topRightCorner<3, 1>();
  } else if (v.size() == 6) {
    T->linear() = (Eigen::AngleAxisd(v[5], Eigen::Vector3d::UnitZ()) *
                   Eigen::AngleAxisd(v[4], Eigen::Vector3d::UnitY()) *
                   Eigen::AngleAxisd(v[3], Eigen::Vector3d::UnitX()))
                      .toRotationMatrix();
    T->translation() = Eigen::Vector3d(v[0], v[1], v[2]);
  } else if (v.size() == 7) {
    const Eigen::Vector4d q(v[6], v[3], v[4], v[5]);  // w x y z
    if (q.stableNorm() < 1e-6) {
      *error = "~initial_transform: zero quaternion";
      return false;
    }
    // Scaled by its largest component first: the norm of large components (from ~1e154, and
    // even stableNorm's near DBL_MAX) overflows to Inf, and dividing by Inf silently gave the
    // identity instead of the rotation asked for.
    const Eigen::Vector4d unit = (q / q.cwiseAbs().maxCoeff()).normalized();
    T->linear() = Eigen::Quaterniond(unit[0], unit[1], unit[2], unit[3]).toRotationMatrix();
    T->translation() = Eigen::Vector3d(v[0], v[1], v[2]);
  } else {
    *error =
        "~initial_transform needs 16 (4x4 row-major), 6 (x y z roll pitch yaw) or 7 "
        "(x y z qx qy qz qw) numbers, got " +
        std::to_string(v.size());
    return false;
  }
  return true;
}

}  // namespace pda_registration
