#pragma once
// The target cloud and its search index, built once and reused by every run and every alignment
// until the target changes. The index is a set of kd-trees over consecutive ranges of the points,
// so a target that grows by appended points (a SLAM map re-published whole with new points at
// the end) is extended at the cost of its new points: extended() shares the trees of the index it
// extends and builds one over the new range only (merging small trees as they accumulate, like a
// binary counter, so there are O(log n) trees).
//
// A query answers exactly the k nearest points strictly within the radius, ties in distance
// broken by the lower point index: the answer depends only on the points and their order, never
// on how the trees are split, so an extended index and one rebuilt from scratch give identical
// candidate sets.
//
// Every query descends each tree, and two trees over interleaved parts of one room both hold
// neighbours of every query: an extended index answers 30-70 % slower than one tree. fold()
// builds that one tree on a background thread while queries go on; from then on queries use it,
// and an index extended from this one starts from it.

#include <atomic>
#include <cstdint>
#include <memory>
#include <mutex>
#include <vector>

#include "pda_registration/core/point_list.hpp"

namespace pda_registration {

class TargetIndex {
 public:
  /// Takes the (already filtered) target points and builds the index.
  explicit TargetIndex(PointList points);
  ~TargetIndex();
  TargetIndex(const TargetIndex&) = delete;
  TargetIndex& operator=(const TargetIndex&) = delete;

  /// An index of `points`, whose first previous->size() points are previous->points() (the caller
  /// checks, e.g. with sharesPrefix()): the trees of `previous` are shared, only the new points
  /// are indexed. `previous` stays valid and unchanged.
  static std::shared_ptr<const TargetIndex> extended(
      const std::shared_ptr<const TargetIndex>& previous, PointList points);

  /// True when this index was made by extended() from `previous` (directly or in steps).
  bool extends(const TargetIndex& previous) const {
    return this != &previous && lineage_ == previous.lineage_ && size() >= previous.size();
  }
  /// Points whose trees the last extended() built (the new points, plus any merged trees'); the
  /// whole index after a build from scratch.
  size_t pointsLastIndexed() const { return last_indexed_; }

  /// True when the first points().size() entries of `points` equal points() exactly.
  bool sharesPrefix(const PointList& points) const;

  const PointList& points() const { return points_; }
  size_t size() const { return points_.size(); }
  /// How many kd-trees a query descends (1 after a build from scratch or a fold).
  size_t trees() const { return folded_.load(std::memory_order_acquire) ? 1 : trees_.size(); }

  /// Builds one kd-tree over all the points, for the queries from then on (their answers are
  /// unchanged). Safe while other threads query this index; O(n log n), for a background thread.
  /// Returns false when there was nothing to fold (one tree, or folded already) or when `cancel`
  /// became true during the build (then nothing changes).
  bool fold(const std::atomic<bool>* cancel = nullptr) const;

  /// Up to k nearest points strictly within `radius` of `query`, nearest first. Writes indices
  /// and squared distances into the arrays (capacity k) and returns how many were found.
  /// `hints` (n_hints point indices, e.g. this query's answer at a nearby pose) only speed the
  /// search up: offered first, they tighten its bound; the answer is the same for any hints
  /// (indices beyond the index are ignored).
  size_t nearestWithinRadius(const Point& query, int k, double radius, size_t* indices,
                             double* squared_distances, const size_t* hints = nullptr,
                             size_t n_hints = 0) const;

 private:
  struct Tree;
  TargetIndex() = default;
  PointList points_;
  std::vector<std::shared_ptr<const Tree>> trees_;  // consecutive ranges of points_
  // The fold's tree: owned by folded_tree_ (written once, before folded_ is published).
  mutable std::mutex fold_mutex_;
  mutable std::shared_ptr<const Tree> folded_tree_;
  mutable std::atomic<const Tree*> folded_{nullptr};
  uint64_t lineage_ = 0;  // shared by an index and those extended from it
  size_t last_indexed_ = 0;
};

}  // namespace pda_registration
