#include "pda_registration/core/alignment_direction.hpp"

#include <algorithm>
#include <limits>

namespace pda_registration {
namespace {

struct Box {
  Point min = Point::Constant(std::numeric_limits<double>::infinity());
  Point max = Point::Constant(-std::numeric_limits<double>::infinity());
  void add(const Point& p) {
    min = min.cwiseMin(p);
    max = max.cwiseMax(p);
  }
  bool contains(const Point& p) const {
    return (p.array() >= min.array()).all() && (p.array() <= max.array()).all();
  }
};

}  // namespace

OverlapCounts countInOverlap(const PointList& target, const PointList& source,
                             const Eigen::Isometry3d& T_target_source) {
  PointList moved(source.size());
  for (size_t j = 0; j < source.size(); ++j) moved[j] = T_target_source * source[j];
  Box target_box, source_box;
  for (const Point& p : target) target_box.add(p);
  for (const Point& p : moved) source_box.add(p);
  Box common;
  common.min = target_box.min.cwiseMax(source_box.min);
  common.max = target_box.max.cwiseMin(source_box.max);
  OverlapCounts counts;
  counts.target = static_cast<size_t>(std::count_if(
      target.begin(), target.end(), [&](const Point& p) { return common.contains(p); }));
  counts.source = static_cast<size_t>(std::count_if(
      moved.begin(), moved.end(), [&](const Point& p) { return common.contains(p); }));
  return counts;
}

bool sourceIsDenser(const OverlapCounts& counts) {
  return static_cast<double>(counts.source) > kSwapDensityRatio * static_cast<double>(counts.target);
}

}  // namespace pda_registration
