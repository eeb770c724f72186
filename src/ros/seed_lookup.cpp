#include "pda_registration/ros/seed_lookup.hpp"

#include <tf2_eigen/tf2_eigen.h>

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

Seed lookupSeed(const tf2_ros::Buffer& buffer, const std::string& dense_frame,
                const std::string& sparse_frame, const ros::Time& stamp,
                const ros::Duration& timeout, const Eigen::Isometry3d* initial_transform) {
  Seed seed;
  try {
    seed.T_dense_sparse =
        tf2::transformToEigen(buffer.lookupTransform(dense_frame, sparse_frame, stamp, timeout));
    seed.source = SeedSource::kTfAtStamp;
    return seed;
  } catch (const tf2::TransformException& at_stamp) {
    seed.detail = at_stamp.what();
  }
  try {
    seed.T_dense_sparse =
        tf2::transformToEigen(buffer.lookupTransform(dense_frame, sparse_frame, ros::Time(0)));
    seed.source = SeedSource::kTfLatest;
    return seed;
  } catch (const tf2::TransformException& latest) {
    seed.detail = latest.what();
  }
  if (initial_transform) {
    seed.T_dense_sparse = *initial_transform;
    seed.source = SeedSource::kInitialTransform;
  }
  return seed;
}

}  // namespace pda_registration
