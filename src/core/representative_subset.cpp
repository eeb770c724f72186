#include "pda_registration/core/representative_subset.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <vector>

#include "pda_registration/core/target_index.hpp"
#include "pda_registration/core/voxel_cell.hpp"

namespace pda_registration {
namespace {

constexpr uint64_t kHashStart = 1469598103934665603ull;

// 64-bit FNV-1a over the bytes of points [from, to), a word at a time, continuing `hash`: a linear
// pass that tells a continued map from a new one without keeping a copy of the whole map.
uint64_t hashPoints(const PointList& points, size_t from, size_t to, uint64_t hash) {
  const auto* words = reinterpret_cast<const unsigned char*>(points.data());
  for (size_t i = from * sizeof(Point); i < to * sizeof(Point); i += sizeof(uint64_t)) {
    uint64_t word;
    std::memcpy(&word, words + i, sizeof(word));
    hash = (hash ^ word) * 1099511628211ull;
  }
  return hash;
}

}  // namespace

double sampleSpacing(const PointList& cloud, size_t samples) {
  if (cloud.size() < 2 || samples == 0) return 0.0;
  const TargetIndex index(cloud);
  // Exact duplicates (a map that holds a point twice) are not the sampling: the nearest
  // neighbour at a positive distance among the few nearest.
  constexpr int kNearest = 8;
  size_t indices[kNearest];
  double squared[kNearest];
  std::vector<double> spacing;
  const size_t step = std::max<size_t>(1, cloud.size() / samples);
  for (size_t i = 0; i < cloud.size(); i += step) {
    const size_t found = index.nearestWithinRadius(
        cloud[i], kNearest, std::numeric_limits<double>::infinity(), indices, squared);
    for (size_t n = 0; n < found; ++n) {
      if (squared[n] > 0.0) {
        spacing.push_back(std::sqrt(squared[n]));
        break;
      }
    }
  }
  if (spacing.empty()) return 0.0;
  std::nth_element(spacing.begin(), spacing.begin() + spacing.size() / 2, spacing.end());
  return spacing[spacing.size() / 2];
}

bool subsetVoxelHolds(double current, double spacing) {
  return current > 0.0 && spacing > 0.0 && std::abs(std::log2(spacing / current)) <= 0.5;
}

bool RepresentativeSubset::update(const PointList& map) {
  bool continued = map_size_ > 0 && map.size() >= map_size_ &&
                   hashPoints(map, 0, map_size_, kHashStart) == map_hash_;
  // A map kept whole is judged again each time it has doubled: the first part of a growing map
  // (a few scan lines) can be sparser than the whole. Thinned from then on, it starts afresh.
  if (continued && !thinned_ && voxel_size_ > 0.0 && map.size() >= 2 * decided_size_) {
    RepresentativeSubset again(voxel_size_, min_redundancy_);
    again.update(map);
    if (again.thinned()) {
      *this = std::move(again);
      return false;
    }
    decided_size_ = map.size();
  }
  if (!continued) {
    points_.clear();
    voxels_.clear();
    map_size_ = 0;
    map_hash_ = kHashStart;
    thinned_ = voxel_size_ > 0.0 && std::isfinite(voxel_size_);
  }
  if (thinned_) add(map, map_size_);
  if (!continued && thinned_) {
    redundancy_ = points_.empty()
                      ? 1.0
                      : static_cast<double>(map.size()) / static_cast<double>(points_.size());
    decided_size_ = map.size();
    if (redundancy_ < min_redundancy_) {
      // Whole: only the hash is kept, to recognise the map's continuations.
      thinned_ = false;
      PointList().swap(points_);
      std::unordered_set<uint64_t>().swap(voxels_);
    }
  }
  map_hash_ = hashPoints(map, map_size_, map.size(), map_hash_);
  map_size_ = map.size();
  return continued;
}

void RepresentativeSubset::add(const PointList& map, size_t from) {
  const double inverse_size = 1.0 / voxel_size_;
  for (size_t i = from; i < map.size(); ++i) {
    // Cells 2^21 voxels apart share a key (voxel_cell.hpp): the later one's point is dropped.
    if (voxels_.insert(voxelCellKey(voxelCellOf(map[i], inverse_size))).second) {
      points_.push_back(map[i]);
    }
  }
}

}  // namespace pda_registration
