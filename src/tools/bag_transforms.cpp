#include "pda_registration/tools/bag_transforms.hpp"

#include <geometry_msgs/TransformStamped.h>
#include <ros/message_traits.h>
#include <rosbag/view.h>
#include <tf2/exceptions.h>
#include <tf2_eigen/tf2_eigen.h>
#include <tf2_msgs/TFMessage.h>

#include <algorithm>
#include <cctype>

namespace pda_registration {
namespace {

// tf2 stores frame ids without a leading slash (ROS 1 style "/map") but refuses one in lookups.
std::string tfFrame(const std::string& frame) {
  return !frame.empty() && frame[0] == '/' ? frame.substr(1) : frame;
}

// tf's messages end in a space; the reports quote them at the end of a line.
std::string trimmed(std::string text) {
  while (!text.empty() && std::isspace(static_cast<unsigned char>(text.back()))) text.pop_back();
  return text;
}

}  // namespace

bool BagTransforms::load(const BagMaps& bag, const std::string& ground_truth_topic,
                         std::string* error) {
  // The cache must span the whole bag: every seed is looked up after all of tf is loaded.
  const ros::Duration span = bag.endTime() - bag.beginTime();
  tf_ = std::make_unique<tf2::BufferCore>(span + ros::Duration(1.0));
  tf_messages_ = 0;
  ground_truth_.clear();

  rosbag::View tf_view(bag.bag(),
                       rosbag::TopicQuery(std::vector<std::string>{"/tf", "/tf_static"}));
  for (const rosbag::MessageInstance& instance : tf_view) {
    const tf2_msgs::TFMessage::ConstPtr message = instance.instantiate<tf2_msgs::TFMessage>();
    if (!message) continue;
    const bool is_static = instance.getTopic() == "/tf_static";
    for (const geometry_msgs::TransformStamped& transform : message->transforms) {
      tf_->setTransform(transform, "bag", is_static);
    }
    ++tf_messages_;
  }

  if (ground_truth_topic.empty() || bag.topicType(ground_truth_topic).empty()) return true;
  const std::string expected = ros::message_traits::datatype<geometry_msgs::TransformStamped>();
  if (bag.topicType(ground_truth_topic) != expected) {
    *error = "ground-truth topic '" + ground_truth_topic + "' is " +
             bag.topicType(ground_truth_topic) + ", not " + expected;
    return false;
  }
  rosbag::View truth_view(bag.bag(), rosbag::TopicQuery(ground_truth_topic));
  for (const rosbag::MessageInstance& instance : truth_view) {
    const auto message = instance.instantiate<geometry_msgs::TransformStamped>();
    if (!message) continue;
    const ros::Time stamp =
        message->header.stamp.isZero() ? instance.getTime() : message->header.stamp;
    ground_truth_.emplace_back(stamp, tf2::transformToEigen(*message));
  }
  if (ground_truth_.empty()) {
    *error = "ground-truth topic '" + ground_truth_topic + "' has no readable message";
    return false;
  }
  std::stable_sort(ground_truth_.begin(), ground_truth_.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  return true;
}

Seed BagTransforms::seed(const std::string& dense_frame, const std::string& sparse_frame,
                         const ros::Time& stamp) const {
  Seed seed;
  try {
    seed.T_dense_sparse = tf2::transformToEigen(
        tf_->lookupTransform(tfFrame(dense_frame), tfFrame(sparse_frame), stamp));
    seed.source = SeedSource::kTfAtStamp;
    return seed;
  } catch (const tf2::TransformException& at_stamp) {
    seed.detail = trimmed(at_stamp.what());
  }
  try {
    // The buffer holds the whole bag, so "latest" may lie after the cloud: only use it if not.
    const geometry_msgs::TransformStamped latest =
        tf_->lookupTransform(tfFrame(dense_frame), tfFrame(sparse_frame), ros::Time(0));
    if (latest.header.stamp <= stamp) {
      seed.T_dense_sparse = tf2::transformToEigen(latest);
      seed.source = SeedSource::kTfLatest;
      seed.detail.clear();
    }
  } catch (const tf2::TransformException&) {
    // The reason at the stamp already says what is missing.
  }
  return seed;
}

Eigen::Isometry3d BagTransforms::groundTruthAt(const ros::Time& stamp) const {
  const auto after =
      std::upper_bound(ground_truth_.begin(), ground_truth_.end(), stamp,
                       [](const ros::Time& t, const std::pair<ros::Time, Eigen::Isometry3d>& g) {
                         return t < g.first;
                       });
  return after == ground_truth_.begin() ? ground_truth_.front().second : std::prev(after)->second;
}

}  // namespace pda_registration
