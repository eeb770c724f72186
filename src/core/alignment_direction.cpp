#include "pda_registration/core/alignment_direction.hpp"

#include <algorithm>

#include "pda_registration/core/target_map.hpp"

namespace pda_registration {

OverlapCounts countInOverlap(const PointList& target, const PointList& source,
                             const Eigen::Isometry3d& T_target_source) {
  PointList moved;
  moved.reserve(source.size());
  for (const Point& p : source) {
    if (p.allFinite()) moved.push_back(T_target_source * p);
  }
  AlignedBox target_box, source_box;
  for (const Point& p : target) target_box.extend(p);
  for (const Point& p : moved) source_box.extend(p);
  AlignedBox common;
  common.min = target_box.min.cwiseMax(source_box.min);
  common.max = target_box.max.cwiseMin(source_box.max);
  const auto inside = [&](const Point& p) { return common.contains(p); };
  OverlapCounts counts;
  counts.target = static_cast<size_t>(std::count_if(target.begin(), target.end(), inside));
  counts.source = static_cast<size_t>(std::count_if(moved.begin(), moved.end(), inside));
  return counts;
}

bool sourceIsDenser(const OverlapCounts& counts) {
  return static_cast<double>(counts.source) >
         kSwapDensityRatio * static_cast<double>(counts.target);
}

}  // namespace pda_registration
