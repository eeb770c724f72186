#pragma once
// Everything an accepted alignment publishes: ~transform, ~pose (with covariance), ~aligned_cloud,
// ~associations (only while subscribed) and the tf edge. Thread-safe to call from the worker.

#include <geometry_msgs/TransformStamped.h>
#include <ros/node_handle.h>
#include <ros/publisher.h>
#include <tf2_ros/transform_broadcaster.h>

#include <Eigen/Geometry>
#include <string>

#include "pda_registration/core/associations.hpp"
#include "pda_registration/core/point_list.hpp"

namespace pda_registration {

struct AlignmentOutput {
  ros::Time stamp;
  std::string dense_frame, sparse_frame;
  Eigen::Isometry3d T_dense_sparse = Eigen::Isometry3d::Identity();
  Eigen::Matrix<double, 6, 6> covariance = Eigen::Matrix<double, 6, 6>::Zero();  ///< dense frame
  std::string target_frame;            ///< the registration target's frame
  const PointList* aligned = nullptr;  ///< registration source moved into target_frame
  const Associations* associations = nullptr;
  size_t max_markers = 0;
  double marker_line_width = 0.01;
};

class AlignmentPublisher {
 public:
  explicit AlignmentPublisher(ros::NodeHandle& private_node);

  /// ~transform, ~pose, ~aligned_cloud and ~associations (the last two only with subscribers).
  void publish(const AlignmentOutput& output);
  bool hasAlignedCloudSubscribers() const { return aligned_cloud_.getNumSubscribers() > 0; }
  bool hasAssociationSubscribers() const { return associations_.getNumSubscribers() > 0; }

  void broadcast(const geometry_msgs::TransformStamped& transform) {
    broadcaster_.sendTransform(transform);
  }

 private:
  ros::Publisher transform_, pose_, aligned_cloud_, associations_;
  tf2_ros::TransformBroadcaster broadcaster_;
};

}  // namespace pda_registration
