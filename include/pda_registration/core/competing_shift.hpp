#pragma once
// A second pose that the data support as well as the estimate, along the estimate's least certain
// direction. The covariance (pose_covariance.hpp) is the curvature of the objective around the
// estimate's own peak: it cannot see a second peak a few decimetres away. A car park on another
// day has one: re-parked cars that moved alike hold the scan 29 cm along the road from the truth,
// where the poles and facades that fix that direction fit at the truth; the estimate took the
// cars' peak, and its expected error was 2.1 cm against the 28.8 cm it made.
//
// The probe slides the moved source points along the translation block's principal axis u, over
// the widest reach the registration searched (its radius), and counts at each shift the points
// whose surface faces u (|n.u| > 1/2: their residual changes at least half as fast as the shift)
// and lie within the inlier distance of the target's surface (the nearest target point within
// the final candidate radius, the residual along the normal). Every source point is probed, not
// only those with candidates at the estimate: the points that fit the other pose are the ones the
// estimate left without any (that car park, one point in three probed: with candidates only,
// 87 fit at the truth against 298 at the slide and about 50 at most shifts; every point, 155
// against 217).
// The counts are taken on up to 128 probe points at a fixed stride; while they leave the decision
// within two standard errors of its threshold, on twice as many, up to 1,024 (the car park above
// read 0.61 on one stride's 128 points, 0.46 on another's and on all of its 1,555: below the
// threshold, so the probe sees the truth's peak there but the covariance does not hold it).
// A peak beyond the estimate's own (which ends at the first count below half of its height) that
// rises above its col by at least half as much as the estimate's peak does is a competing pose
// the data do not rule out (prominence, not height: a cluttered room fits 40-50 % of the
// estimate's count at many shifts, by points that land near some surface by chance, and the dips
// measure that background where the peaks are). The col is the higher of the deepest dip between
// the two peaks and the deepest beyond the competitor: a peak falls off on both sides, a count
// that climbs to the end of the reach or stays on a plateau of clutter does not. Where even the
// dip beyond stands as high as the estimate's peak, the dip between the two decides alone.
// The estimate won it by the annealing's path and the weights' choice of which points to believe.
// The covariance then holds the competitor's share p of the two rises times its squared distance
// along u (the mean squared error about the estimate if the competitor were the truth with
// probability p): the estimate stays, its uncertainty says it could be that far off. Only the
// points whose surface faces u count: on a road the ground fits every shift along it and would
// hide the second peak.

#include <Eigen/Geometry>

#include "pda_registration/core/point_list.hpp"
#include "pda_registration/core/target_index.hpp"

namespace pda_registration {

struct CompetingShift {
  Eigen::Vector3d shift = Eigen::Vector3d::Zero();  ///< [length] from the estimate (target frame)
  double share = 0.0;       ///< the competitor's rise / (its rise + the estimate's)
  size_t probe_points = 0;  ///< source points whose surface faces the probed direction
  /// Probe points that fit within the inlier distance, counted above the dip between the two
  /// peaks: at the estimate's own peak, and at the competitor's (0: none found).
  double estimate_support = 0.0;
  double competitor_support = 0.0;
  /// The most prominent peak beyond the estimate's, found or not: its rise above its col relative
  /// to the estimate's (a competitor from 0.5), and where it lies.
  double relative_prominence = 0.0;
  Eigen::Vector3d peak_shift = Eigen::Vector3d::Zero();
  bool found() const { return competitor_support > 0; }
};

struct CompetingShiftSettings {
  double inlier_distance = 0.0;  ///< [length] a probe point fits within this of the surface
  double search_radius = 0.0;    ///< [length] its nearest target point is looked for within this
  double reach = 0.0;            ///< [length] the shifts probed, -reach .. +reach
  /// The facing points counted first, at most, at a power-of-two stride: a count of 100 errs by
  /// about 10, and the probe costs at most 128 x 49 searches.
  size_t first_count_points = 128;
  /// While the counts leave the decision within two standard errors of its threshold, the
  /// stride halves (the points between are counted too), up to this many points: a third of the
  /// first count's error, at most 8 times its cost (kinect_pairwise's probe 50 ms at most).
  size_t recount_points = 1024;
};

/// Probes along the principal axis of `translation_covariance` (target frame) from the estimate
/// T. `normals[j]` is source point j's surface normal in the target frame (zero: none).
CompetingShift findCompetingShift(const PointList& source, const PointList& normals,
                                  const Eigen::Isometry3d& T, const TargetIndex& index,
                                  const Eigen::Matrix3d& translation_covariance,
                                  const CompetingShiftSettings& settings);

/// `covariance` (ROS order) with the competitor's mean squared error share * shift shift^T added
/// to its translation block.
Eigen::Matrix<double, 6, 6> withCompetingShift(const Eigen::Matrix<double, 6, 6>& covariance,
                                               const CompetingShift& competitor);

}  // namespace pda_registration
