#include "pda_registration/ros/edge_broadcaster.hpp"

#include <tf2_eigen/tf2_eigen.h>

#include <algorithm>

namespace pda_registration {

void EdgeBroadcaster::rebroadcast() {
  const ros::Time now = ros::Time::now();
  if (!now.isZero()) send(nullptr, now);
}

void EdgeBroadcaster::send(const TfEdge* fresh, const ros::Time& requested_stamp) {
  TfEdge edge;
  ros::Time stamp = requested_stamp;
  {
    // The edge and its stamp are taken together, so a re-broadcast never sends an older edge at
    // a newer stamp than a fresh one.
    std::lock_guard<std::mutex> lock(mutex_);
    if (fresh) {
      edge_ = *fresh;
      have_edge_ = true;
    } else if (!have_edge_) {
      return;
    }
    edge = edge_;
    // A late cloud's estimate goes out stamped now; a re-broadcast while simulated time stands
    // still is skipped; a clock that jumped back (a looping bag) starts the edge afresh.
    const ros::Time now = ros::Time::now();
    if (now + ros::Duration(1.0) < last_stamp_) last_stamp_ = ros::Time();
    if (stamp <= last_stamp_) {
      if (!fresh) return;
      stamp = std::max(now, last_stamp_ + ros::Duration(0, 1000));
    }
    last_stamp_ = stamp;
  }
  geometry_msgs::TransformStamped transform = tf2::eigenToTransform(edge.T_parent_child);
  transform.header.stamp = stamp;
  transform.header.frame_id = edge.parent;
  transform.child_frame_id = edge.child;
  publisher_->broadcast(transform);
}

}  // namespace pda_registration
