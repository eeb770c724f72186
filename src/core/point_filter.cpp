#include "pda_registration/core/point_filter.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "pda_registration/core/voxel_cell.hpp"
#include "pda_registration/core/voxel_slots.hpp"

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
