#include "pda_registration/core/source_budget.hpp"

#include <algorithm>
#include <iterator>
#include <random>

#include "pda_registration/core/point_filter.hpp"

namespace pda_registration {

PointList applySourceBudget(const PointList& points, size_t max_points) {
  if (max_points == 0 || points.size() <= max_points) return PointList();
  return applySourceBudget(points, max_points, countFinitePoints(points));
}

PointList applySourceBudget(const PointList& points, size_t max_points, size_t finite_points) {
  if (max_points == 0 || points.size() <= max_points) return PointList();
  // Selection sampling: every point equally likely, input order kept, the same subsample for the
  // same cloud (fixed seed), so results are reproducible. A cloud of finite points (the usual
  // case) is sampled in place: a copy of a 2M-point map is 48 MB of memory traffic for nothing.
  std::mt19937_64 generator(0x5eedULL);
  PointList kept;
  kept.reserve(max_points);
  if (finite_points == points.size()) {
    std::sample(points.begin(), points.end(), std::back_inserter(kept), max_points, generator);
    return kept;
  }
  PointList finite;
  finite.reserve(points.size());
  std::copy_if(points.begin(), points.end(), std::back_inserter(finite),
               [](const Point& p) { return p.allFinite(); });
  if (finite.size() <= max_points) return finite;
  std::sample(finite.begin(), finite.end(), std::back_inserter(kept), max_points, generator);
  return kept;
}

}  // namespace pda_registration
