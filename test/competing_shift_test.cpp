// A second pose along the estimate's least certain direction (competing_shift.hpp): found where a
// repeat of the scene fits as well, not found where there is none, and taken into the covariance
// end to end on the car park on another day, whose estimate rests on the wrong one of two peaks.
#include "pda_registration/core/competing_shift.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "pda_registration/core/pose_covariance.hpp"
#include "pda_registration/simulation/map_simulation.hpp"
#include "test_support/simulated_cases.hpp"

namespace pda_registration {
namespace {

// A wall x = x0 sampled every `spacing` over 4 m x 2 m (y from -2 m to `y_end`).
void addWall(double x0, double spacing, PointList* points, double y_end = 2.0) {
  for (double y = -2.0; y <= y_end; y += spacing) {
    for (double z = 0.0; z <= 2.0; z += spacing) points->push_back(Point(x0, y, z));
  }
}

struct WallCase {
  PointList source, normals;
  PointList target;
};

// The source sees one wall; the target holds it and, if `repeat` > 0, a parallel wall that far
// behind it (a row of parked cars, the next desk of a walkway).
WallCase wallCase(double repeat) {
  WallCase c;
  addWall(0.0, 0.1, &c.source);
  c.normals.assign(c.source.size(), Point(1.0, 0.0, 0.0));
  addWall(0.0, 0.05, &c.target);
  if (repeat > 0.0) addWall(repeat, 0.05, &c.target);
  return c;
}

CompetingShiftSettings wallSettings() {
  CompetingShiftSettings s;
  s.inlier_distance = 0.03;
  s.search_radius = 0.25;
  s.reach = 1.0;
  return s;
}

// The covariance's least certain direction: x (across the walls).
Eigen::Matrix3d weakAlongX() {
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Identity() * 1e-6;
  covariance(0, 0) = 1e-4;
  return covariance;
}

TEST(CompetingShift, FindsAParallelWallThatFitsAsWellAndTakesItIntoTheCovariance) {
  const WallCase c = wallCase(0.4);
  TargetIndex index(c.target);
  const CompetingShift found = findCompetingShift(
      c.source, c.normals, Eigen::Isometry3d::Identity(), index, weakAlongX(), wallSettings());
  ASSERT_TRUE(found.found());
  EXPECT_NEAR(found.shift.x(), 0.4, 0.035);  // within a step (reach / 32)
  EXPECT_NEAR(found.shift.y(), 0.0, 1e-9);
  EXPECT_NEAR(found.share, 0.5, 0.05);  // every probed point fits either wall
  EXPECT_GE(found.probe_points, 32u);

  Eigen::Matrix<double, 6, 6> covariance = Eigen::Matrix<double, 6, 6>::Identity() * 1e-6;
  const Eigen::Matrix<double, 6, 6> widened = withCompetingShift(covariance, found);
  EXPECT_NEAR(widened(0, 0), 1e-6 + found.share * found.shift.squaredNorm(), 1e-12);
  EXPECT_EQ((widened - covariance).bottomRightCorner(3, 3).norm(), 0.0);  // rotations untouched
}

TEST(CompetingShift, NoneWhereTheSceneHasNoRepeatOrTheDirectionIsNotTheWeakOne) {
  const WallCase single = wallCase(0.0);
  TargetIndex single_index(single.target);
  EXPECT_FALSE(findCompetingShift(single.source, single.normals, Eigen::Isometry3d::Identity(),
                                  single_index, weakAlongX(), wallSettings())
                   .found());
  // With the repeat, but y the least certain direction: no point's surface faces it.
  const WallCase repeated = wallCase(0.4);
  TargetIndex repeated_index(repeated.target);
  Eigen::Matrix3d weak_along_y = Eigen::Matrix3d::Identity() * 1e-6;
  weak_along_y(1, 1) = 1e-4;
  const CompetingShift along_y =
      findCompetingShift(repeated.source, repeated.normals, Eigen::Isometry3d::Identity(),
                         repeated_index, weak_along_y, wallSettings());
  EXPECT_FALSE(along_y.found());
  EXPECT_EQ(along_y.probe_points, 0u);
  // Beyond the reach the registration searched, a repeat is not a competitor.
  const WallCase far = wallCase(1.5);
  TargetIndex far_index(far.target);
  EXPECT_FALSE(findCompetingShift(far.source, far.normals, Eigen::Isometry3d::Identity(),
                                  far_index, weakAlongX(), wallSettings())
                   .found());
}

// Beyond the estimate's peak the source moves into clutter that fits more than half of its
// points at every shift (walls 5 cm apart over half its width, from 0.35 m to past the reach,
// like shelves or a hedge): the counts climb back to that level and stay there to the end of the
// reach. That is the background the clutter sets, not a second pose (RGB-D fragments sharing a
// third of the scene read so: sigma 0.58 m against a 7-mm error); a second wall alone at 0.7 m
// still is one.
TEST(CompetingShift, NoneWhereTheCountsClimbIntoClutterThatFitsEveryShift) {
  WallCase c = wallCase(0.0);
  for (double x = 0.35; x <= 1.3; x += 0.05) addWall(x, 0.05, &c.target, 0.0);
  TargetIndex index(c.target);
  const CompetingShift into_clutter = findCompetingShift(
      c.source, c.normals, Eigen::Isometry3d::Identity(), index, weakAlongX(), wallSettings());
  EXPECT_GE(into_clutter.probe_points, 32u);
  EXPECT_FALSE(into_clutter.found()) << "a competitor at " << into_clutter.shift.x() << " m";

  WallCase peaked = wallCase(0.7);
  TargetIndex peaked_index(peaked.target);
  const CompetingShift found =
      findCompetingShift(peaked.source, peaked.normals, Eigen::Isometry3d::Identity(),
                         peaked_index, weakAlongX(), wallSettings());
  ASSERT_TRUE(found.found());
  EXPECT_NEAR(found.shift.x(), 0.7, 0.035);
}

// Which points a fixed stride picks must not decide: a repeat wall 0.5 m behind that holds only
// some of the 861 source points' counterparts (the rest see nothing within the search radius
// there). Where the first count's points read a competitor within two standard errors of the
// threshold, more points decide: picked points that fit 60 % against 8 % of all of them is no
// competitor, 40 % against 92 % is one.
TEST(CompetingShift, ADecisionNearItsThresholdIsCountedOnMorePointsNotLeftToAStridesPick) {
  CompetingShiftSettings settings = wallSettings();
  settings.search_radius = 0.05;  // half the source's spacing: only a counterpart is found
  for (const bool picked_mostly : {true, false}) {
    WallCase c = wallCase(0.0);
    const size_t n = c.source.size();
    ASSERT_GT(n, 4 * settings.first_count_points);
    ASSERT_LE(n, settings.recount_points);
    // The first count's stride: the smallest power of two that leaves at most 128 points.
    size_t stride = 1;
    while (stride * settings.first_count_points < n) stride *= 2;
    size_t picked = 0, fitting = 0;
    for (size_t j = 0; j < n; ++j) {
      const bool is_picked = j % stride == 0;
      // Of the picked points every fifth three (60 %) or two (40 %); of the others none or all.
      const bool counterpart =
          is_picked ? (picked++ % 5) < (picked_mostly ? 3u : 2u) : !picked_mostly;
      if (!counterpart) continue;
      c.target.push_back(c.source[j] + Point(0.5, 0.0, 0.0));
      ++fitting;
    }
    TargetIndex index(c.target);
    const CompetingShift probed = findCompetingShift(
        c.source, c.normals, Eigen::Isometry3d::Identity(), index, weakAlongX(), settings);
    const double share_of_all = static_cast<double>(fitting) / static_cast<double>(n);
    if (picked_mostly) {
      ASSERT_LT(share_of_all, 0.15);
      EXPECT_FALSE(probed.found()) << "a competitor at " << probed.shift.x() << " m";
      EXPECT_LT(probed.relative_prominence, 0.4);
    } else {
      ASSERT_GT(share_of_all, 0.85);
      ASSERT_TRUE(probed.found());
      EXPECT_NEAR(probed.shift.x(), 0.5, 0.025);
      EXPECT_GT(probed.relative_prominence, 0.6);
    }
    EXPECT_NEAR(probed.peak_shift.x(), 0.5, 0.025);
  }
}

// The car park on another day (pda_simulate --seed 6 --scene outdoor --scene-changes 0.6; see
// lattice_registration_test's ACarParkOnAnotherDay... for the spread budget that aligns it): with
// the defaults the estimate rests 28.8 cm along the road, on the re-parked cars' peak, and the
// curvature there says 2.1 cm (13.8x too confident). The probe finds the truth's peak where the
// error lies, but on all 1,555 facing points it stands 0.46 as prominent as the estimate's, below
// the competitor's 0.5: the covariance does not hold it. (Until the recount, one stride's pick of
// 128 points read 0.61 and held it: chance, not a measurement.)
TEST(CompetingShift, ACarParkOnAnotherDayShowsTheTruthsPeakBelowTheCompetitorsThreshold) {
  simulation::MapSimulationOptions options =
      testing_support::carParkOptions(simulation::DenseSensor::kLidar64, false);
  options.seed = 6;
  options.scene_change_share = 0.6;
  const simulation::SimulatedMaps maps = simulation::simulateMaps(options);
  for (const uint64_t seed : {1u, 2u}) {
    RegistrationResult result;
    testing_support::alignedError(maps, RegistrationParameters(), 5.0, 0.25, seed, &result);
    const Eigen::Vector3d t_error =
        result.T_target_source.translation() - maps.T_target_source.translation();
    ASSERT_GT(t_error.norm(), 0.1) << "the slide this test is about is gone: perturbation seed "
                                   << seed << " lands " << t_error.norm() << " m off";
    EXPECT_GT(result.competing_prominence, 0.35) << "perturbation seed " << seed;
    EXPECT_LT(result.competing_prominence, 0.5) << "perturbation seed " << seed;
    EXPECT_EQ(result.competing_shift, 0.0) << "perturbation seed " << seed;
  }
}

// RGB-D fragments that share a third of the scene (layout 4, each 40 % of the walkway), from 2
// deg: two thirds of the probe points have no counterpart and fit here and there by chance, so
// beyond the estimate's peak the counts climb back towards it (15 beside its 73, 53 at 0.92 m).
// With the dip between the peaks as the only col that read as a competitor of share 0.4: an
// expected error of 0.58 m against a 7-mm one. No second pose falls off on both sides here, and
// the covariance stays within the bound on the cautious side too (sigma at most 3x the
// error).
TEST(CompetingShift, FragmentsThatShareAThirdOfTheSceneReadNoneFromTheBackgroundOfChanceFits) {
  simulation::MapSimulationOptions options = testing_support::rgbdFragmentOptions(4);
  options.fragment_length = 0.4;
  const simulation::SimulatedMaps maps = simulation::simulateMaps(options);
  RegistrationResult result;
  const double error =
      testing_support::alignedError(maps, RegistrationParameters(), 2.0, 0.1, 1, &result);
  ASSERT_TRUE(result.converged) << result.reason;
  ASSERT_LT(error, 0.02) << "the alignment this test is about fails";
  const double t_error =
      (result.T_target_source.translation() - maps.T_target_source.translation()).norm();
  EXPECT_EQ(result.competing_shift, 0.0) << "share " << result.competing_share;
  EXPECT_LT(expectedError(result.covariance).translation, 3.0 * t_error);
  EXPECT_GT(expectedError(result.covariance).translation, t_error / 3.0);
}

}  // namespace
}  // namespace pda_registration
