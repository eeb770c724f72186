#pragma once
// Surface normals of the target on voxel grids, for the surface-aware noise model
// (Sigma_j = sigma^2 (n n^T + kappa (I - n n^T))). Each voxel accumulates its points' first and
// second moments and its normal is their smallest principal axis, kept only where the voxel is
// planar. Coarser levels (2x ... 32x the voxel) merge their eight children's moments (in a fixed
// order), and a lookup takes the finest planar level: fine detail on dense maps, while on
// ring-structured lidar maps (whose small voxels hold a single scan line) the coarser levels
// still find the surface.
//
// The moments are kept, so points added later (a growing map) update only the voxels they fall in
// and their parents: add() costs about the new points, and gives exactly the map a build from all
// the points (in the same order) would.

#include <cstdint>
#include <unordered_map>
#include <vector>

#include "pda_registration/core/point_list.hpp"
#include "pda_registration/core/voxel_cell.hpp"

namespace pda_registration {

class SurfaceNormalMap {
 public:
  static constexpr int kLevels = 6;
  /// Points spread over a surface, not along a line, when their second principal variance is at
  /// least this fraction of the first (an extent ratio of about 1:3). Shared with the target's
  /// scan-line scale (scan_line_scale.hpp), which asks the same question of a neighbourhood.
  static constexpr double kTwoDimensionalSpread = 0.1;
  /// A planar voxel's normal stands unless its parent (twice the size) is planar too and tilted
  /// from it by more than 45 degrees (|cos| below this): see normalAt.
  static constexpr double kParentAgreement = 0.70710678118654752;

  SurfaceNormalMap() = default;
  /// finest_voxel_size <= 0 builds an empty map (every lookup says "no normal").
  SurfaceNormalMap(const PointList& points, double finest_voxel_size);

  /// Adds points[from ...] to the map (re-fitting the voxels they touch). No-op on an empty map.
  void add(const PointList& points, size_t from);

  /// The unit normal at p from the finest level whose voxel around p is planar; zero when no
  /// level has one (empty space, a line, a blob, or fewer than 5 points). Where the next coarser
  /// voxel is planar too and its normal is more than 45 degrees from that one's, the coarser
  /// normal: a single lidar ring thickened by range noise (2 cm on a VLP-16, in a 15-cm voxel at
  /// 5 m) spreads enough to pass as planar, and its plane is the laser's cone, which meets the
  /// wall steeply; the coarser voxel holds several rings and the wall. A real detail the finer
  /// voxel sees (an edge, a step) leaves its coarser voxel mixed, not planar, and stands.
  Eigen::Vector3d normalAt(const Point& p) const { return normalAt(p, nullptr); }

  /// A lookup's answer kept for the next question about a point that moved a little (a source
  /// point, run after run): a point in the same finest voxel gets the same answer (every coarser
  /// voxel around it is the same too), without probing the levels' tables. Tied to the map's
  /// version, which every add() changes.
  struct Memo {
    uint64_t version = 0;  ///< 0: holds nothing
    VoxelCell cell;
    Eigen::Vector3d normal = Eigen::Vector3d::Zero();
  };
  /// normalAt(p), answered from *memo when it holds p's finest voxel, and *memo updated.
  Eigen::Vector3d normalAt(const Point& p, Memo* memo) const;

  size_t voxelsWithNormal() const;

 private:
  using Cell = VoxelCell;
  // First and second moments of a voxel's points, relative to the voxel's own corner so that
  // large coordinates do not cancel catastrophically in the covariance.
  struct Moments {
    Cell cell;
    double count = 0.0;
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    Eigen::Matrix3d outer = Eigen::Matrix3d::Zero();
  };
  struct Level {
    double voxel_size = 0.0;
    std::unordered_map<uint64_t, Moments> moments;
    std::unordered_map<uint64_t, Eigen::Vector3f> normals;
  };
  /// Re-fits the given voxels of `level` (keys sorted, unique) and then their parents upwards.
  void refit(int level, std::vector<uint64_t> keys);
  /// Copies each level's normals into its open-addressing table (after every add()).
  void rebuildLookup();

  // The lookup's copy of each level's normals: an open-addressing table (key + 1, 0 = empty,
  // linear probing), read by normalAt once per source point and run: ~3x faster than a chain of
  // std::unordered_map lookups (~75 ns a call on the real cases).
  struct FlatLevel {
    std::vector<uint64_t> keys;
    std::vector<Eigen::Vector3f> normals;
    int shift = 64;
  };
  std::vector<Level> levels_;
  std::vector<FlatLevel> lookup_;
  uint64_t version_ = 0;  ///< new (never 0) with every rebuildLookup()
};

}  // namespace pda_registration
