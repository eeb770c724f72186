#include "pda_registration/core/point_filter.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "pda_registration/core/voxel_cell.hpp"

namespace pda_registration {

size_t removeNonFinitePoints(PointList* points) {
  const size_t before = points->size();
  points->erase(
      std::remove_if(points->begin(), points->end(), [](const Point& p) { return !p.allFinite(); }),
      points->end());
  return before - points->size();
}

size_t countFinitePoints(const PointList& points) {
  return static_cast<size_t>(
      std::count_if(points.begin(), points.end(), [](const Point& p) { return p.allFinite(); }));
}

namespace {

// The voxel filter's table: open addressing with linear probing (key + 1; 0 = empty), grown at
// half load. A pass over a map of millions of points is its hash lookups; std::unordered_map's
// node per voxel and pointer chase cost more (2M Kinect points: 39-56 -> 28-32 ms, same output).
class VoxelSlots {
 public:
  VoxelSlots() : keys_(kInitialCapacity, 0), slots_(kInitialCapacity) {}

  /// The slot of `key`, or `next` (recorded as the key's slot) when the key is new.
  size_t find(uint64_t key, size_t next, bool* inserted) {
    const uint64_t stored = key + 1;
    size_t i = mix(stored) & mask();
    while (keys_[i] != 0 && keys_[i] != stored) i = (i + 1) & mask();
    *inserted = keys_[i] == 0;
    if (!*inserted) return slots_[i];
    keys_[i] = stored;
    slots_[i] = next;
    if (2 * ++used_ > keys_.size()) grow();
    return next;
  }

 private:
  static constexpr size_t kInitialCapacity = 1024;
  static uint64_t mix(uint64_t k) {  // a 64-bit finaliser (MurmurHash3's)
    k ^= k >> 33;
    k *= 0xff51afd7ed558ccdull;
    k ^= k >> 33;
    return k;
  }
  size_t mask() const { return keys_.size() - 1; }
  void grow() {
    std::vector<uint64_t> keys(2 * keys_.size(), 0);
    std::vector<size_t> slots(keys.size());
    const size_t mask = keys.size() - 1;
    for (size_t j = 0; j < keys_.size(); ++j) {
      if (keys_[j] == 0) continue;
      size_t i = mix(keys_[j]) & mask;
      while (keys[i] != 0) i = (i + 1) & mask;
      keys[i] = keys_[j];
      slots[i] = slots_[j];
    }
    keys_.swap(keys);
    slots_.swap(slots);
  }

  std::vector<uint64_t> keys_;
  std::vector<size_t> slots_;
  size_t used_ = 0;
};

}  // namespace

PointList voxelDownsample(const PointList& points, double voxel_size) {
  if (!(voxel_size > 0.0) || points.empty()) return points;
  const double inverse_size = 1.0 / voxel_size;
  VoxelSlots slots;
  PointList sums;
  std::vector<int> counts;
  // A point often lies in the voxel of the one before it (an RGB-D map in pixel order: 36 % of
  // a simulated 1-cm map on 4.5-cm voxels; a lidar's consecutive points are on other rings):
  // that voxel's slot is kept, without a hash lookup.
  uint64_t last_key = 0;
  size_t last_slot = 0;
  bool have_last = false;
  for (const Point& p : points) {
    const uint64_t key = voxelCellKey(voxelCellOf(p, inverse_size));
    if (have_last && key == last_key) {
      sums[last_slot] += p;
      ++counts[last_slot];
      continue;
    }
    bool inserted = false;
    const size_t slot = slots.find(key, sums.size(), &inserted);
    last_key = key;
    last_slot = slot;
    have_last = true;
    if (inserted) {
      sums.push_back(p);
      counts.push_back(1);
    } else {
      sums[slot] += p;
      ++counts[slot];
    }
  }
  for (size_t i = 0; i < sums.size(); ++i) sums[i] /= counts[i];
  return sums;
}

}  // namespace pda_registration
