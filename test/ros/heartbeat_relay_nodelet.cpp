// A test nodelet standing in for the rest of a robot's perception in a shared manager: it relays
// every message on ~input to ~output at once. If the map-alignment nodelet ever held the
// manager's callback thread during an alignment, the relayed stream would stall.
#include <nodelet/nodelet.h>
#include <ros/ros.h>
#include <std_msgs/Header.h>

#include <pluginlib/class_list_macros.hpp>

namespace pda_registration {
namespace testing_support {

class HeartbeatRelay : public nodelet::Nodelet {
 private:
  void onInit() override {
    ros::NodeHandle& private_node = getPrivateNodeHandle();
    output_ = private_node.advertise<std_msgs::Header>("output", 100);
    input_ = private_node.subscribe<std_msgs::Header>(
        "input", 100, [this](const std_msgs::Header::ConstPtr& m) { output_.publish(m); });
  }

  ros::Publisher output_;
  ros::Subscriber input_;
};

}  // namespace testing_support
}  // namespace pda_registration

PLUGINLIB_EXPORT_CLASS(pda_registration::testing_support::HeartbeatRelay, nodelet::Nodelet)
