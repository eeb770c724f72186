#pragma once
// A small synthetic room for core tests: a dense target sampled on its surfaces and a sparse,
// noisy source seen from another pose, optionally with outliers. Deterministic per seed.

#include <Eigen/Geometry>
#include <cstdint>

#include "pda_registration/core/point_list.hpp"

namespace pda_registration {
namespace testing_support {

struct SyntheticCase {
  PointList target;                                                   ///< dense, target frame
  PointList source;                                                   ///< sparse, source frame
  Eigen::Isometry3d T_target_source = Eigen::Isometry3d::Identity();  ///< ground truth
};

struct SyntheticOptions {
  double target_spacing = 0.04;   ///< [m] grid spacing on every surface
  int source_points = 2000;       ///< inliers sampled at random on the surfaces
  double source_noise = 0.01;     ///< [m] Gaussian, per axis
  double outlier_fraction = 0.0;  ///< extra points (fraction of source_points) uniform in the room
  double scale = 1.0;             ///< multiply every length (1000 = millimetres)
  uint64_t seed = 1;
};

/// The ground truth is a fixed, moderate transform (about 8 degrees and 0.3 m).
SyntheticCase makeSyntheticRoom(const SyntheticOptions& options);

/// Points on a single plane (degenerate geometry for the bad-input tests).
PointList makePlane(double size, double spacing);

/// A fixed moderate transform used as ground truth by the synthetic cases.
Eigen::Isometry3d syntheticGroundTruth(double scale);

}  // namespace testing_support
}  // namespace pda_registration
