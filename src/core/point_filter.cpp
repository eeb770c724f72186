#include "pda_registration/core/point_filter.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_map>

#include "pda_registration/core/voxel_cell.hpp"

namespace pda_registration {

size_t removeNonFinitePoints(PointList* points) {
  const size_t before = points->size();
  points->erase(
      std::remove_if(points->begin(), points->end(), [](const Point& p) { return !p.allFinite(); }),
      points->end());
  return before - points->size();
}

PointList voxelDownsample(const PointList& points, double voxel_size) {
  if (!(voxel_size > 0.0) || points.empty()) return points;
  const double inverse_size = 1.0 / voxel_size;
  std::unordered_map<uint64_t, size_t> slot_of_voxel;
  slot_of_voxel.reserve(points.size());
  PointList sums;
  std::vector<int> counts;
  for (const Point& p : points) {
    const auto inserted = slot_of_voxel.emplace(voxelCellKey(voxelCellOf(p, inverse_size)), sums.size());
    if (inserted.second) {
      sums.push_back(p);
      counts.push_back(1);
    } else {
      sums[inserted.first->second] += p;
      ++counts[inserted.first->second];
    }
  }
  for (size_t i = 0; i < sums.size(); ++i) sums[i] /= counts[i];
  return sums;
}

}  // namespace pda_registration
