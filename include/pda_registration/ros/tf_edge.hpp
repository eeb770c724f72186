#pragma once
// The estimate as the tf edge the node is configured to broadcast. By default dense frame ->
// sparse frame + "_aligned"; an own edge dense -> sparse; or a correction edge such as amcl's
// map -> odom: parent <- child = (parent <- dense)(dense <- sparse)(sparse <- child), the outer
// two looked up at the cloud's stamp. The edge then holds the correction, not the robot's pose
// at that stamp: re-sent unchanged, odometry keeps moving the robot under it.

#include <tf2_ros/buffer.h>

#include <Eigen/Geometry>
#include <string>

namespace pda_registration {

struct TfEdge {
  std::string parent, child;
  Eigen::Isometry3d T_parent_child = Eigen::Isometry3d::Identity();
  /// False when a transform composed into the edge was not in tf at the cloud's stamp and the
  /// latest one stood in: the edge is then off by whatever moved between the two.
  bool at_stamp = true;
};

/// The child frame of the node's edge: `child_setting`, or "<sparse frame>_aligned" when empty.
std::string edgeChildFrame(const std::string& sparse_frame, const std::string& child_setting);

/// Empty `parent_setting` / `child_setting` mean the defaults above. False, with tf's error in
/// *error, when tf cannot relate the parent to the dense frame or the sparse frame to the child
/// (at the stamp, waiting up to `timeout`, else with the latest transforms).
bool expressOnTfEdge(const tf2_ros::Buffer& buffer, const Eigen::Isometry3d& T_dense_sparse,
                     const std::string& dense_frame, const std::string& sparse_frame,
                     const std::string& parent_setting, const std::string& child_setting,
                     const ros::Time& stamp, const ros::Duration& timeout, TfEdge* edge,
                     std::string* error);

}  // namespace pda_registration
