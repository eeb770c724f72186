// The turned start (turned_start.hpp): the seed turned about the sensor, ranked by the share of the
// source that has a target point within the approach's radius, tried after the second starts.
// On the 3-m VLP-16 scan pair of seed 5 from 20 deg it turns four false rests into the truth; on
// the 20-m one of seed 3, where the first answer is right, it heads back to it and is left; on
// fragments that share a third of the scene, one not at a fit within its runs is left there.

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "pda_registration/core/error_metrics.hpp"
#include "pda_registration/core/turned_start.hpp"
#include "pda_registration/simulation/map_simulation.hpp"
#include "test_support/simulated_cases.hpp"
#include "test_support/traced_alignment.hpp"

namespace pda_registration {
namespace {

using testing_support::alignTraced;
using testing_support::attemptNamed;
using testing_support::ranAndWas;
using testing_support::TracedAlignment;

double errorOf(const simulation::SimulatedMaps& maps, const RegistrationResult& r) {
  return poseError(maps.sparse, r.T_target_source, maps.T_target_source).mean_distance;
}

TEST(TurnedStart, TurnsTheHeadingAboutTheSensor) {
  Eigen::Isometry3d seed = Eigen::Isometry3d::Identity();
  seed.linear() = Eigen::AngleAxisd(0.3, Eigen::Vector3d(1.0, 2.0, 3.0).normalized()).matrix();
  seed.translation() = Eigen::Vector3d(4.0, -2.0, 1.5);
  const Eigen::Isometry3d turned = turnedAboutSensor(seed, 7.5);
  // The sensor (the source frame's origin) stays where the seed put it ...
  EXPECT_LT((turned.translation() - seed.translation()).norm(), 1e-12);
  // ... and the source turns by 7.5 deg about the target's z axis.
  const Eigen::AngleAxisd turn(turned.linear() * seed.linear().transpose());
  EXPECT_NEAR(turn.angle(), 7.5 * M_PI / 180.0, 1e-12);
  EXPECT_NEAR(turn.axis().z(), 1.0, 1e-12);
}

TEST(TurnedStart, TriesTheBestTurnOnlyIfItReachesTheSeedsShare) {
  EXPECT_EQ(turnToTry({0.1, 0.3, 0.2, 0.3}, 0.2), 1);  // the best; a tie goes to the first
  EXPECT_EQ(turnToTry({0.1, 0.2, 0.15, 0.05}, 0.2), 1);  // as many as the seed's is enough
  EXPECT_EQ(turnToTry({0.1, 0.19, 0.15, 0.05}, 0.2), -1);  // fewer points in reach: none
}

TEST(TurnedStart, SharesCountThePointsWithATargetPointInReach) {
  PointList target;
  for (int i = 0; i < 10; ++i) target.emplace_back(i, 0.0, 0.0);
  const TargetIndex index(target);
  const PointList points = {Point(0.0, 0.5, 0.0), Point(3.0, 0.9, 0.0), Point(5.0, 1.5, 0.0),
                            Point(20.0, 0.0, 0.0)};
  EXPECT_DOUBLE_EQ(shareWithinReach(index, points, Eigen::Isometry3d::Identity(), 1.0, 1), 0.5);
  Eigen::Isometry3d down = Eigen::Isometry3d::Identity();
  down.translation() = Eigen::Vector3d(-11.0, -0.5, 0.0);  // moves the 4th point in, the 3rd out
  EXPECT_DOUBLE_EQ(shareWithinReach(index, points, down, 1.0, 1), 0.25);
  EXPECT_DOUBLE_EQ(shareWithinReach(index, {}, down, 1.0, 1), 0.0);
}

// The 3-m VLP-16 scan pair of seed 5 (scan_vlp16_vlp16_seed5) from 20 deg / 1 m: from perturbations
// 1, 2, 3 and 10 the alignment ended 2.8-5.9 m off (three false rests reported converged), and the
// second starts from the rotation it found went back there. The turned start reaches the truth
// (5.3 mm) and is kept: after the first attempt (1, 3, 10) or, where the first ended unresolved and
// a wider search came to rest 4.7 m off, in the near search that questions it (2).
TEST(TurnedStart, ReachesTheTruthWhereTheSeedsHeadingRestsFalse) {
  const simulation::SimulatedMaps maps = simulation::simulateMaps(testing_support::scanPairOptions(
      simulation::DenseSensor::kVlp16, 5, Eigen::Vector3d(3.0, 0.0, 31.0)));
  for (const uint64_t seed : {1u, 2u, 3u, 10u}) {
    const TracedAlignment traced = alignTraced(maps, 20.0, 1.0, seed);
    const RegistrationResult& r = traced.result;
    EXPECT_TRUE(r.converged) << "seed " << seed << ": " << r.reason;
    EXPECT_LT(errorOf(maps, r), 0.01) << "seed " << seed;
    const char* turned = seed == 2u ? "near search: turned start" : "turned start";
    EXPECT_TRUE(ranAndWas(traced, turned, /*adopted=*/true)) << "seed " << seed;
  }
}

// The 20-m VLP-16 scan pair of seed 3 from 20 deg / 1 m, perturbations 3 and 5: the first answer
// is right (1.2 cm) with nu at its floor, so second starts run. The best turn points towards the
// truth, and its start comes back to that answer; it is left after two runs, heading back (run into
// the first answer's basin, the four turns cost 1.6-2.5x the alignment's time).
TEST(TurnedStart, IsLeftWhenItHeadsBackToARightFirstAnswer) {
  const simulation::SimulatedMaps maps = simulation::simulateMaps(testing_support::scanPairOptions(
      simulation::DenseSensor::kVlp16, 3, Eigen::Vector3d(20.0, 3.0, 0.0)));
  for (const uint64_t seed : {3u, 5u}) {
    const TracedAlignment traced = alignTraced(maps, 20.0, 1.0, seed);
    const RegistrationResult& r = traced.result;
    EXPECT_TRUE(r.converged) << "seed " << seed << ": " << r.reason;
    EXPECT_LT(errorOf(maps, r), 0.02) << "seed " << seed;
    const AttemptRecord* turned = attemptNamed(traced, "turned start");
    ASSERT_NE(turned, nullptr) << "seed " << seed << ": no turned start ran";
    EXPECT_FALSE(turned->adopted) << "seed " << seed;
    EXPECT_EQ(turned->reason, "second start: heading back to the first result") << "seed " << seed;
    EXPECT_LE(turned->runs, 3) << "seed " << seed;
    EXPECT_TRUE(ranAndWas(traced, "first", /*adopted=*/true)) << "seed " << seed;
  }
}

// The RGB-D fragment pair of seed 2 that shares a third of the office (fragment length 0.4) from
// 2 deg / 0.1 m, perturbation 3: the first answer is right (1.5 cm) with nu at its floor, and the
// best turn points into the overlap but not at the truth. Its start wandered 17 runs at sigma
// 0.23 m, as wide as the 1-m search, into the "unresolved" verdict; now it is left after
// kTurnedStartFitRuns, and the answer is the same.
TEST(TurnedStart, IsLeftWhenItIsNotAtAFitWithinItsRuns) {
  const simulation::SimulatedMaps maps =
      simulation::simulateMaps(testing_support::lowOverlapFragmentOptions(2));
  const TracedAlignment traced = alignTraced(maps, 2.0, 0.1, 3);
  const RegistrationResult& r = traced.result;
  EXPECT_TRUE(r.converged) << r.reason;
  EXPECT_LT(errorOf(maps, r), 0.02);
  EXPECT_TRUE(ranAndWas(traced, "first", /*adopted=*/true));
  const AttemptRecord* turned = attemptNamed(traced, "turned start");
  ASSERT_NE(turned, nullptr) << "no turned start ran";
  EXPECT_FALSE(turned->adopted);
  EXPECT_EQ(turned->reason, "turned start: not at a fit within its runs");
  EXPECT_EQ(turned->runs, kTurnedStartFitRuns);
  EXPECT_GE(6.0 * turned->sigma, RegistrationParameters().radius);
}

}  // namespace
}  // namespace pda_registration
