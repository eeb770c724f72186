#pragma once
// A turned start: one more second start (second_start.hpp), from the seed turned about the
// vertical. A tf chain errs mostly in heading (odometry's yaw drifts; gravity fixes roll and
// pitch), and from 20 deg the approach can slide 0.2 deg a run for 30 runs or come to rest in a
// false one with nu at its floor. On the 3-m VLP-16 scan pair of seed 5 from 20 deg / 1 m, 4 of 10
// perturbations came to such rests (2.8-5.9 m off) and two more slid 40-70 runs; from the seed
// turned by -15, -7.5, +7.5 and +15 deg about the sensor, every one of the ten had at least two
// turns that ended at the truth, the fastest in 9-14 runs.
//
// Trying all four cost too much where the first answer was right: on the 20-m VLP-16 pairs (right
// answers with nu at its floor, which asks for second starts) the turns that pointed away from the
// truth wandered at sigma ~0.3 m for 20-30 runs before they came back, 1.6-2.5x the alignment's
// time. So the turns are ranked before any is run, by a test that costs one nearest-neighbour
// query a point: the share of the source that has a target point within the approach's radius
// (the share that has candidates in the approach's first run). Only the best turn is tried, and
// only if it reaches at least the seed's share: a turn that gives fewer points a candidate than
// the seed does points away from the overlap.
//
// A turn that points into the overlap but not at the truth still costs: on RGB-D fragments that
// share a third of the scene (scripts/benchmark_low_overlap, L = 0.4) none of 88 turned starts
// was kept, and 51 were still at sigma 0.18-0.45 m, as wide as the 1-m search, at their 8th run;
// they ran on for 9-79 runs, most into the "unresolved" verdict. A turned start is a guess, not a
// found rotation: one whose residuals still span the search (residualsSpanTheSearch) at its
// kTurnedStartFitRuns-th run is left there. The 15 kept that reach the truth (nine in
// scripts/benchmark, six at L = 0.55, all from 20 deg) were at a fit by then, 6 sigma at most 0.44
// of the radius; at the 5th run one was still at 1.02 (a near search's on the fragments of seed 5
// at L = 0.55).

#include <Eigen/Geometry>
#include <array>

#include "pda_registration/core/point_list.hpp"
#include "pda_registration/core/target_index.hpp"

namespace pda_registration {

/// The turns (degrees, both ways; a tie in share goes to the one listed first): a grid with a
/// 7.5-deg step, so that some turn (or the seed) lies within 3.75 deg of any heading error up to
/// 18.75 deg and within 7.5 deg up to 22.5 deg.
constexpr std::array<double, 4> kTurnDegrees = {7.5, -7.5, 15.0, -15.0};

/// Runs within which a turned start must come to a fit (AttemptOptions::fit_within_runs).
constexpr int kTurnedStartFitRuns = 8;

/// T_initial turned by `degrees` about the target frame's z axis (REP-103: up) through where
/// T_initial puts the source frame's origin (the sensor): the source's position stays, its
/// heading changes.
Eigen::Isometry3d turnedAboutSensor(const Eigen::Isometry3d& T_initial, double degrees);

/// The share of `points` (source frame) that, placed by T, have a target point within `reach`.
double shareWithinReach(const TargetIndex& index, const PointList& points,
                        const Eigen::Isometry3d& T, double reach, int threads);

/// Which turn to try (an index into kTurnDegrees), given each turn's shareWithinReach and the
/// seed's: the turn with the largest share, if it is at least the seed's; -1 for none.
int turnToTry(const std::array<double, kTurnDegrees.size()>& turn_shares, double seed_share);

}  // namespace pda_registration
