#pragma once
// The dense and sparse maps of a recorded bag, read with the rosbag C++ API: the topics are
// checked when the bag is opened, and the clouds are visited in record order without holding
// more than one message at a time.

#include <rosbag/bag.h>
#include <sensor_msgs/PointCloud2.h>

#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace pda_registration {

struct MapTopics {
  std::string dense = "/dense_map";
  std::string sparse = "/sparse_map";
};

/// One dense or sparse map message.
struct MapMessage {
  bool dense = false;
  sensor_msgs::PointCloud2::ConstPtr cloud;  ///< null when it could not be deserialised
  std::string error;                         ///< why cloud is null
  /// The header stamp, or the record time when the header has none.
  ros::Time stamp;
};

class BagMaps {
 public:
  /// Opens the bag; fails (error set, one line) when it cannot be read or lacks either map topic
  /// (naming the topics it does have) or holds another type on it.
  bool open(const std::string& path, const MapTopics& topics, std::string* error);

  const rosbag::Bag& bag() const { return *bag_; }
  const std::string& path() const { return path_; }
  const MapTopics& topics() const { return topics_; }
  /// The datatype recorded on `topic`; empty when the bag does not have it.
  std::string topicType(const std::string& topic) const;
  /// "name (type)" for every topic, for error messages.
  std::string describeTopics() const;
  size_t messageCount(const std::string& topic) const;
  ros::Time beginTime() const { return begin_; }
  ros::Time endTime() const { return end_; }

  /// Visits the dense and sparse messages in record order until `visit` returns false.
  void forEachMap(const std::function<bool(const MapMessage&)>& visit) const;

 private:
  std::string path_;
  MapTopics topics_;
  std::unique_ptr<rosbag::Bag> bag_;
  std::map<std::string, std::string> topic_types_;
  std::map<std::string, size_t> message_counts_;
  ros::Time begin_, end_;
};

}  // namespace pda_registration
