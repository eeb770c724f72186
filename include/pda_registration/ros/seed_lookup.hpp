#pragma once
// Where an alignment starts: tf's dense <- sparse transform at the sparse cloud's stamp (waiting
// up to the timeout), else the latest tf has, else ~initial_transform, else nothing.

#include <tf2_ros/buffer.h>

#include <Eigen/Geometry>
#include <string>

namespace pda_registration {

enum class SeedSource { kTfAtStamp, kTfLatest, kInitialTransform, kNone };

const char* toString(SeedSource source);

struct Seed {
  Eigen::Isometry3d T_dense_sparse = Eigen::Isometry3d::Identity();
  SeedSource source = SeedSource::kNone;
  std::string detail;  ///< tf's error when it could not help
};

/// target <- source from tf at `stamp` (waiting up to `timeout`), else the latest tf has;
/// *at_stamp says which. False, with tf's error in *error, when tf has neither.
bool lookupAtStampOrLatest(const tf2_ros::Buffer& buffer, const std::string& target_frame,
                           const std::string& source_frame, const ros::Time& stamp,
                           const ros::Duration& timeout, Eigen::Isometry3d* T, bool* at_stamp,
                           std::string* error);

/// True when `frame` lies on tf's chain from `dense_frame` to `sparse_frame` (either end
/// included): an edge whose child is `frame` then moves the seed. Also true when tf cannot tell
/// (no chain yet), the cautious answer for the warm start (core/warm_start.hpp).
bool frameInSeedChain(const tf2_ros::Buffer& buffer, const std::string& dense_frame,
                      const std::string& sparse_frame, const std::string& frame);

Seed lookupSeed(const tf2_ros::Buffer& buffer, const std::string& dense_frame,
                const std::string& sparse_frame, const ros::Time& stamp,
                const ros::Duration& timeout, const Eigen::Isometry3d* initial_transform);

}  // namespace pda_registration
