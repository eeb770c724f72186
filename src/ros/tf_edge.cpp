#include "pda_registration/ros/tf_edge.hpp"

#include "pda_registration/ros/seed_lookup.hpp"

namespace pda_registration {

std::string edgeChildFrame(const std::string& sparse_frame, const std::string& child_setting) {
  return child_setting.empty() ? sparse_frame + "_aligned" : child_setting;
}

bool expressOnTfEdge(const tf2_ros::Buffer& buffer, const Eigen::Isometry3d& T_dense_sparse,
                     const std::string& dense_frame, const std::string& sparse_frame,
                     const std::string& parent_setting, const std::string& child_setting,
                     const ros::Time& stamp, const ros::Duration& timeout, TfEdge* edge,
                     std::string* error) {
  const std::string aligned_sparse = sparse_frame + "_aligned";
  edge->parent = parent_setting.empty() ? dense_frame : parent_setting;
  edge->child = edgeChildFrame(sparse_frame, child_setting);
  edge->T_parent_child = T_dense_sparse;
  edge->at_stamp = true;
  bool at_stamp = true;
  if (edge->parent != dense_frame) {
    Eigen::Isometry3d T_parent_dense;
    if (!lookupAtStampOrLatest(buffer, edge->parent, dense_frame, stamp, timeout, &T_parent_dense,
                               &at_stamp, error)) {
      return false;
    }
    edge->T_parent_child = T_parent_dense * edge->T_parent_child;
    edge->at_stamp = edge->at_stamp && at_stamp;
  }
  if (edge->child != sparse_frame && edge->child != aligned_sparse) {
    // At the cloud's stamp: odometry's sparse <- child then, not now (the robot has moved since).
    Eigen::Isometry3d T_sparse_child;
    if (!lookupAtStampOrLatest(buffer, sparse_frame, edge->child, stamp, timeout, &T_sparse_child,
                               &at_stamp, error)) {
      return false;
    }
    edge->T_parent_child = edge->T_parent_child * T_sparse_child;
    edge->at_stamp = edge->at_stamp && at_stamp;
  }
  return true;
}

}  // namespace pda_registration
