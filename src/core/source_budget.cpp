#include "pda_registration/core/source_budget.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iterator>
#include <random>
#include <utility>
#include <vector>

#include "pda_registration/core/point_filter.hpp"
#include "pda_registration/core/registration_parameters.hpp"
#include "pda_registration/core/voxel_cell.hpp"
#include "pda_registration/core/voxel_slots.hpp"

namespace pda_registration {
namespace {

constexpr uint64_t kSeed = 0x5eedULL;
// The budget first keeps a random share of a very large source, about this many times the
// budget, so that a 2M-point map costs one pass to pick them and later passes over 120k points
// (every later step is a few passes over the pool: 16 times the budget cost 15 ms on a 353k-point
// RGB-D fragment, 8 times about half that). The share is the same everywhere, so a region loses
// weight to it only where it holds under an eighth of the points its space would earn (a lidar
// map of millions, its farthest parts).
constexpr size_t kPoolFactor = 8;
// The voxel size is searched for on a random probe of about this many times the budget, whose
// passes are cheap (a uniform cloud's voxels hold four of its points there on average); then the
// grid is laid over the whole pool, and moved once more if the pool's count is off by more than
// the tolerance (a probe misses voxels of the sparsest parts, which is what the budget favours).
constexpr size_t kProbeFactor = 4;
constexpr double kCountTolerance = 0.2;
constexpr int kProbePasses = 6;
// Salts of the fixed-seed hashes that pick the pool, the voxels that keep one point more, each
// voxel's points and the probe.
constexpr uint64_t kPoolSalt = 1, kVoxelSalt = 2, kRankSalt = 3, kProbeSalt = 4;

// What one budget call works in, kept by each thread between calls: fresh pages cost a fault
// each on the machines measured here (registration_workspace.hpp), and a budget of a large map
// fills several megabytes.
struct BudgetScratch {
  VoxelSlots slots;
  std::vector<uint32_t> pool, probe, slot_of, counts, start, filled;
  std::vector<std::pair<uint64_t, uint32_t>> members, fuller;
  std::vector<unsigned char> one_more_here, keep;
};

BudgetScratch& scratch() {
  thread_local BudgetScratch kept;
  return kept;
}

// A fixed-seed hash of (salt, i) (splitmix64's finaliser): a uniform 64-bit number per point.
uint64_t hashOf(uint64_t salt, uint64_t i) {
  uint64_t z = i + kSeed + salt * 0xD1B54A32D192ED03ULL + 0x9E3779B97F4A7C15ULL;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  return z ^ (z >> 31);
}

// Whether hash h falls in the first `share` of the 64-bit range (share in [0, 1]).
bool within(uint64_t h, double share) {
  return share >= 1.0 || static_cast<double>(h) < share * 18446744073709551616.0;
}

// The voxel slot of each point `members` names, on a grid `size` wide; returns how many voxels
// are occupied. The table starts with room for about `expected` voxels (the count searched for,
// not the points: a table sized to the points left the cache on every lookup, 4x slower).
size_t voxelSlotsOf(const PointList& points, const std::vector<uint32_t>& members, double size,
                    size_t expected, VoxelSlots* table, std::vector<uint32_t>* slot_of) {
  VoxelSlots& slots = *table;
  slots.clear(expected);
  const double inverse = 1.0 / size;
  slot_of->resize(members.size());
  for (size_t m = 0; m < members.size(); ++m) {
    bool inserted = false;
    (*slot_of)[m] = static_cast<uint32_t>(slots.find(
        voxelCellKey(voxelCellOf(points[members[m]], inverse)), slots.size(), &inserted));
  }
  return slots.size();
}

// One step of the voxel search: a surface's count goes as size^-2, a volume's (foliage) as
// size^-3, a scan line's as size^-1; the slope is read from the last two grids (a secant in
// log-log) once there are two.
struct VoxelSearch {
  double size = 0.0, count = 0.0, last_size = 0.0, last_count = 0.0, slope = -2.0;

