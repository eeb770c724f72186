#include "pda_registration/simulation/map_bag_writer.hpp"

#include <geometry_msgs/TransformStamped.h>
#include <rosbag/bag.h>
#include <sensor_msgs/PointCloud2.h>
#include <tf2_eigen/tf2_eigen.h>
#include <tf2_msgs/TFMessage.h>

#include <algorithm>
#include <boost/make_shared.hpp>
#include <cmath>
#include <vector>

#include "pda_registration/ros/point_cloud_conversion.hpp"

namespace pda_registration {
namespace simulation {
namespace {

sensor_msgs::PointCloud2 toCloudMessage(const PointList& points, const std::string& frame,
                                        const ros::Time& stamp) {
  std_msgs::Header header;
  header.frame_id = frame;
  header.stamp = stamp;
  return toPointCloud2(points, header);
}

geometry_msgs::TransformStamped toTransformMessage(const Eigen::Isometry3d& T,
                                                   const std::string& parent,
                                                   const std::string& child,
                                                   const ros::Time& stamp) {
  geometry_msgs::TransformStamped message = tf2::eigenToTransform(T);
  message.header.frame_id = parent;
  message.header.stamp = stamp;
  message.child_frame_id = child;
  return message;
}

// A latched connection: `rosbag play` then re-sends the last message to late subscribers, as
// a map server would.
template <typename Message>
boost::shared_ptr<ros::M_string> latchedConnection() {
  auto header = boost::make_shared<ros::M_string>();
  (*header)["type"] = ros::message_traits::datatype<Message>();
  (*header)["md5sum"] = ros::message_traits::md5sum<Message>();
  (*header)["message_definition"] = ros::message_traits::definition<Message>();
  (*header)["callerid"] = "/pda_simulate";
  (*header)["latching"] = "1";
  return header;
}

enum class Topic { kTf, kGroundTruth, kDense, kSparse };

struct Publication {
  double time;  // [s] since the start of the bag
  Topic topic;
};

}  // namespace

bool writeMapBag(const std::string& path, const PointList& dense, const PointList& sparse,
                 const Eigen::Isometry3d& T_ground_truth, const Eigen::Isometry3d& T_seed,
                 const MapBagOptions& options, MapBagSummary* summary, std::string* error) {
  if (options.dense_messages < 1 || options.sparse_messages < 1 || !(options.tf_rate > 0.0)) {
    *error = "a bag needs at least one dense and one sparse map and a positive tf rate";
    return false;
  }
  MapBagSummary counts;
  counts.duration = options.sparse_messages + 1.0;
  std::vector<Publication> schedule;
  const int tf_messages = static_cast<int>(std::floor(counts.duration * options.tf_rate + 1e-9));
  for (int i = 0; i <= tf_messages; ++i) schedule.push_back({i / options.tf_rate, Topic::kTf});
  for (int i = 0; i <= static_cast<int>(counts.duration); ++i) {
    schedule.push_back({static_cast<double>(i), Topic::kGroundTruth});
  }
  for (int i = 0; i < options.dense_messages; ++i) {
    schedule.push_back({0.5 + i * counts.duration / options.dense_messages, Topic::kDense});
  }
  for (int i = 0; i < options.sparse_messages; ++i) {
    schedule.push_back({1.0 + i, Topic::kSparse});
  }
  // Messages in time order; at equal times tf comes first so a seed precedes the cloud.
  std::stable_sort(schedule.begin(), schedule.end(),
                   [](const Publication& a, const Publication& b) {
                     return a.time < b.time || (a.time == b.time && a.topic < b.topic);
                   });

  try {
    rosbag::Bag bag(path, rosbag::bagmode::Write);
    const auto dense_connection = latchedConnection<sensor_msgs::PointCloud2>();
    const auto truth_connection = latchedConnection<geometry_msgs::TransformStamped>();
    for (const Publication& publication : schedule) {
      const ros::Time stamp(options.start_time + publication.time);
      switch (publication.topic) {
        case Topic::kTf: {
          tf2_msgs::TFMessage tf;
          tf.transforms.push_back(
              toTransformMessage(T_seed, options.dense_frame, options.sparse_frame, stamp));
          bag.write("/tf", stamp, tf);
          ++counts.tf_messages;
          break;
        }
        case Topic::kGroundTruth:
          bag.write(
              "/ground_truth", stamp,
              toTransformMessage(T_ground_truth, options.dense_frame, options.sparse_frame, stamp),
              truth_connection);
          ++counts.ground_truth_messages;
          break;
        case Topic::kDense:
          bag.write("/dense_map", stamp, toCloudMessage(dense, options.dense_frame, stamp),
                    dense_connection);
          ++counts.dense_messages;
          break;
        case Topic::kSparse:
          bag.write("/sparse_map", stamp, toCloudMessage(sparse, options.sparse_frame, stamp));
          ++counts.sparse_messages;
          break;
      }
    }
    bag.close();
  } catch (const std::exception& e) {
    *error = "cannot write bag '" + path + "': " + e.what();
    return false;
  }
  if (summary != nullptr) *summary = counts;
  return true;
}

}  // namespace simulation
}  // namespace pda_registration
