#include "pda_registration/core/candidate_sets.hpp"

#include <algorithm>

namespace pda_registration {
namespace {
constexpr size_t kMaxHints = 64;  // k beyond this (the .cfg allows 50) searches without hints
}  // namespace

size_t CandidateSets::sourcePointsWithCandidates() const {
  size_t count = 0;
  for (size_t j = 0; j < sourceCount(); ++j) count += candidateCount(j) > 0 ? 1 : 0;
  return count;
}

CandidateSets findCandidateSets(const TargetIndex& target, const PointList& source,
                                const Eigen::Isometry3d& T_target_source, int k, double radius,
                                int threads) {
  CandidateSearchBuffers buffers;
  CandidateSets sets;
  findCandidateSets(target, source, T_target_source, k, radius, threads, &buffers, &sets);
  return sets;
}

void findCandidateSets(const TargetIndex& target, const PointList& source,
                       const Eigen::Isometry3d& T_target_source, int k, double radius, int threads,
                       CandidateSearchBuffers* buffers, CandidateSets* sets) {
  const size_t n = source.size();
  const size_t capacity = static_cast<size_t>(std::max(k, 0));
  // Search into fixed-size slots first (parallel, no allocation per point), then compact.
  std::vector<size_t>& slots = buffers->slots;
  std::vector<double>& squared_distances = buffers->squared_distances;
  std::vector<size_t>& found = buffers->found;
  // The last call's answers for the same number of points and k are, run after run of one
  // alignment, the answers at a slightly different pose: offered first, they bound the search
  // from the start (any hints give the same answer; unrelated ones only cost k distances).
  const bool hinted = found.size() == n && slots.size() == n * capacity && capacity <= kMaxHints;
  slots.resize(n * capacity);
  squared_distances.resize(n * capacity);
  found.resize(n);

#pragma omp parallel for schedule(dynamic, 256) num_threads(std::max(threads, 1))
  for (long long j = 0; j < static_cast<long long>(n); ++j) {
    const Point query = T_target_source * source[j];
    size_t hints[kMaxHints];
    const size_t n_hints = hinted ? std::min(found[j], capacity) : 0;
    std::copy_n(&slots[j * capacity], n_hints, hints);
    found[j] = target.nearestWithinRadius(query, k, radius, &slots[j * capacity],
                                          &squared_distances[j * capacity], hints, n_hints);
  }

  sets->offsets.resize(n + 1);
  sets->offsets[0] = 0;
  for (size_t j = 0; j < n; ++j) sets->offsets[j + 1] = sets->offsets[j] + found[j];
  sets->target_indices.resize(sets->offsets[n]);
  sets->points.resize(sets->offsets[n]);
  const PointList& target_points = target.points();
#pragma omp parallel for schedule(static) num_threads(std::max(threads, 1))
  for (long long j = 0; j < static_cast<long long>(n); ++j) {
    std::copy_n(&slots[j * capacity], found[j], &sets->target_indices[sets->offsets[j]]);
    for (size_t c = sets->offsets[j]; c < sets->offsets[j + 1]; ++c) {
      sets->points[c] = target_points[sets->target_indices[c]];
    }
  }
}

}  // namespace pda_registration
