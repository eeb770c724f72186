#pragma once
// Surface normals of the target on voxel grids, for the surface-aware noise model
// (Sigma_j = sigma^2 (n n^T + kappa (I - n n^T))). Built once per target in one pass over the
// points: each voxel accumulates its points' first and second moments and its normal is their
// smallest principal axis, kept only where the voxel is planar. Coarser levels (2x ... 32x the
// voxel) merge their children's moments, and a lookup takes the finest planar level: fine detail
// on dense maps, while on ring-structured lidar maps (whose small voxels hold a single scan line)
// the coarser levels still find the surface.

#include <cstdint>
#include <unordered_map>
#include <vector>

#include "pda_registration/core/point_list.hpp"

namespace pda_registration {

class SurfaceNormalMap {
 public:
  static constexpr int kLevels = 6;

  SurfaceNormalMap() = default;
  /// finest_voxel_size <= 0 builds an empty map (every lookup says "no normal").
  SurfaceNormalMap(const PointList& points, double finest_voxel_size);

  /// The unit normal at p from the finest level whose voxel around p is planar; zero when no
  /// level has one (empty space, a line, a blob, or fewer than 5 points).
  Eigen::Vector3d normalAt(const Point& p) const;

  size_t voxelsWithNormal() const;

 private:
  struct Level {
    double voxel_size = 0.0;
    std::unordered_map<uint64_t, Eigen::Vector3f> normals;
  };
  std::vector<Level> levels_;
};

}  // namespace pda_registration
