#include "pda_registration/tools/bag_maps.hpp"

#include <ros/message_traits.h>
#include <rosbag/view.h>

namespace pda_registration {

bool BagMaps::open(const std::string& path, const MapTopics& topics, std::string* error) {
  path_ = path;
  topics_ = topics;
  topic_types_.clear();
  message_counts_.clear();
  try {
    bag_ = std::make_unique<rosbag::Bag>(path, rosbag::bagmode::Read);
    rosbag::View everything(*bag_);
    for (const rosbag::ConnectionInfo* connection : everything.getConnections()) {
      topic_types_[connection->topic] = connection->datatype;
    }
    for (const auto& topic_type : topic_types_) {
      rosbag::View view(*bag_, rosbag::TopicQuery(topic_type.first));
      message_counts_[topic_type.first] = view.size();
    }
    begin_ = everything.size() > 0 ? everything.getBeginTime() : ros::Time();
    end_ = everything.size() > 0 ? everything.getEndTime() : ros::Time();
  } catch (const std::exception& e) {
    bag_.reset();
    *error = "cannot read bag '" + path + "': " + e.what();
    return false;
  }
  const std::string cloud_type = ros::message_traits::datatype<sensor_msgs::PointCloud2>();
  for (const std::string* topic : {&topics_.dense, &topics_.sparse}) {
    const std::string type = topicType(*topic);
    if (type.empty()) {
      *error = "bag '" + path + "' has no topic '" + *topic + "'; its topics: " + describeTopics();
      return false;
    }
    if (type != cloud_type) {
      *error = "topic '" + *topic + "' in bag '" + path + "' is " + type + ", not " + cloud_type;
      return false;
    }
  }
  return true;
}

std::string BagMaps::topicType(const std::string& topic) const {
  const auto it = topic_types_.find(topic);
  return it == topic_types_.end() ? "" : it->second;
}

std::string BagMaps::describeTopics() const {
  if (topic_types_.empty()) return "none";
  std::string text;
  for (const auto& topic_type : topic_types_) {
    text += (text.empty() ? "" : ", ") + topic_type.first + " (" + topic_type.second + ")";
  }
  return text;
}

size_t BagMaps::messageCount(const std::string& topic) const {
  const auto it = message_counts_.find(topic);
  return it == message_counts_.end() ? 0 : it->second;
}

void BagMaps::forEachMap(const std::function<bool(const MapMessage&)>& visit) const {
  rosbag::View view(*bag_,
                    rosbag::TopicQuery(std::vector<std::string>{topics_.dense, topics_.sparse}));
  for (const rosbag::MessageInstance& instance : view) {
    MapMessage message;
    message.dense = instance.getTopic() == topics_.dense;
    message.stamp = instance.getTime();
    try {
      message.cloud = instance.instantiate<sensor_msgs::PointCloud2>();
      if (!message.cloud) message.error = "not a sensor_msgs/PointCloud2";
    } catch (const std::exception& e) {
      // A truncated or corrupt record: the caller reports it and moves on.
      message.error = std::string("cannot deserialise: ") + e.what();
    }
    if (message.cloud && !message.cloud->header.stamp.isZero()) {
      message.stamp = message.cloud->header.stamp;
    }
    if (!visit(message)) return;
  }
}

}  // namespace pda_registration
