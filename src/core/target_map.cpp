#include "pda_registration/core/target_map.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <exception>

#include "pda_registration/core/point_filter.hpp"
#include "pda_registration/core/representative_subset.hpp"
#include "pda_registration/core/scan_line_scale.hpp"

namespace pda_registration {
namespace {

// A crop that keeps most of the cloud saves little and would be redone whenever the source
// moves: index the whole cloud instead.
constexpr double kWorthCroppingFraction = 0.7;
// The indexed region extends this fraction of the needed region's size beyond it, so a source
// that moves a little (the next scan of a robot) is still served by the same index.
constexpr double kCropSlack = 0.25;

}  // namespace

AlignedBox AlignedBox::expanded(double margin) const {
  AlignedBox out = *this;
  if (empty()) return out;
  out.min.array() -= margin;
  out.max.array() += margin;
  return out;
}

AlignedBox reachableRegion(const PointList& source, const Eigen::Isometry3d& T,
                           double max_translation, double max_rotation, double radius) {
  AlignedBox box;
  if (source.empty()) return box;
  Point centroid = Point::Zero();
  for (const Point& p : source) {
    const Point moved = T * p;
    box.min = box.min.cwiseMin(moved);
    box.max = box.max.cwiseMax(moved);
    centroid += moved;
  }
  centroid /= static_cast<double>(source.size());
  double farthest = 0.0;
  for (const Point& p : source) farthest = std::max(farthest, (T * p - centroid).norm());
  const double angle = std::min(std::abs(max_rotation), M_PI);
  return box.expanded(std::abs(max_translation) + 2.0 * farthest * std::sin(0.5 * angle) +
                      std::abs(radius));
}

size_t TargetMap::cloudSize() const {
  if (!compact_.empty()) return compact_.size();
  if (index_owns_cloud_ && index_) return index_->size();
  return whole_.size();
}

bool TargetMap::setCloud(PointList points) {
  const size_t dropped = removeNonFinitePoints(&points);
  last_update_ = TargetUpdate::kStored;
  last_appended_ = 0;
  if (!points.empty() && extend(&points)) {
    dropped_ = dropped;
    return true;
  }
  // Not an extension: index the new cloud the way the previous one was (if it was).
  const bool reindex = index_ && have_indexing_;
  const TargetIndexing indexing = indexing_;
  const bool was_cropped = cropped_;
  const AlignedBox region = indexed_region_;
  clear();
  dropped_ = dropped;
  whole_ = std::move(points);
  if (whole_.empty()) return false;
  if (reindex && build(indexing, was_cropped ? &region : nullptr)) {
    last_update_ = TargetUpdate::kReindexed;
  }
  return true;
}

bool TargetMap::extend(PointList* points) {
  // A downsampled or thinned index is made afresh (the nodelet's keeper extends its own subset).
  if (!index_ || !have_indexing_ || indexing_.voxel_size > 0.0 || indexing_.subset_voxel > 0.0)
    return false;
  const auto start = std::chrono::steady_clock::now();
  size_t from;  // first new point
  size_t index_from = index_->size();
  try {
    if (!cropped_) {
      // The whole cloud is indexed: its points are the index's (doubles of the single-precision
      // copy for a large cloud).
      if (!index_->sharesPrefix(*points)) return false;
      from = index_from;
      if (!compact_.empty()) {
        for (size_t i = from; i < points->size(); ++i) {
          compact_.push_back((*points)[i].cast<float>());
          (*points)[i] = compact_.back().cast<double>();  // as an index of compact_ holds it
        }
      }
      index_ = TargetIndex::extended(index_, std::move(*points));
      index_owns_cloud_ = compact_.empty();
      whole_ = PointList();
    } else {
      // Cropped: the cloud is the single-precision copy; the crop grows by the new points inside
      // the indexed region (in cloud order, as a re-crop would keep them).
      if (points->size() < compact_.size()) return false;
      for (size_t i = 0; i < compact_.size(); ++i) {
        if ((*points)[i] != compact_[i].cast<double>()) return false;
      }
      from = compact_.size();
      PointList crop = index_->points();
      for (size_t i = from; i < points->size(); ++i) {
        compact_.push_back((*points)[i].cast<float>());
        const Point q = compact_.back().cast<double>();
        if (indexed_region_.contains(q)) crop.push_back(q);
      }
      index_ = TargetIndex::extended(index_, std::move(crop));
    }
  } catch (const std::exception&) {
    clear();  // out of memory: the caller stores the cloud afresh
    return false;
  }
  addNormals(index_from);
  last_update_ = TargetUpdate::kExtended;
  last_appended_ = cloudSize() - from;
  ++builds_;
  last_build_ms_ =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return true;
}

void TargetMap::addNormals(size_t from) {
  if (!normals_) return;
  try {
    // In place when nobody else holds the map (an alignment in flight keeps its own copy alive).
    if (normals_.use_count() != 1) normals_ = std::make_shared<SurfaceNormalMap>(*normals_);
    normals_->add(index_->points(), from);
  } catch (const std::exception&) {
    normals_ = std::make_shared<SurfaceNormalMap>();  // no normals: isotropic fallback
  }
}

void TargetMap::clear() {
  whole_.clear();
  whole_.shrink_to_fit();
  compact_.clear();
  compact_.shrink_to_fit();
  index_owns_cloud_ = false;
  dropped_ = 0;
  index_.reset();
  normals_.reset();
  have_indexing_ = false;
  cropped_ = false;
  subset_voxel_ = 0.0;
  normal_voxel_size_ = 0.0;
}

bool TargetMap::prepare(const TargetIndexing& indexing, const AlignedBox& region) {
  if (cloudSize() == 0) return false;
  const bool crop = croppingApplies(indexing) && !region.empty();
  if (index_ && have_indexing_ && indexing_ == indexing) {
    if (!cropped_) return true;  // the whole cloud is indexed: serves every region
    if (crop && indexed_region_.contains(region)) return true;
  }
  if (!crop) return build(indexing, nullptr);
  const Point size = region.max - region.min;
  const AlignedBox with_slack = region.expanded(kCropSlack * size.maxCoeff());
  return build(indexing, &with_slack);
}

bool TargetMap::build(const TargetIndexing& indexing, const AlignedBox* crop) {
  const auto start = std::chrono::steady_clock::now();
  // Recover the cloud from an index that took it over.
  if (index_owns_cloud_ && index_) whole_ = index_->points();
  index_owns_cloud_ = false;
  index_.reset();
  normals_.reset();
  have_indexing_ = false;
  cropped_ = false;
  subset_voxel_ = 0.0;

  PointList points;
  try {
    // Count first: a crop that would keep most of the cloud is not worth converting for.
    if (crop) {
      size_t inside = 0;
      for (const Point& p : whole_) inside += crop->contains(p) ? 1 : 0;
      for (const Eigen::Vector3f& p : compact_) inside += crop->contains(p.cast<double>()) ? 1 : 0;
      cropped_ = static_cast<double>(inside) <
                 kWorthCroppingFraction * static_cast<double>(cloudSize());
      if (cropped_) indexed_region_ = *crop;
    }
    if (cropped_ && compact_.empty()) {
      // A large cloud moves to single precision once it is first cropped.
      compact_.reserve(whole_.size());
      for (const Point& p : whole_) compact_.push_back(p.cast<float>());
      whole_ = PointList();
    }
    if (!compact_.empty()) {
      if (!cropped_) points.reserve(compact_.size());
      for (const Eigen::Vector3f& p : compact_) {
        const Point q = p.cast<double>();
        if (!cropped_ || crop->contains(q)) points.push_back(q);
      }
    }
    // The full-resolution cloud stays in whole_ when it is thinned (for later changes); read in
    // place, not copied.
    const PointList& input = compact_.empty() ? whole_ : points;
    PointList thinned;
    bool is_thinned = false;
    if (indexing.voxel_size > 0.0 && std::isfinite(indexing.voxel_size)) {
      thinned = voxelDownsample(input, indexing.voxel_size);
      is_thinned = true;
    }
    if (indexing.subset_voxel > 0.0 && std::isfinite(indexing.subset_voxel)) {
      const PointList& before = is_thinned ? thinned : input;
      PointList averaged = voxelDownsample(before, indexing.subset_voxel);
      if (static_cast<double>(before.size()) >=
          kMuchFinerRedundancy * static_cast<double>(averaged.size())) {
        thinned = std::move(averaged);
        is_thinned = true;
        subset_voxel_ = indexing.subset_voxel;
      }
    }
    if (is_thinned) {
      points = std::move(thinned);
    } else if (compact_.empty()) {
      points = std::move(whole_);
      whole_ = PointList();
      index_owns_cloud_ = true;
    }
    if (points.empty()) {
      if (index_owns_cloud_) index_owns_cloud_ = false;
      return false;
    }
    index_ = std::make_shared<const TargetIndex>(std::move(points));
  } catch (const std::exception&) {
    index_.reset();  // out of memory: align() reports "no target"
    if (index_owns_cloud_) index_owns_cloud_ = false;
    return false;
  }
  try {
    // The finest voxel is raised to the target's scan-line scale (scan_line_scale.hpp), measured
    // once here: a map that grows later keeps it, as its normal map keeps its voxels.
    normal_voxel_size_ = std::max(indexing.normal_voxel_size, scanLineScale(*index_));
    normals_ = std::make_shared<SurfaceNormalMap>(index_->points(), normal_voxel_size_);
  } catch (const std::exception&) {
    normals_ = std::make_shared<SurfaceNormalMap>();  // no normals: isotropic fallback
  }
  indexing_ = indexing;
  have_indexing_ = true;
  ++builds_;
  last_build_ms_ =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return true;
}

}  // namespace pda_registration
