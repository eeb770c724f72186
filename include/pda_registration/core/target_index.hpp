#pragma once
// The target cloud and its kd-tree, built once and reused by every run and every alignment
// until the target changes (building it dominates the cost of a single k-NN pass).

#include <memory>

#include "pda_registration/core/point_list.hpp"

namespace pda_registration {

class TargetIndex {
 public:
  /// Takes the (already filtered) target points and builds the kd-tree.
  explicit TargetIndex(PointList points);
  ~TargetIndex();
  TargetIndex(const TargetIndex&) = delete;
  TargetIndex& operator=(const TargetIndex&) = delete;

  const PointList& points() const { return points_; }
  size_t size() const { return points_.size(); }

  /// Up to k nearest points strictly within `radius` of `query`, nearest first. Writes indices
  /// and squared distances into the arrays (capacity k) and returns how many were found.
  size_t nearestWithinRadius(const Point& query, int k, double radius, size_t* indices,
                             double* squared_distances) const;

 private:
  struct KdTree;
  PointList points_;
  std::unique_ptr<KdTree> tree_;
};

}  // namespace pda_registration
