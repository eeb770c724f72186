#pragma once
// A representative subset of a dense map, for maps sampled much more finely than the sparse
// clouds aligned to them (a Kinect map of 1-cm samples, many frames deep, against a VLP-16 scan).
// The candidate search needs the k nearest samples of the surface around each sparse point, not
// k duplicates within a centimetre: indexing the first map point of every voxel of the sparse
// cloud's own sample spacing keeps the surface sampled at least as finely as the sparse cloud
// sees it, and makes each query several times cheaper (docs/nodelet.md, "Dense map subset").
//
// The subset is the first point of each voxel in map order, so a map that grows by appended
// points (a SLAM map re-published whole) yields the previous subset plus the new points that open
// new voxels: its index is extended, not rebuilt, and equals the subset of the whole map.

#include <cstdint>
#include <unordered_set>

#include "pda_registration/core/point_list.hpp"

namespace pda_registration {

/// The median distance from a point of `cloud` to its nearest distinct neighbour, on up to
/// `samples` points spread over the cloud; 0 when the cloud has fewer than two distinct points.
double sampleSpacing(const PointList& cloud, size_t samples = 1000);

/// Whether a subset decided at `current` [length] still serves a source of spacing `spacing`:
/// within a factor sqrt(2) (the scans of one sensor vary a little; only a real change re-indexes).
bool subsetVoxelHolds(double current, double spacing);

/// Map points per voxel from which a map counts as much finer than the voxel (it samples the
/// surface at least twice as densely): below it, thinning would save little and cost detail.
constexpr double kMuchFinerRedundancy = 2.0;

class RepresentativeSubset {
 public:
  /// A new map is thinned to the first point of each `voxel_size` voxel when it holds at least
  /// `min_redundancy` points per occupied voxel, and kept whole otherwise; a map that continues
  /// the last one keeps that decision (so its index can be extended).
  explicit RepresentativeSubset(double voxel_size, double min_redundancy = kMuchFinerRedundancy)
      : voxel_size_(voxel_size), min_redundancy_(min_redundancy) {}

  /// Takes the whole map. When it starts with the map taken last (same points, same order), only
  /// the appended points are examined and points() grows by those that open a new voxel;
  /// otherwise the subset is made afresh and the decision taken again. Returns true in the
  /// first case. A map kept whole is judged again whenever it has doubled since (its first part
  /// may be sparser than the whole); when that thins it, the subset is new (returns false).
  bool update(const PointList& map);

  double voxelSize() const { return voxel_size_; }
  /// Whether the map is thinned; points() is the subset then (and empty otherwise).
  bool thinned() const { return thinned_; }
  const PointList& points() const { return points_; }
  /// Map points per occupied voxel, when the decision was taken.
  double redundancy() const { return redundancy_; }

 private:
  void add(const PointList& map, size_t from);

  double voxel_size_, min_redundancy_;
  bool thinned_ = false;
  double redundancy_ = 1.0;
  size_t decided_size_ = 0;  // map size at the last decision
  PointList points_;
  std::unordered_set<uint64_t> voxels_;
  size_t map_size_ = 0;    // points of the map taken last
  uint64_t map_hash_ = 0;  // of those points' bytes (FNV-1a)
};

}  // namespace pda_registration
