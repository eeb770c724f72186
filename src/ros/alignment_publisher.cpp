#include "pda_registration/ros/alignment_publisher.hpp"

#include <geometry_msgs/PoseWithCovarianceStamped.h>
#include <tf2_eigen/tf2_eigen.h>
#include <visualization_msgs/MarkerArray.h>

#include "pda_registration/ros/association_markers.hpp"
#include "pda_registration/ros/point_cloud_conversion.hpp"

namespace pda_registration {

AlignmentPublisher::AlignmentPublisher(ros::NodeHandle& private_node)
    : transform_(private_node.advertise<geometry_msgs::TransformStamped>("transform", 5)),
      pose_(private_node.advertise<geometry_msgs::PoseWithCovarianceStamped>("pose", 5)),
      aligned_cloud_(private_node.advertise<sensor_msgs::PointCloud2>("aligned_cloud", 1)),
      associations_(private_node.advertise<visualization_msgs::MarkerArray>("associations", 1)) {}

void AlignmentPublisher::publish(const AlignmentOutput& o) {
  geometry_msgs::TransformStamped transform = tf2::eigenToTransform(o.T_dense_sparse);
  transform.header.stamp = o.stamp;
  transform.header.frame_id = o.dense_frame;
  transform.child_frame_id = o.sparse_frame;
  transform_.publish(transform);

  geometry_msgs::PoseWithCovarianceStamped pose;
  pose.header = transform.header;
  pose.pose.pose = tf2::toMsg(o.T_dense_sparse);
  for (int r = 0; r < 6; ++r) {
    for (int c = 0; c < 6; ++c) pose.pose.covariance[6 * r + c] = o.covariance(r, c);
  }
  pose_.publish(pose);

  std_msgs::Header target_header;
  target_header.stamp = o.stamp;
  target_header.frame_id = o.target_frame;
  if (o.aligned && aligned_cloud_.getNumSubscribers() > 0) {
    aligned_cloud_.publish(toPointCloud2(*o.aligned, target_header));
  }
  if (o.associations && associations_.getNumSubscribers() > 0) {
    associations_.publish(
        associationMarkers(*o.associations, target_header, o.max_markers, o.marker_line_width));
  }
}

}  // namespace pda_registration
