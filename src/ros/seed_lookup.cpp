#include "pda_registration/ros/seed_lookup.hpp"

#include <tf2_eigen/tf2_eigen.h>

#include <algorithm>
#include <vector>

namespace pda_registration {

const char* toString(SeedSource source) {
  switch (source) {
    case SeedSource::kTfAtStamp:
      return "tf at the cloud's stamp";
    case SeedSource::kTfLatest:
      return "latest tf";
    case SeedSource::kInitialTransform:
      return "~initial_transform";
    case SeedSource::kNone:
      return "none";
  }
  return "unknown";
}

bool lookupAtStampOrLatest(const tf2_ros::Buffer& buffer, const std::string& target_frame,
                           const std::string& source_frame, const ros::Time& stamp,
                           const ros::Duration& timeout, Eigen::Isometry3d* T, bool* at_stamp,
                           std::string* error) {
  try {
    *T = tf2::transformToEigen(buffer.lookupTransform(target_frame, source_frame, stamp, timeout));
    *at_stamp = true;
    return true;
  } catch (const tf2::TransformException& e) {
    *error = e.what();
  }
  try {
    *T = tf2::transformToEigen(buffer.lookupTransform(target_frame, source_frame, ros::Time(0)));
    *at_stamp = false;
    return true;
  } catch (const tf2::TransformException& e) {
    *error = e.what();
  }
  return false;
}

bool frameInSeedChain(const tf2_ros::Buffer& buffer, const std::string& dense_frame,
                      const std::string& sparse_frame, const std::string& frame) {
  if (frame == dense_frame || frame == sparse_frame) return true;
  std::vector<std::string> chain;
  try {
    buffer._chainAsVector(dense_frame, ros::Time(0), sparse_frame, ros::Time(0), dense_frame,
                          chain);
  } catch (const tf2::TransformException&) {
    return true;
  }
  return std::find(chain.begin(), chain.end(), frame) != chain.end();
}

Seed lookupSeed(const tf2_ros::Buffer& buffer, const std::string& dense_frame,
                const std::string& sparse_frame, const ros::Time& stamp,
                const ros::Duration& timeout, const Eigen::Isometry3d* initial_transform) {
  Seed seed;
  bool at_stamp = false;
  if (lookupAtStampOrLatest(buffer, dense_frame, sparse_frame, stamp, timeout, &seed.T_dense_sparse,
                            &at_stamp, &seed.detail)) {
    seed.source = at_stamp ? SeedSource::kTfAtStamp : SeedSource::kTfLatest;
    return seed;
  }
  if (initial_transform) {
    seed.T_dense_sparse = *initial_transform;
    seed.source = SeedSource::kInitialTransform;
  }
  return seed;
}

}  // namespace pda_registration
