#include "pda_registration/core/source_budget.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <unordered_set>
#include <vector>

namespace pda_registration {
namespace {

uint64_t cellKey(const Point& p, const Point& origin, double inverse_size) {
  const auto bits = [](double v) { return static_cast<uint64_t>(static_cast<int64_t>(v)) & 0x1FFFFF; };
  const Point c = ((p - origin) * inverse_size).array().floor();
  return (bits(c.x()) << 42) | (bits(c.y()) << 21) | bits(c.z());
}

// Indices of the first point in each occupied cell (input order); stops early past `limit`.
std::vector<size_t> firstPerCell(const PointList& points, const Point& origin, double size,
                                 size_t limit) {
  std::unordered_set<uint64_t> seen;
  seen.reserve(std::min(points.size(), 2 * limit));
  std::vector<size_t> kept;
  const double inverse_size = 1.0 / size;
  for (size_t i = 0; i < points.size() && kept.size() <= limit; ++i) {
    if (!points[i].allFinite()) continue;
    if (seen.insert(cellKey(points[i], origin, inverse_size)).second) kept.push_back(i);
  }
  return kept;
}

}  // namespace

PointList applySourceBudget(const PointList& points, size_t max_points) {
  if (max_points == 0 || points.size() <= max_points) return PointList();
  Point lo = Point::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (const Point& p : points) {
    if (!p.allFinite()) continue;
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  if (!(lo.array() <= hi.array()).all()) return PointList();  // no finite point at all
  // A first guess as if the points covered a surface filling the box's two largest sides; then
  // a bracket [too_small, big_enough] of cell sizes narrowed geometrically until a size keeps
  // between 90 % and 100 % of the budget (or the bracket is tight: the best fit is kept).
  Point extent = (hi - lo).cwiseMax(1e-9);
  std::sort(extent.data(), extent.data() + 3);
  double size = std::sqrt(extent[1] * extent[2] / static_cast<double>(max_points));
  double too_small = 0.0, big_enough = 0.0;
  std::vector<size_t> kept, best;
  for (int attempt = 0; attempt < 40; ++attempt) {
    kept = firstPerCell(points, lo, size, max_points);
    if (kept.size() > max_points) {
      too_small = size;
    } else {
      big_enough = size;
      if (kept.size() > best.size()) best = kept;
      if (kept.size() * 10 >= max_points * 9) break;
    }
    if (too_small > 0.0 && big_enough > 0.0) {
      if (big_enough / too_small < 1.001) break;
      size = std::sqrt(too_small * big_enough);
    } else {
      size *= too_small > 0.0 ? 2.0 : 0.5;
    }
  }
  kept.swap(best);
  if (kept.size() > max_points) {
    // Still over (unlikely): an even stride over the cells found keeps the spread.
    std::vector<size_t> strided;
    for (size_t i = 0; i < max_points; ++i) strided.push_back(kept[i * kept.size() / max_points]);
    kept.swap(strided);
  }
  PointList out;
  out.reserve(kept.size());
  for (const size_t i : kept) out.push_back(points[i]);
  return out;
}

}  // namespace pda_registration
