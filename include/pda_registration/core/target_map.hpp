#pragma once
// The registration target: the whole (finite) cloud, and the search index and surface normal
// map built from it. Small targets are indexed whole, once. A large target (a building-sized
// dense map) is indexed only around the region a source can reach from its seed (its bounds
// plus the largest correction the caller accepts, plus the candidate radius), with some slack,
// and re-indexed only when a later source needs a region outside the indexed one. Indexing time
// and the memory of the index and normal map then follow the source's reach, not the map's size;
// the map itself is kept compactly (single precision) for re-cropping.

#include <Eigen/Geometry>
#include <limits>
#include <memory>
#include <vector>

#include "pda_registration/core/point_list.hpp"
#include "pda_registration/core/surface_normals.hpp"
#include "pda_registration/core/target_index.hpp"

namespace pda_registration {

/// An axis-aligned box; empty when min > max on any axis.
struct AlignedBox {
  Point min = Point::Constant(std::numeric_limits<double>::infinity());
  Point max = Point::Constant(-std::numeric_limits<double>::infinity());

  bool empty() const { return (min.array() > max.array()).any(); }
  void extend(const Point& p) {
    min = min.cwiseMin(p);
    max = max.cwiseMax(p);
  }
  bool contains(const Point& p) const {
    return (p.array() >= min.array()).all() && (p.array() <= max.array()).all();
  }
  bool contains(const AlignedBox& other) const {
    return !other.empty() && contains(other.min) && contains(other.max);
  }
  AlignedBox expanded(double margin) const;
};

/// Where the moved source T * source can land after a correction of at most `max_translation`
/// and `max_rotation` [rad] (about its centroid), widened by the candidate `radius`. The rotation
/// moves a point at distance r from the centroid by at most 2 r sin(angle / 2).
AlignedBox reachableRegion(const PointList& source, const Eigen::Isometry3d& T,
                           double max_translation, double max_rotation, double radius);

/// How the index is built; a change of any field re-indexes on the next prepare().
struct TargetIndexing {
  double voxel_size = 0.0;          ///< target downsampling before indexing (0 = off)
  /// Index the voxel means on this grid when the cloud holds at least kMuchFinerRedundancy
  /// points per occupied voxel (representative_subset.hpp); 0 = every point.
  double subset_voxel = 0.0;
  /// Finest voxel of the normal map, raised to the target's scan-line scale where that is larger.
  double normal_voxel_size = 0.15;
  /// Targets with more finite points than this are cropped to the source's reach (0 = never).
  size_t crop_above_points = 0;

  bool operator==(const TargetIndexing& o) const {
    return voxel_size == o.voxel_size && subset_voxel == o.subset_voxel &&
           normal_voxel_size == o.normal_voxel_size &&
           crop_above_points == o.crop_above_points;
  }
};

/// How setCloud() took a new cloud.
enum class TargetUpdate {
  kStored,     ///< kept; indexed by the next prepare() (no index to follow yet)
  kReindexed,  ///< indexed again from scratch, the way the previous cloud was (whole or cropped)
  kExtended,   ///< the previous cloud is its prefix: only the appended points were indexed
};

class TargetMap {
 public:
  /// Replaces the cloud: non-finite points are dropped (and counted). Returns false when no
  /// finite point is left. When the previous cloud was indexed:
  ///  - a cloud that starts with the previous cloud's points (a growing map re-published whole,
  ///    new points appended) extends the index and the normal map by the new points only
  ///    (the whole index; or, cropped, by the new points inside the indexed region), unless the
  ///    target is voxel-downsampled;
  ///  - any other cloud is indexed right here the same way (whole, or around the same region),
  ///    so a caller that sets the cloud on a background thread finds it ready.
  /// Otherwise nothing is indexed yet (prepare() does it).
  bool setCloud(PointList points);
  TargetUpdate lastUpdate() const { return last_update_; }
  /// Points appended by the last extension.
  size_t lastAppended() const { return last_appended_; }
  void clear();

  size_t cloudSize() const;
  size_t droppedPoints() const { return dropped_; }
  bool croppingApplies(const TargetIndexing& indexing) const {
    return indexing.crop_above_points > 0 && cloudSize() > indexing.crop_above_points;
  }

  /// Makes the index serve `region` (ignored unless the target is large enough to crop). Builds
  /// nothing when the current index already does. Returns false when nothing could be indexed
  /// (no finite point, or no target point inside the region: the caller reports no overlap).
  bool prepare(const TargetIndexing& indexing, const AlignedBox& region);

  /// The current index and normal map; null before the first successful prepare().
  std::shared_ptr<const TargetIndex> index() const { return index_; }
  std::shared_ptr<const SurfaceNormalMap> normals() const { return normals_; }
  bool cropped() const { return cropped_; }
  /// The normal map's finest voxel: TargetIndexing's, or the target's scan-line scale if larger.
  double normalVoxelSize() const { return normal_voxel_size_; }
  /// The grid of the indexed voxel means (subset_voxel); 0 when every point (of the crop) is.
  double subsetVoxel() const { return subset_voxel_; }
  /// Wall time of the last (re)build [ms], and how many builds so far (for tests and reports).
  double lastBuildMs() const { return last_build_ms_; }
  size_t builds() const { return builds_; }

 private:
  bool build(const TargetIndexing& indexing, const AlignedBox* crop);
  /// The extension of setCloud(); false (nothing changed) when `points` does not extend the
  /// indexed cloud.
  bool extend(PointList* points);
  void addNormals(size_t from);

  // Small targets keep their points in double precision; when they are indexed without
  // downsampling the index takes them over (index_owns_cloud_), so they are not held twice.
  // Large targets are kept in single precision and only their crops are indexed.
  PointList whole_;
  bool index_owns_cloud_ = false;
  std::vector<Eigen::Vector3f> compact_;
  size_t dropped_ = 0;

  std::shared_ptr<const TargetIndex> index_;
  std::shared_ptr<SurfaceNormalMap> normals_;  // updated in place when nobody else holds it
  bool have_indexing_ = false;
  TargetIndexing indexing_;
  bool cropped_ = false;
  double subset_voxel_ = 0.0;
  double normal_voxel_size_ = 0.0;
  AlignedBox indexed_region_;  // valid when cropped_
  double last_build_ms_ = 0.0;
  size_t builds_ = 0;
  TargetUpdate last_update_ = TargetUpdate::kStored;
  size_t last_appended_ = 0;
};

}  // namespace pda_registration