  void measured(double new_size, double new_count) {
    last_size = size;
    last_count = count;
    size = new_size;
    count = new_count;
    if (last_size > 0.0 && last_count != count && last_size != size) {
      slope = std::clamp(std::log(count / last_count) / std::log(size / last_size), -3.0, -0.5);
    }
  }
  bool near(size_t wanted) const {
    return std::abs(count - static_cast<double>(wanted)) <= kCountTolerance * wanted;
  }
  double next(size_t wanted) const {
    return size * std::pow(static_cast<double>(wanted) / count, 1.0 / slope);
  }
};

// The voxel slots of the pool's points on a grid where about `wanted` voxels are occupied;
// returns how many are. Searched on `probe` (a random part of the pool, or the pool itself),
// then laid over the pool.
size_t voxelsForCount(const PointList& points, const std::vector<uint32_t>& pool,
                      const std::vector<uint32_t>& probe, size_t wanted, BudgetScratch* work) {
  Point low = points[probe.front()], high = low;
  for (uint32_t m : probe) {
    low = low.cwiseMin(points[m]);
    high = high.cwiseMax(points[m]);
  }
  VoxelSearch search;
  double size = std::max((high - low).maxCoeff(), 1e-6) / std::sqrt(static_cast<double>(wanted));
  for (int pass = 0; pass < kProbePasses; ++pass) {
    search.measured(size, static_cast<double>(voxelSlotsOf(points, probe, size, wanted,
                                                           &work->slots, &work->slot_of)));
    if (search.near(wanted)) break;
    size = search.next(wanted);
  }
  if (&probe == &pool) return static_cast<size_t>(search.count);
  size_t count = voxelSlotsOf(points, pool, search.size, wanted, &work->slots, &work->slot_of);
  if (std::abs(static_cast<double>(count) - static_cast<double>(wanted)) >
      kCountTolerance * wanted) {
    search.measured(search.size, static_cast<double>(count));  // the pool's count; same slope
    count = voxelSlotsOf(points, pool, search.next(wanted), wanted, &work->slots, &work->slot_of);
  }
  return count;
}

// The level c at which keeping min(n_v, c) points of every voxel v keeps `wanted` points in all
// (water-filling: the densest voxels are thinned first), as floor(c) and how many of the voxels
// fuller than that keep one point more.
void waterLevel(std::vector<uint32_t> counts, size_t wanted, size_t* level, size_t* one_more) {
  std::sort(counts.begin(), counts.end());
  size_t below = 0;  // points of the voxels already under the level
  for (size_t v = 0; v < counts.size(); ++v) {
    const size_t fuller = counts.size() - v;  // voxels from v on, each holding >= counts[v]
    if (below + fuller * counts[v] >= wanted) {
      *level = (wanted - below) / fuller;
      *one_more = (wanted - below) % fuller;
      return;
    }
    below += counts[v];
  }
  *level = counts.empty() ? 0 : counts.back();
  *one_more = 0;
}

// `max_points` of the points `pool` names (finite, more than max_points, in input order): every
// voxel of the grid on which about max_points voxels are occupied keeps its points up to a common
// level, those it keeps in a fixed random order; input order kept.
PointList spreadOverSpace(const PointList& points, const std::vector<uint32_t>& pool,
                          size_t max_points) {
  BudgetScratch& work = scratch();
  const double probe_share =
      static_cast<double>(kProbeFactor * max_points) / static_cast<double>(pool.size());
  work.probe.clear();
  if (probe_share < 1.0) {
    for (size_t p = 0; p < pool.size(); ++p) {
      if (within(hashOf(kProbeSalt, p), probe_share)) work.probe.push_back(pool[p]);
    }
  }
  const bool probed = work.probe.size() > max_points;
  const size_t voxels = voxelsForCount(points, pool, probed ? work.probe : pool, max_points, &work);
  const std::vector<uint32_t>& slot_of = work.slot_of;
  std::vector<uint32_t>& counts = work.counts;
  counts.assign(voxels, 0);
  for (uint32_t slot : slot_of) ++counts[slot];
  size_t level = 0, one_more = 0;
  waterLevel(counts, max_points, &level, &one_more);
  // The pool's points grouped by voxel (a counting sort), each with its rank, so that each voxel
  // keeps its share in rank order.
  std::vector<uint32_t>& start = work.start;
  start.assign(voxels + 1, 0);
  for (size_t v = 0; v < voxels; ++v) start[v + 1] = start[v] + counts[v];
  std::vector<std::pair<uint64_t, uint32_t>>& members = work.members;
  members.resize(pool.size());
  std::vector<uint32_t>& filled = work.filled;
  filled.assign(start.begin(), start.end() - 1);
  for (size_t p = 0; p < pool.size(); ++p) {
    members[filled[slot_of[p]]++] = {hashOf(kRankSalt, p), static_cast<uint32_t>(p)};
  }
  // The voxels fuller than the level that keep one point more: `one_more` of them at random.
  std::vector<unsigned char>& one_more_here = work.one_more_here;
  one_more_here.assign(voxels, 0);
  if (one_more > 0) {
    std::vector<std::pair<uint64_t, uint32_t>>& fuller = work.fuller;
    fuller.clear();
    for (size_t v = 0; v < voxels; ++v) {
      if (counts[v] > level) fuller.emplace_back(hashOf(kVoxelSalt, v), static_cast<uint32_t>(v));
    }
    std::nth_element(fuller.begin(), fuller.begin() + static_cast<std::ptrdiff_t>(one_more),
                     fuller.end());
    for (size_t f = 0; f < one_more; ++f) one_more_here[fuller[f].second] = 1;
  }
  std::vector<unsigned char>& keep = work.keep;
  keep.assign(pool.size(), 0);
  for (size_t v = 0; v < voxels; ++v) {
    const size_t share = std::min<size_t>(counts[v], level) + one_more_here[v];
    const auto first = members.begin() + start[v];
    const auto last = members.begin() + start[v + 1];
    const auto kept_end = first + static_cast<std::ptrdiff_t>(share);
    if (share < counts[v]) std::nth_element(first, kept_end, last);
    for (auto m = first; m != kept_end; ++m) keep[m->second] = 1;
  }
  PointList kept;
  kept.reserve(max_points);
  for (size_t p = 0; p < pool.size(); ++p) {
    if (keep[p]) kept.push_back(points[pool[p]]);
  }
  return kept;
}

}  // namespace

PointList randomSubsample(const PointList& points, size_t max_points) {
  if (max_points == 0 || points.size() <= max_points) return PointList();
  return randomSubsample(points, max_points, countFinitePoints(points));
}

PointList randomSubsample(const PointList& points, size_t max_points, size_t finite_points) {
  if (max_points == 0 || points.size() <= max_points) return PointList();
  // Selection sampling: every point equally likely, input order kept, the same subsample for the
  // same cloud (fixed seed), so results are reproducible. A cloud of finite points (the usual
  // case) is sampled in place: a copy of a 2M-point map is 48 MB of memory traffic for nothing.
  std::mt19937_64 generator(kSeed);
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

PointList spatialSubsample(const PointList& points, size_t max_points) {
  if (max_points == 0 || points.size() <= max_points) return PointList();
  return spatialSubsample(points, max_points, countFinitePoints(points));
}

PointList spatialSubsample(const PointList& points, size_t max_points, size_t finite_points) {
  if (max_points == 0 || points.size() <= max_points) return PointList();
  // The pool, by input index: the finite points, or a random share of them (picked by the hash of
  // each one's place among the finite points, so that NaNs in between change nothing else).
  const double pool_share =
      static_cast<double>(kPoolFactor * max_points) / static_cast<double>(finite_points);
  std::vector<uint32_t>& pool = scratch().pool;
  pool.clear();
  if (pool_share >= 1.0) {
    for (size_t i = 0; i < points.size(); ++i) {
      if (points[i].allFinite()) pool.push_back(static_cast<uint32_t>(i));
    }
  } else {
    // A random share of the finite points, each kept with probability pool_share: the gaps
    // between kept ones are geometric, so only the kept ones are drawn (a 2M-point map: 120k
    // draws, not 2M). Counted in places among the finite points, so that NaNs in between change
    // nothing else.
    const double log_keep_not = std::log1p(-pool_share);
    uint64_t draws = 0;
    const auto nextKept = [&](double after) {
      const double u = (static_cast<double>(hashOf(kPoolSalt, draws++) >> 11) + 0.5) * 0x1.0p-53;
      return after + std::floor(std::log(u) / log_keep_not);
    };
    double next = nextKept(0.0);
    if (finite_points == points.size()) {
      for (; next < static_cast<double>(points.size()); next = nextKept(next + 1.0)) {
        pool.push_back(static_cast<uint32_t>(next));
      }
    } else {
      uint64_t finite_rank = 0;
      for (size_t i = 0; i < points.size() && next < static_cast<double>(finite_points); ++i) {
        if (!points[i].allFinite()) continue;
        if (static_cast<double>(finite_rank++) == next) {
          pool.push_back(static_cast<uint32_t>(i));
          next = nextKept(next + 1.0);
        }
      }
    }
  }
  if (pool.size() <= max_points) {  // few finite points (or, by chance, a small random share)
    PointList kept;
    kept.reserve(pool.size());
    for (uint32_t i : pool) kept.push_back(points[i]);
    return kept;
  }
  return spreadOverSpace(points, pool, max_points);
}

bool prepareAlignedSource(const PointList& input, size_t finite_points,
                          const RegistrationParameters& parameters, PointList* source) {
  const size_t budget =
      parameters.max_source_points > 0 ? static_cast<size_t>(parameters.max_source_points) : 0;
  const auto subsample = [&](const PointList& points, size_t finite) {
    return parameters.spread_source_budget ? spatialSubsample(points, budget, finite)
                                           : randomSubsample(points, budget, finite);
  };
  // A source beyond the budget (and not voxelised first) is sampled straight from the input: the
  // same subset as from a filtered copy, without copying a map of millions of points.
  if (budget > 0 && !(parameters.source_voxel_size > 0.0) && finite_points > budget) {
    *source = subsample(input, finite_points);
    return true;
  }
  *source = input;
  removeNonFinitePoints(source);
  if (parameters.source_voxel_size > 0.0) {
    *source = voxelDownsample(*source, parameters.source_voxel_size);
  }
  if (budget == 0) return false;
  PointList kept = subsample(*source, source->size());
  if (kept.empty()) return false;  // within the budget already
  *source = std::move(kept);
  return true;
}

}  // namespace pda_registration
