#pragma once
// The transforms a bag records: its tf tree (/tf and /tf_static, cached over the whole bag) for
// the seed, and an optional ground-truth topic (geometry_msgs/TransformStamped, dense <- sparse:
// p_dense = T * p_sparse) to measure the estimate against.

#include <tf2/buffer_core.h>

#include <Eigen/Geometry>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "pda_registration/ros/seed_lookup.hpp"
#include "pda_registration/tools/bag_maps.hpp"

namespace pda_registration {

class BagTransforms {
 public:
  /// Reads tf and, when ground_truth_topic is non-empty and in the bag, the ground truth.
  /// Fails (error set) when the ground-truth topic holds another type or no readable message.
  bool load(const BagMaps& bag, const std::string& ground_truth_topic, std::string* error);

  /// T dense_frame <- sparse_frame at `stamp`, else the latest tf before it (kTfAtStamp,
  /// kTfLatest); source kNone with tf's reason when neither exists.
  Seed seed(const std::string& dense_frame, const std::string& sparse_frame,
            const ros::Time& stamp) const;

  bool hasGroundTruth() const { return !ground_truth_.empty(); }
  /// The latest ground truth at or before `stamp`, else the earliest one.
  Eigen::Isometry3d groundTruthAt(const ros::Time& stamp) const;

  size_t tfMessages() const { return tf_messages_; }

 private:
  std::unique_ptr<tf2::BufferCore> tf_;
  size_t tf_messages_ = 0;
  std::vector<std::pair<ros::Time, Eigen::Isometry3d>> ground_truth_;  ///< sorted by stamp
};

}  // namespace pda_registration
