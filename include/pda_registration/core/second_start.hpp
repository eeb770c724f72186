#pragma once
// A second start for a result that rests on a false minimum after a large correction. From 20 deg
// and 1 m off, the approach corrects rotation and translation together, and on a map with a
// repeated structure (an office walkway lined with desks) the source can slide along it while it
// turns and come to rest turned right but one repeat off. Such a rest fits half the points and not
// the other half: the Student-t's nu, estimated by EM, ends at its floor (all 20 converged
// failures of simulated RGB-D fragment pairs from 20 deg; their correct results ended at 1.5-3.2).
// Started again from the rotation it found, the same alignment reaches the right pose, and the
// result that fits more of the overlap (both measured with one yardstick) is kept. align() asks
// as soon as the first attempt's refine runs leave nu at its floor (second_start_attempts.cpp).
//
// Where to put the source for that start depends on where the seed's error pivots, which is not
// known: a tf chain errs by a rotation about the sensor plus a translation, so the seed puts the
// source frame's origin (the sensor) off by the translation alone while it swings the source's
// centroid, metres away, by the rotation too (20 deg at 8 m: 2.8 m); a seed that errs about the
// data puts the centroid closer. So there are two starts, tried in turn until one is kept: the
// found rotation with the source frame's origin where the seed put it, then with the centroid
// there. A survey (pda_align, the benchmark's perturbations 1-10 at 10 and 20 deg: seven RGB-D
// fragment layouts, four held-out ones, lidar scenes, scan pairs, offices, the shared cases): of
// 39 results that warranted a second start, 25 stayed wrong with the centroid start alone; the
// origin start first put 14 of them right (0.7-2.7 mm) and none wrong that the centroid start had
// put right; the centroid start first, then the origin, 11 (it kept three other false rests that
// were better supported than the first).

#include <Eigen/Geometry>
#include <array>

#include "pda_registration/core/point_list.hpp"
#include "pda_registration/core/registration_parameters.hpp"
#include "pda_registration/core/registration_result.hpp"

namespace pda_registration {

/// Where the second starts begin, in the order they are tried: the rotation T_found holds, with
/// (0) the source frame's origin where T_initial put it, (1) `centroid` (of the source points,
/// source frame) where T_initial put it.
std::array<Eigen::Isometry3d, 2> secondStartPoses(const Eigen::Isometry3d& T_found,
                                                  const Eigen::Isometry3d& T_initial,
                                                  const Point& centroid);

/// Whether `first`, converged from T_initial, warrants a second start: nu (estimated) ended at its
/// floor, and the first alignment moved the centroid further than its final candidate radius, so
/// that the second start is another hypothesis and not the basin the first one already searched.
bool secondStartWarranted(const RegistrationResult& first, const RegistrationParameters& p,
                          const Eigen::Isometry3d& T_initial, const Point& centroid,
                          double final_radius);

/// The first result's neighbourhood: where the source points lie, in root mean square, within
/// the first alignment's final candidate radius of where the first result put them. A second
/// start that enters it is in the basin the first one already searched (its last runs searched
/// that far around it), and is abandoned: the same rest, found again, is not worth a second settle
/// and refine. In root mean square, not for every point: a lidar scan's farthest return is 100 m
/// out where its points' RMS distance is 27 m, and a bound on the farthest point kept a second
/// start of a right VLP-16 result running for 11 more runs at 0.2-0.5 deg from it.
struct FirstResultBasin {
  Eigen::Isometry3d T_found = Eigen::Isometry3d::Identity();
  Point centroid = Point::Zero();  ///< of the source points (source frame)
  double source_rms_radius = 0.0;  ///< the RMS distance of the source points from the centroid
  double final_radius = 0.0;

  /// The source points' RMS displacement between T_found and T is below final_radius.
  bool contains(const Eigen::Isometry3d& T) const { return near(T_found, T); }
  /// The source points' RMS displacement between a and b is below final_radius (bounded by the
  /// centroid's shift and the angle between them times source_rms_radius, in quadrature): two
  /// second starts that near are one hypothesis.
  bool near(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) const;
};

/// Whether a second start heads back to the first result's basin: the source points' RMS
/// displacement from where the first result puts them (`apart_now`) has halved since the start
/// (`apart_at_start`), counted from its second run. Such a start comes to the first result again,
/// only slower: on the 20-m VLP-16 scan pairs from 10-20 deg, turned starts (turned_start.hpp)
/// that ended in the right first result's basin took 3-29 runs to enter it. Screened on every
/// benchmark group (1,950 trials, all four turns tried), leaving at half the distance cost one
/// success (1,936 -> 1,935) and took 1.6 % off the time of all trials.
bool headingBack(double apart_at_start, double apart_now);

/// The yardstick two results' support is measured with (supportFractionAt, final_statistics.hpp):
/// inlier_sigmas times the smaller sigma. Each result's own favours the one whose residuals are
/// wider: an RGB-D fragment pair sharing a third of the office came to rest 2.73 m off at sigma
/// 3.8 cm, and its second start, at the truth with sigma 1.8 cm, fitted less of the overlap
/// within its own 3 sigma than the false rest within its 3 sigma, and was dropped.
double commonYardstick(const RegistrationParameters& p, double sigma_first, double sigma_second);

/// Whether the second start's result replaces the first's: converged, and a larger share of the
/// overlap fits it than fits the first, both measured with one yardstick (commonYardstick; the
/// false rests' support was 0.44-0.54 where the right pose's was 0.63).
bool secondStartIsBetter(const RegistrationResult& second, double second_support,
                         double first_support);

}  // namespace pda_registration
