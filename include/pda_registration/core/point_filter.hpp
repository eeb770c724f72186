#pragma once
// Pre-processing shared by the core, the tools and the nodelet: drop non-finite points, and
// voxel-grid downsample (one centroid per occupied voxel).

#include "pda_registration/core/point_list.hpp"

namespace pda_registration {

/// Removes points with a NaN or Inf coordinate in place; returns how many were removed.
size_t removeNonFinitePoints(PointList* points);

/// How many points have three finite coordinates.
size_t countFinitePoints(const PointList& points);

/// One centroid per occupied cubic voxel of side `voxel_size`. voxel_size <= 0 returns the input.
/// Output order follows the first point seen in each voxel, so it is deterministic.
PointList voxelDownsample(const PointList& points, double voxel_size);

}  // namespace pda_registration
