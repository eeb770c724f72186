// What a running system decides around each alignment, ROS-free: where it starts (the warm
// start's correction, and the retry from the seed when a warm attempt is rejected) and whether
// its result may replace the last good estimate (the acceptance gate), when a converged result
// is tried again from a second start, and when an unresolved one is tried with a wider search.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "pda_registration/core/alignment_gate.hpp"
#include "pda_registration/core/degrees_of_freedom.hpp"
#include "pda_registration/core/second_start.hpp"
#include "pda_registration/core/warm_start.hpp"
#include "pda_registration/core/wider_search.hpp"

namespace pda_registration {
namespace {

TEST(AlignmentGate, RejectsUnconvergedPoorAndWildResults) {
  RegistrationResult result;
  result.converged = true;
  result.inlier_fraction = 0.8;
  const Eigen::Isometry3d seed = Eigen::Isometry3d::Identity();
  AcceptanceThresholds thresholds;
  EXPECT_TRUE(judgeAlignment(result, seed, thresholds).accepted);

  RegistrationResult poor = result;
  poor.inlier_fraction = 0.1;
  EXPECT_NE(judgeAlignment(poor, seed, thresholds).reason.find("inlier fraction"),
            std::string::npos);
  RegistrationResult far = result;
  far.T_target_source.translation() = Eigen::Vector3d(2.0, 0, 0);
  EXPECT_NE(judgeAlignment(far, seed, thresholds).reason.find("max_correction_translation"),
            std::string::npos);
  RegistrationResult turned = result;
  turned.T_target_source.linear() =
      Eigen::AngleAxisd(0.5, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  EXPECT_NE(judgeAlignment(turned, seed, thresholds).reason.find("max_correction_rotation"),
            std::string::npos);
  RegistrationResult failed = result;
  failed.converged = false;
  failed.reason = "no overlap";
  EXPECT_NE(judgeAlignment(failed, seed, thresholds).reason.find("no overlap"), std::string::npos);
}

// The covariance's expected error (1 sigma, sqrt of each block's trace) against the stack's
// limits: off by default, and each limit rejects with its reason.
TEST(AlignmentGate, RejectsResultsThatExpectMoreErrorThanAsked) {
  RegistrationResult result;
  result.converged = true;
  result.inlier_fraction = 0.8;
  // 3 cm in each of x, y, z: sqrt(3) * 3 = 5.2 cm expected; 0.1 deg about each axis: 0.17 deg.
  result.covariance.diagonal() << 9e-4, 9e-4, 9e-4, std::pow(0.1 * M_PI / 180.0, 2),
      std::pow(0.1 * M_PI / 180.0, 2), std::pow(0.1 * M_PI / 180.0, 2);
  const Eigen::Isometry3d seed = Eigen::Isometry3d::Identity();
  AcceptanceThresholds thresholds;
  EXPECT_TRUE(judgeAlignment(result, seed, thresholds).accepted) << "no limit by default";
  thresholds.max_expected_translation = 0.06;
  thresholds.max_expected_rotation = 0.2 * M_PI / 180.0;
  EXPECT_TRUE(judgeAlignment(result, seed, thresholds).accepted);
  thresholds.max_expected_translation = 0.05;
  const Verdict translation = judgeAlignment(result, seed, thresholds);
  EXPECT_FALSE(translation.accepted);
  EXPECT_NE(translation.reason.find("max_expected_error "), std::string::npos)
      << translation.reason;
  thresholds.max_expected_translation = 0.0;
  thresholds.max_expected_rotation = 0.15 * M_PI / 180.0;
  const Verdict rotation = judgeAlignment(result, seed, thresholds);
  EXPECT_FALSE(rotation.accepted);
  EXPECT_NE(rotation.reason.find("max_expected_error_deg"), std::string::npos) << rotation.reason;
}

// The correction is kept on the dense side: it turns the seed it came from into the estimate,
// and carries over to a seed the sensor has moved on from (seed * motion -> estimate * motion),
// which a correction kept on the sparse side would not.
TEST(WarmStart, CarriesTheLastCorrectionOverToTheNextSeed) {
  const auto pose = [](double yaw, const Eigen::Vector3d& t) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    T.translation() = t;
    return T;
  };
  const Eigen::Isometry3d truth = pose(0.7, Eigen::Vector3d(2.0, -1.0, 0.3));
  const Eigen::Isometry3d drift = pose(0.05, Eigen::Vector3d(0.2, 0.1, 0.0));  // dense side
  const Eigen::Isometry3d seed = drift * truth;

  WarmStart warm;
  EXPECT_FALSE(warm.holds("map", "velodyne"));
  warm.remember(seed, truth, "map", "velodyne");
  ASSERT_TRUE(warm.holds("map", "velodyne"));
  EXPECT_FALSE(warm.holds("map", "kinect"));
  EXPECT_FALSE(warm.holds("odom", "velodyne"));
  EXPECT_TRUE(warm.corrected(seed).isApprox(truth, 1e-12));

  // The sensor moved 3 m and turned; the seed publisher's drift is the same.
  const Eigen::Isometry3d motion = pose(-0.4, Eigen::Vector3d(3.0, 0.5, 0.0));
  const Eigen::Isometry3d next_truth = truth * motion;
  EXPECT_TRUE(warm.corrected(drift * next_truth).isApprox(next_truth, 1e-12));

  // A non-finite estimate is not kept, and forget() drops what was.
  Eigen::Isometry3d broken = truth;
  broken.translation().x() = std::numeric_limits<double>::quiet_NaN();
  warm.remember(seed, broken, "map", "velodyne");
  EXPECT_FALSE(warm.holds("map", "velodyne"));
  warm.remember(seed, truth, "map", "velodyne");
  warm.forget();
  EXPECT_FALSE(warm.holds("map", "velodyne"));
}

// Where the attempts start: the corrected seed, then (only when that is rejected) the seed.
TEST(WarmStart, ARejectedWarmAttemptIsRetriedFromTheSeed) {
  Eigen::Isometry3d seed = Eigen::Isometry3d::Identity();
  seed.translation() = Eigen::Vector3d(1.0, 2.0, 0.0);
  Eigen::Isometry3d estimate = seed;
  estimate.translation().x() += 0.3;
  WarmStart warm;
  warm.remember(seed, estimate, "map", "velodyne");

  std::vector<Eigen::Isometry3d> starts;
  std::vector<bool> warm_flags;
  const auto acceptOnly = [&](const Eigen::Isometry3d& accepted) {
    return [&starts, &warm_flags, accepted](const Eigen::Isometry3d& initial, bool warm_attempt) {
      starts.push_back(initial);
      warm_flags.push_back(warm_attempt);
      return initial.isApprox(accepted) ? AttemptOutcome::kAccepted : AttemptOutcome::kRejected;
    };
  };
  EXPECT_FALSE(alignFromWarmStart(warm, true, seed, acceptOnly(estimate)));
  ASSERT_EQ(starts.size(), 1u);
  EXPECT_TRUE(starts[0].isApprox(estimate));

  starts.clear();
  warm_flags.clear();
  EXPECT_TRUE(alignFromWarmStart(warm, true, seed, acceptOnly(seed)));
  ASSERT_EQ(starts.size(), 2u);
  EXPECT_TRUE(starts[0].isApprox(estimate));
  EXPECT_TRUE(starts[1].isApprox(seed));
  EXPECT_EQ(warm_flags, (std::vector<bool>{true, false}));

  starts.clear();
  warm_flags.clear();
  EXPECT_FALSE(alignFromWarmStart(warm, false, seed, acceptOnly(estimate)));
  ASSERT_EQ(starts.size(), 1u);
  EXPECT_TRUE(starts[0].isApprox(seed));
  EXPECT_EQ(warm_flags, std::vector<bool>{false});
}

// A warm attempt cut by its time limit is not retried from the seed: the next scan is waiting.
TEST(WarmStart, AWarmAttemptOutOfTimeIsNotRetried) {
  const Eigen::Isometry3d seed = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d estimate = seed;
  estimate.translation().y() -= 0.2;
  WarmStart warm;
  warm.remember(seed, estimate, "map", "velodyne");
  int attempts = 0;
  EXPECT_FALSE(alignFromWarmStart(warm, true, seed, [&](const Eigen::Isometry3d&, bool) {
    ++attempts;
    return AttemptOutcome::kOutOfTime;
  }));
  EXPECT_EQ(attempts, 1);
}

Eigen::Isometry3d yawed(double degrees, const Eigen::Vector3d& translation) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() =
      Eigen::AngleAxisd(degrees * M_PI / 180.0, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  T.translation() = translation;
  return T;
}

TEST(SecondStart, KeepsTheFoundRotationWithTheOriginThenTheCentroidWhereTheSeedPutThem) {
  const Point centroid(3.0, 1.0, 0.5);
  const Eigen::Isometry3d seed = yawed(5.0, Eigen::Vector3d(2.0, 0.0, 0.0));
  const Eigen::Isometry3d found = yawed(25.0, Eigen::Vector3d(3.4, -0.8, 0.1));
  const auto starts = secondStartPoses(found, seed, centroid);
  for (const Eigen::Isometry3d& start : starts) {
    EXPECT_TRUE(start.linear().isApprox(found.linear()));
  }
  EXPECT_LT((starts[0].translation() - seed.translation()).norm(), 1e-12);
  EXPECT_LT((starts[1] * centroid - seed * centroid).norm(), 1e-12);
  // 20 degrees between seed and found swing the centroid, 3.2 m from the origin, by 1.1 m.
  EXPECT_GT((starts[0] * centroid - starts[1] * centroid).norm(), 1.0);
}

TEST(SecondStart, OnlyARestWithNuAtItsFloorThatMovedTheCentroidBeyondTheRadius) {
  const Point centroid(3.0, 1.0, 0.5);
  const Eigen::Isometry3d seed = yawed(5.0, Eigen::Vector3d(2.0, 0.0, 0.0));
  RegistrationResult first;
  first.converged = true;
  first.nu = kMinDegreesOfFreedom;
  first.T_target_source = yawed(25.0, Eigen::Vector3d(3.4, -0.8, 0.1));
  const RegistrationParameters defaults;
  EXPECT_TRUE(secondStartWarranted(first, defaults, seed, centroid, 0.25));
  // The centroid stayed within the final search radius: the same basin.
  EXPECT_FALSE(secondStartWarranted(first, defaults, seed, centroid, 10.0));
  RegistrationResult heavy_tailed_but_fitting = first;
  heavy_tailed_but_fitting.nu = 1.5;
  EXPECT_FALSE(secondStartWarranted(heavy_tailed_but_fitting, defaults, seed, centroid, 0.25));
  RegistrationResult failed = first;
  failed.converged = false;
  EXPECT_FALSE(secondStartWarranted(failed, defaults, seed, centroid, 0.25));
  RegistrationParameters fixed_nu = defaults;
  fixed_nu.nu_mode = NuMode::kFixed;
  fixed_nu.nu = kMinDegreesOfFreedom;
  EXPECT_FALSE(secondStartWarranted(first, fixed_nu, seed, centroid, 0.25));
}

TEST(SecondStart, TheFirstBasinHoldsPosesThatMoveThePointsByLessThanTheRadiusInRms) {
  FirstResultBasin basin;
  basin.T_found = yawed(25.0, Eigen::Vector3d(1.5, -0.8, 0.1));
  basin.centroid = Point(3.0, 0.0, 0.0);
  basin.source_rms_radius = 4.0;
  basin.final_radius = 0.25;
  EXPECT_TRUE(basin.contains(basin.T_found));
  EXPECT_TRUE(basin.contains(yawed(25.0, Eigen::Vector3d(1.6, -0.8, 0.1))));
  EXPECT_FALSE(basin.contains(yawed(25.0, Eigen::Vector3d(1.8, -0.8, 0.1))));
  // 4 degrees turn the points, 4 m from the centroid in RMS, by 0.28 m in RMS.
  EXPECT_FALSE(basin.contains(yawed(29.0, Eigen::Vector3d(1.5, -0.8, 0.1))));
  // The centroid 0.15 m further and 2 degrees more (0.14 m at 4 m) add in quadrature to 0.205 m:
  // inside, where their sum (0.29 m) is not.
  Eigen::Isometry3d turned = yawed(27.0, Eigen::Vector3d::Zero());
  turned.translation() = basin.T_found * basin.centroid + Eigen::Vector3d(0.15, 0.0, 0.0) -
                         turned.linear() * basin.centroid;
  EXPECT_TRUE(basin.contains(turned));
  // The same bound between any two poses: a start near one already tried is the same hypothesis.
  EXPECT_TRUE(basin.near(turned, basin.T_found));
  EXPECT_FALSE(basin.near(yawed(25.0, Eigen::Vector3d(2.0, -0.8, 0.1)), turned));
}

TEST(SecondStart, ReplacesTheFirstOnlyWhenConvergedAndBetterSupported) {
  RegistrationResult second;
  second.converged = true;
  EXPECT_TRUE(secondStartIsBetter(second, 0.63, 0.51));
  EXPECT_FALSE(secondStartIsBetter(second, 0.51, 0.63));
  EXPECT_FALSE(secondStartIsBetter(second, 0.51, 0.51));
  second.out_of_time = true;
  EXPECT_FALSE(secondStartIsBetter(second, 0.63, 0.51));
  second.out_of_time = false;
  second.converged = false;
  EXPECT_FALSE(secondStartIsBetter(second, 0.63, 0.51));
}

// Both supports are measured with the tighter of the two results' 3 sigma, whichever is first.
TEST(SecondStart, MeasuresBothSupportsWithTheTighterYardstick) {
  const RegistrationParameters p;
  EXPECT_DOUBLE_EQ(commonYardstick(p, 0.038, 0.018), p.inlier_sigmas * 0.018);
  EXPECT_DOUBLE_EQ(commonYardstick(p, 0.018, 0.038), p.inlier_sigmas * 0.018);
}

// Only a result that came to rest with residuals as wide as its search (6 sigma >= radius) is
// aligned again, and only if it stopped on its own: a result out of time has no time left, a
// converged one needs nothing, and fixed sigma or the single-run mode never judge the residuals.
TEST(WiderSearch, OnlyAnUnresolvedRestIsSearchedAgain) {
  const RegistrationParameters p;  // radius 1 m
  RegistrationResult unresolved;
  unresolved.sigma = 0.22;  // the car park's rest 11 deg short in yaw
  EXPECT_TRUE(widerSearchWarranted(unresolved, p));
  RegistrationResult resolved = unresolved;
  resolved.sigma = 0.15;  // 6 sigma below the radius: failed for another reason
  EXPECT_FALSE(widerSearchWarranted(resolved, p));
  RegistrationResult converged = unresolved;
  converged.converged = true;
  EXPECT_FALSE(widerSearchWarranted(converged, p));
  RegistrationResult out_of_time = unresolved;
  out_of_time.out_of_time = true;
  EXPECT_FALSE(widerSearchWarranted(out_of_time, p));
  RegistrationParameters fixed_sigma = p;
  fixed_sigma.sigma_mode = SigmaMode::kFixed;
  EXPECT_FALSE(widerSearchWarranted(unresolved, fixed_sigma));
  RegistrationParameters single_run = p;
  single_run.max_runs = 1;
  EXPECT_FALSE(widerSearchWarranted(unresolved, single_run));
}

// The wider search widens the radius and nothing else (a radius the user fixed stays the refine
// runs' floor); its result is kept only where it would
// also be resolved at the user's radius (a rest at sigma 0.3 m passes 6 sigma < 2 m, not < 1 m).
TEST(WiderSearch, DoublesTheRadiusAndKeepsOnlyAResultResolvedAtTheUsersRadius) {
  RegistrationParameters p;
  p.radius = 1.5;
  p.k = 7;
  const RegistrationParameters wider = widerSearchParameters(p);
  EXPECT_DOUBLE_EQ(wider.radius, 3.0);
  EXPECT_EQ(wider.k, 7);
  EXPECT_DOUBLE_EQ(wider.min_radius, p.min_radius);
  EXPECT_DOUBLE_EQ(wider.time_limit_ms, p.time_limit_ms);
  RegistrationParameters fixed_radius = p;
  fixed_radius.min_radius = 2.0;  // >= radius: the user fixed the radius at 1.5 m
  EXPECT_DOUBLE_EQ(widerSearchParameters(fixed_radius).min_radius, 1.5);

  RegistrationResult wide;
  wide.converged = true;
  wide.sigma = 0.015;
  EXPECT_TRUE(widerSearchHolds(wide, p));
  wide.sigma = 0.3;  // resolved at 3 m, not at 1.5 m
  EXPECT_FALSE(widerSearchHolds(wide, p));
  wide.sigma = 0.015;
  wide.converged = false;
  EXPECT_FALSE(widerSearchHolds(wide, p));
}

}  // namespace
}  // namespace pda_registration
