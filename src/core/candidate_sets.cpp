#include "pda_registration/core/candidate_sets.hpp"

#include <algorithm>
#include <cmath>

namespace pda_registration {
namespace {
constexpr size_t kMaxHints = 64;  // k beyond this (the .cfg allows 50) searches without hints
}  // namespace

size_t CandidateSets::sourcePointsWithCandidates() const {
  size_t count = 0;
  for (size_t j = 0; j < sourceCount(); ++j) count += candidateCount(j) > 0 ? 1 : 0;
  return count;
}

void CandidateSearchBuffers::carryToSuperset(const PointList& subset, const PointList& superset) {
  const size_t m = subset.size();
  if (!have_answers || source != subset.data() || m == 0 || found.size() != m ||
      slots.size() % m != 0) {
    return;
  }
  const size_t stride = slots.size() / m;
  std::vector<size_t> carried_slots(superset.size() * stride);
  std::vector<double> carried_distances(superset.size() * stride);
  std::vector<size_t> carried_found(superset.size(), 0), carried_kept(superset.size(), 0);
  // No answer: a bound of 0 lets no point be answered without a search.
  std::vector<double> carried_bound(superset.size(), 0.0);
  // The subset keeps the superset's order: each of its points is the next equal one (an equal
  // point has the same answer, whichever copy it is matched to).
  size_t j = 0;
  for (size_t c = 0; c < m; ++c) {
    while (j < superset.size() && !(superset[j].array() == subset[c].array()).all()) ++j;
    if (j == superset.size()) return;  // not a subset in order: leave the buffers as they were
    std::copy_n(&slots[c * stride], stride, &carried_slots[j * stride]);
    std::copy_n(&squared_distances[c * stride], stride, &carried_distances[j * stride]);
    carried_found[j] = found[c];
    carried_kept[j] = kept[c];
    carried_bound[j] = outsider_bound[c];
    ++j;
  }
  slots = std::move(carried_slots);
  squared_distances = std::move(carried_distances);
  found = std::move(carried_found);
  kept = std::move(carried_kept);
  outsider_bound = std::move(carried_bound);
  source = superset.data();
}

CandidateSets findCandidateSets(const TargetIndex& target, const PointList& source,
                                const Eigen::Isometry3d& T_target_source, int k, double radius,
                                int threads) {
  CandidateSearchBuffers buffers;
  CandidateSets sets;
  findCandidateSets(target, source, T_target_source, k, radius, threads, &buffers, &sets);
  return sets;
}

namespace {

// Target points kept per source point beyond its k candidates, so that a small move can be
// answered from them: the farther the nearest point outside the kept ones, the larger the move
// that still cannot let another point in.
constexpr size_t kReserve = 4;
// The searches reach this much beyond the radius for the points to keep (candidates stay within
// the radius). A point with fewer than k + kReserve + 1 target points within the radius (at the
// edge of the overlap, in sparse parts of the map) otherwise knew only that the others lay beyond
// the radius, so any move at all could let one in, and it was searched again every run: a seventh
// of a room scan's points in every run at the full radius.
constexpr double kKeepReach = 1.05;

// Answers a source point that moved by `moved` since its last search from the `kept` target
// points that search returned, without a search: every other target point was at least
// sqrt(*outsider_bound) away, so it is now at least that minus `moved` away; if the k-th nearest
// kept point (or, with fewer than k within the radius, the radius) is strictly nearer than that,
// no other point can take its place. On success the kept points are re-measured and re-sorted as
// the tree would return them, *found is how many of them are candidates (the first ones), and
// *outsider_bound is lowered to what this argument still guarantees.
bool answerFromKept(const PointList& target_points, const Point& query, double moved, size_t kept,
                    size_t k, double squared_radius, size_t* indices, double* squared_distances,
                    size_t* found, double* outsider_bound) {
  const double outsider_reach = std::sqrt(*outsider_bound) - moved;
  if (!(outsider_reach > 0.0)) return false;
  for (size_t i = 0; i < kept; ++i) {
    const Point d = query - target_points[indices[i]];
    squared_distances[i] = d.x() * d.x() + d.y() * d.y() + d.z() * d.z();
  }
  // The tree's order: (squared distance, index) lexicographic.
  for (size_t i = 1; i < kept; ++i) {
    for (size_t j = i; j > 0; --j) {
      const bool before = squared_distances[j] < squared_distances[j - 1] ||
                          (squared_distances[j] == squared_distances[j - 1] &&
                           indices[j] < indices[j - 1]);
      if (!before) break;
      std::swap(squared_distances[j], squared_distances[j - 1]);
      std::swap(indices[j], indices[j - 1]);
    }
  }
  size_t within = 0;
  while (within < std::min(kept, k) && squared_distances[within] < squared_radius) ++within;
  const double needed =
      within == k ? std::sqrt(squared_distances[k - 1]) : std::sqrt(squared_radius);
  // A relative margin keeps rounding in the square roots from deciding a tie.
  constexpr double kMargin = 1e-9;
  if (!(needed * (1.0 + kMargin) + kMargin * outsider_reach < outsider_reach)) return false;
  *found = within;
  *outsider_bound = outsider_reach * outsider_reach;
  return true;
}

}  // namespace

void findCandidateSets(const TargetIndex& target, const PointList& source,
                       const Eigen::Isometry3d& T_target_source, int k, double radius, int threads,
                       CandidateSearchBuffers* buffers, CandidateSets* sets) {
  const size_t n = source.size();
  const size_t capacity = static_cast<size_t>(std::max(k, 0));
  // Each search returns the k candidates, kReserve more to keep, and one whose distance bounds
  // every point not kept.
  const size_t stride = capacity + kReserve + 1;
  // Search into fixed-size slots first (parallel, no allocation per point), then compact.
  std::vector<size_t>& slots = buffers->slots;
  std::vector<double>& squared_distances = buffers->squared_distances;
  std::vector<size_t>& found = buffers->found;
  std::vector<size_t>& kept = buffers->kept;
  std::vector<double>& outsider_bound = buffers->outsider_bound;
  // The last call's answers for the same number of points and k are, run after run of one
  // alignment, the answers at a slightly different pose: offered first, they bound the search
  // from the start (any hints give the same answer; unrelated ones only cost their distances).
  const bool hinted = found.size() == n && kept.size() == n && slots.size() == n * stride &&
                      stride <= kMaxHints;
  // The same points, target and k as the last call: a point that moved little is answered from
  // the target points kept for it when answerFromKept proves that no other can enter, which late
  // runs (steps of a fraction of a millimetre) allow for most points.
  const bool same_problem = hinted && buffers->have_answers && buffers->source == source.data() &&
                            buffers->target == &target && buffers->target_size == target.size() &&
                            buffers->k == k && outsider_bound.size() == n;
  const Eigen::Isometry3d T_last = buffers->T_target_source;
  slots.resize(n * stride);
  squared_distances.resize(n * stride);
  found.resize(n);
  kept.resize(n);
  outsider_bound.resize(n);
  const PointList& target_points = target.points();
  const double squared_radius = radius * radius;
  const double reach = kKeepReach * radius;
  std::vector<unsigned char>& answered = buffers->answered;
  answered.assign(n, 0);

#pragma omp parallel for schedule(dynamic, 256) num_threads(std::max(threads, 1))
  for (long long j = 0; j < static_cast<long long>(n); ++j) {
    const Point query = T_target_source * source[j];
    size_t* indices = &slots[j * stride];
    double* distances = &squared_distances[j * stride];
    if (same_problem) {
      const double moved = (query - T_last * source[j]).norm();
      if (answerFromKept(target_points, query, moved, kept[j], capacity, squared_radius, indices,
                         distances, &found[j], &outsider_bound[j])) {
        answered[j] = 1;
        continue;
      }
    }
    size_t hints[kMaxHints];
    const size_t n_hints = hinted ? kept[j] : 0;
    std::copy_n(indices, n_hints, hints);
    const size_t nearest = target.nearestWithinRadius(query, static_cast<int>(stride), reach,
                                                      indices, distances, hints, n_hints);
    // The candidates: those within the radius, a prefix of the answer (nearest first).
    size_t within = 0;
    while (within < std::min(nearest, capacity) && distances[within] < squared_radius) ++within;
    found[j] = within;
    kept[j] = std::min(nearest, stride - 1);
    outsider_bound[j] = nearest == stride ? distances[stride - 1] : reach * reach;
  }
  buffers->source = source.data();
  buffers->target = &target;
  buffers->target_size = target.size();
  buffers->k = k;
  buffers->T_target_source = T_target_source;
  buffers->have_answers = true;
  buffers->answered_from_kept =
      static_cast<size_t>(std::count(answered.begin(), answered.end(), 1));

  sets->offsets.resize(n + 1);
  sets->offsets[0] = 0;
  for (size_t j = 0; j < n; ++j) sets->offsets[j + 1] = sets->offsets[j] + found[j];
  sets->target_indices.resize(sets->offsets[n]);
  sets->points.resize(sets->offsets[n]);
#pragma omp parallel for schedule(static) num_threads(std::max(threads, 1))
  for (long long j = 0; j < static_cast<long long>(n); ++j) {
    std::copy_n(&slots[j * stride], found[j], &sets->target_indices[sets->offsets[j]]);
    for (size_t c = sets->offsets[j]; c < sets->offsets[j + 1]; ++c) {
      sets->points[c] = target_points[sets->target_indices[c]];
    }
  }
}

}  // namespace pda_registration
