#pragma once
// Writes simulated maps as a rosbag a robot stack would record, for replay through the nodelet:
//   /dense_map     sensor_msgs/PointCloud2 in dense_frame (latched; published dense_messages times)
//   /sparse_map    sensor_msgs/PointCloud2 in sparse_frame, at 1 Hz from t = 1 s
//   /tf            tf2_msgs/TFMessage: the seed T_seed dense_frame -> sparse_frame at tf_rate
//   /ground_truth  geometry_msgs/TransformStamped: the exact T_target_source (latched), at 1 Hz
// The bag lasts sparse_messages + 1 seconds; tf and ground truth cover all of it, so the seed
// can be looked up at every sparse map's stamp. The interface is ROS-free.

#include <Eigen/Geometry>
#include <string>

#include "pda_registration/core/point_list.hpp"

namespace pda_registration {
namespace simulation {

struct MapBagOptions {
  int dense_messages = 2;
  int sparse_messages = 5;
  double tf_rate = 10.0;      ///< [Hz]
  double start_time = 100.0;  ///< [s] ROS time of the bag's first message
  std::string dense_frame = "dense_map";
  std::string sparse_frame = "sparse_map";
};

struct MapBagSummary {
  int dense_messages = 0;
  int sparse_messages = 0;
  int tf_messages = 0;
  int ground_truth_messages = 0;
  double duration = 0.0;  ///< [s]
};

/// Writes the bag (overwriting `path`). On failure returns false with a one-line reason.
bool writeMapBag(const std::string& path, const PointList& dense, const PointList& sparse,
                 const Eigen::Isometry3d& T_ground_truth, const Eigen::Isometry3d& T_seed,
                 const MapBagOptions& options, MapBagSummary* summary, std::string* error);

}  // namespace simulation
}  // namespace pda_registration
