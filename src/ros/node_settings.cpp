#include "pda_registration/ros/node_settings.hpp"

#include <cmath>
#include <vector>

namespace pda_registration {
namespace {

bool transformFromList(const std::vector<double>& v, Eigen::Isometry3d* T, std::string* error) {
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
    const Eigen::Matrix3d r = m.topLeftCorner<3, 3>();
    if ((r.transpose() * r - Eigen::Matrix3d::Identity()).norm() > 1e-3 || r.determinant() <= 0) {
      *error = "~initial_transform: the 3x3 block is not a rotation";
      return false;
    }
    T->linear() = Eigen::Quaterniond(r).normalized().toRotationMatrix();
    T->translation() = m.topRightCorner<3, 1>();
  } else if (v.size() == 6) {
    T->linear() = (Eigen::AngleAxisd(v[5], Eigen::Vector3d::UnitZ()) *
                   Eigen::AngleAxisd(v[4], Eigen::Vector3d::UnitY()) *
                   Eigen::AngleAxisd(v[3], Eigen::Vector3d::UnitX()))
                      .toRotationMatrix();
    T->translation() = Eigen::Vector3d(v[0], v[1], v[2]);
  } else if (v.size() == 7) {
    const Eigen::Quaterniond q(v[6], v[3], v[4], v[5]);
    if (q.norm() < 1e-6) {
      *error = "~initial_transform: zero quaternion";
      return false;
    }
    T->linear() = q.normalized().toRotationMatrix();
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

}  // namespace

bool readNodeSettings(const ros::NodeHandle& nh, NodeSettings* s, std::string* error) {
  const std::string target = nh.param<std::string>("target_cloud", "dense");
  if (target != "dense" && target != "sparse") {
    *error = "~target_cloud must be 'dense' or 'sparse', got '" + target + "'";
    return false;
  }
  s->dense_is_target = target == "dense";
  s->tf_timeout = nh.param("tf_timeout", s->tf_timeout);
  s->publish_tf = nh.param("publish_tf", s->publish_tf);
  s->tf_parent_frame = nh.param<std::string>("tf_parent_frame", "");
  s->tf_child_frame = nh.param<std::string>("tf_child_frame", "");
  s->tf_publish_rate = nh.param("tf_publish_rate", s->tf_publish_rate);
  s->expected_dense_frame = nh.param<std::string>("expected_dense_frame", "");
  s->expected_sparse_frame = nh.param<std::string>("expected_sparse_frame", "");
  s->marker_line_width = nh.param("marker_line_width", s->marker_line_width);
  if (!(s->tf_timeout >= 0.0 && s->tf_timeout < 60.0)) {
    *error = "~tf_timeout must be in [0, 60) s";
    return false;
  }
  if (!(s->tf_publish_rate >= 0.0 && s->tf_publish_rate <= 1000.0)) {
    *error = "~tf_publish_rate must be in [0, 1000] Hz";
    return false;
  }
  if (nh.hasParam("initial_transform")) {
    std::vector<double> values;
    if (!nh.getParam("initial_transform", values)) {
      *error = "~initial_transform must be a list of numbers";
      return false;
    }
    if (!transformFromList(values, &s->initial_transform, error)) return false;
    s->has_initial_transform = true;
  }
  return true;
}

}  // namespace pda_registration
