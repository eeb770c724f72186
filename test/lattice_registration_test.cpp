// Registration on data the defaults were never tuned on (issue "Registration that holds on data
// it was never tuned on"): the same-sensor lattice case and the ground-dominated outdoor scene
// from the simulator, and the honest verdict. The lattice case failed on the constant-kappa model
// of the previous release (scripts/benchmark's lat64 rows: 0/3 at every level, 17-34 cm).

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "pda_registration/core/pda_registration.hpp"
#include "pda_registration/core/pose_covariance.hpp"
#include "pda_registration/simulation/map_simulation.hpp"
#include "test_support/simulated_cases.hpp"

namespace pda_registration {
namespace simulation {
namespace {

using testing_support::alignedError;
using testing_support::carParkOptions;
using testing_support::latticeMaps;

TEST(LatticeCase, SparseReturnsLieOnTheDenseLatticeOfTheSameSensor) {
  const SimulatedMaps& maps = latticeMaps();
  ASSERT_GT(maps.sparse.size(), 5000u);
  ASSERT_GT(maps.dense.size(), 10 * maps.sparse.size());
  // Mostly ground: the regime where a yaw of whole azimuth steps fits almost as well as the truth.
  size_t ground = 0;
  for (const Point& p : maps.dense) ground += std::abs(p.z()) < 0.1 ? 1 : 0;
  EXPECT_GT(ground, maps.dense.size() / 2);
}

TEST(LatticeCase, DefaultsRecoverTheTruthInsteadOfAYawOfWholeAzimuthSteps) {
  const SimulatedMaps& maps = latticeMaps();
  for (const double degrees : {2.0, 5.0}) {
    for (uint64_t seed : {1u, 2u}) {
      RegistrationResult result;
      const double error =
          alignedError(maps, RegistrationParameters(), degrees, degrees / 20.0, seed, &result);
      EXPECT_TRUE(result.converged) << result.reason;
      EXPECT_LT(error, 0.01) << degrees << " deg, perturbation seed " << seed;
    }
  }
}

TEST(OutdoorScene, DefaultsAlignAVlp16ScanWithA64BeamMapFromTenDegrees) {
  MapSimulationOptions options = carParkOptions(DenseSensor::kLidar64, false);
  options.velodyne_revolutions = 1;
  const SimulatedMaps maps = simulateMaps(options);
  RegistrationResult result;
  const double error = alignedError(maps, RegistrationParameters(), 10.0, 0.5, 1, &result);
  EXPECT_TRUE(result.converged) << result.reason;
  EXPECT_LT(error, 0.02);
}

// The car park on another day (pda_simulate --seed 6 --scene outdoor --scene-changes 0.6): 19 of
// its parking places drawn again for the sparse map. Along the road the cars' faces, a few metres
// from the sensors, hold most of the points that constrain that direction; with every point
// weighed alike (the default budget) a few re-parked cars that moved alike outvote the poles,
// trees and buildings that stayed: 28.8 cm off along the road from every perturbation, reported
// converged. The budget spread over space (spread_source_budget, source_budget.hpp) weighs what
// stayed.
TEST(OutdoorScene, ACarParkOnAnotherDayIsAlignedOnWhatStayedWithTheSpreadBudget) {
  MapSimulationOptions options = carParkOptions(DenseSensor::kLidar64, false);
  options.seed = 6;
  options.scene_change_share = 0.6;
  const SimulatedMaps maps = simulateMaps(options);
  ASSERT_GT(maps.changed_places, 10u);
  RegistrationParameters spread;
  spread.spread_source_budget = true;
  for (const uint64_t seed : {1u, 2u}) {
    RegistrationResult result;
    const double error = alignedError(maps, spread, 5.0, 0.25, seed, &result);
    EXPECT_TRUE(result.converged) << result.reason;
    EXPECT_LT(error, 0.01) << "perturbation seed " << seed;
  }
}

// The office on another day (pda_simulate --seed 4 --scene-changes 1.0): every one of its ten
// chairs gone or moved for the sparse map's day, the dense map the first day's. Indoors the walls,
// desks and shelves outnumber the chairs, and the default budget holds: 4.2-4.5 mm from 5 deg
// (1.9 mm unchanged; GICP 2.0-2.1 cm), and the covariance widens with it, if less (error / sigma
// 1.8 translation, 1.6 rotation, pda_covariance_check). Asserted: the hard bound, sigma
// never 3x smaller than the error.
TEST(OfficeScene, AnOfficeWhoseChairsMovedIsAlignedWithTheDefaults) {
  MapSimulationOptions options;
  options.seed = 4;
  options.scene_change_share = 1.0;
  const SimulatedMaps maps = simulateMaps(options);
  ASSERT_GE(maps.changed_places, 8u);
  for (const uint64_t seed : {1u, 2u}) {
    RegistrationResult result;
    const double error = alignedError(maps, RegistrationParameters(), 5.0, 0.25, seed, &result);
    EXPECT_TRUE(result.converged) << result.reason;
    EXPECT_LT(error, 0.01) << "perturbation seed " << seed;
    const double t_error =
        (result.T_target_source.translation() - maps.T_target_source.translation()).norm();
    EXPECT_LT(t_error, 3.0 * expectedError(result.covariance).translation)
        << "perturbation seed " << seed;
  }
}

// The verdict: a result is never reported converged while most of the source contradicts it.
TEST(HonestVerdict, AResultSupportedByTooSmallAFractionOfTheSourceIsNotConverged) {
  const SimulatedMaps& maps = latticeMaps();
  RegistrationParameters parameters;
  RegistrationResult result;
  alignedError(maps, parameters, 2.0, 0.1, 1, &result);
  ASSERT_TRUE(result.converged) << result.reason;
  ASSERT_GT(result.support_fraction, 0.0);
  ASSERT_LT(result.support_fraction, 1.0);
  // The same alignment with a support requirement above what it has.
  parameters.min_support_fraction = std::min(1.0, result.support_fraction + 0.05);
  RegistrationResult strict;
  alignedError(maps, parameters, 2.0, 0.1, 1, &strict);
  EXPECT_FALSE(strict.converged);
  EXPECT_NE(strict.reason.find("unsupported"), std::string::npos) << strict.reason;
}

TEST(HonestVerdict, SameSensorVlp16CasesAreEitherRightOrNotConverged) {
  const SimulatedMaps maps = simulateMaps(carParkOptions(DenseSensor::kVlp16, true));
  for (double degrees : {2.0, 5.0, 10.0}) {
    for (uint64_t seed : {1u, 2u}) {
      RegistrationResult result;
      const double error =
          alignedError(maps, RegistrationParameters(), degrees, degrees / 20.0, seed, &result);
      if (result.converged) {
        EXPECT_LT(error, 0.05) << degrees << " deg, seed " << seed << ": converged but wrong";
      } else {
        EXPECT_FALSE(result.reason.empty());
      }
    }
  }
}

// A static VLP-16 re-observed by itself: every sparse ring is one of the dense map's rings, on the
// same cones. Each ring, thickened by range noise, used to pass as a plane whose normal is its
// cone's; across it the two scans agree to ~10 um, sigma collapsed and 5-10 deg seeds ended
// 5-8 cm off (0 inliers, reported not converged). Now the real surfaces are found.
TEST(LatticeCase, DefaultsRecoverTheVlp16LatticeInsteadOfFittingTheLaserCones) {
  const SimulatedMaps maps = simulateMaps(carParkOptions(DenseSensor::kVlp16, true));
  for (double degrees : {5.0, 10.0}) {
    for (uint64_t seed : {1u, 2u}) {
      RegistrationResult result;
      const double error =
          alignedError(maps, RegistrationParameters(), degrees, degrees / 20.0, seed, &result);
      EXPECT_TRUE(result.converged) << degrees << " deg, seed " << seed << ": " << result.reason;
      EXPECT_LT(error, 0.01) << degrees << " deg, seed " << seed;
      EXPECT_GT(result.sigma, 1e-3) << "sigma collapsed below the simulated noise";
    }
  }
}

// Two single VLP-16 revolutions 3 m and 31 deg apart (scripts/benchmark_scan_pairs' scan_* rows):
// sparse against sparse, the kept-aside "two sparse outdoor scans" regime. The scan is in its
// sensor's frame, as a real scan is, so a perturbation turns it about its sensor.
MapSimulationOptions scanPairOptions() {
  return testing_support::scanPairOptions(DenseSensor::kVlp16, 3, Eigen::Vector3d(3.0, 0.0, 31.0));
}

TEST(ScanPair, TheScanIsInItsSensorsFrameAndTheMapsSensorWhereTheOffsetSays) {
  const SimulatedMaps maps = simulateMaps(scanPairOptions());
  ASSERT_EQ(maps.dense_lidar_poses.size(), 1u);
  ASSERT_EQ(maps.velodyne_poses.size(), 1u);
  EXPECT_TRUE(maps.velodyne_poses[0].isApprox(Eigen::Isometry3d::Identity(), 1e-12));
  // The sparse sensor in the scene (dense) frame is the ground truth; the dense sensor stands
  // 3 m along its x axis, turned by 31 deg.
  const Eigen::Isometry3d sparse_in_scene = maps.T_target_source * maps.velodyne_poses[0];
  const Eigen::Vector3d offset =
      maps.dense_lidar_poses[0].translation() - sparse_in_scene.translation();
  EXPECT_NEAR(offset.x(), 3.0, 1e-9);
  EXPECT_NEAR(offset.y(), 0.0, 1e-9);
  EXPECT_NEAR(offset.z(), 0.0, 1e-9);
  const Eigen::AngleAxisd turn(sparse_in_scene.linear().transpose() *
                               maps.dense_lidar_poses[0].linear());
  EXPECT_NEAR(turn.angle() * 180.0 / M_PI, 31.0, 1e-6);
  EXPECT_NEAR(std::abs(turn.axis().z()), 1.0, 1e-9);
}

TEST(ScanPair, DefaultsAlignTwoVlp16ScansThreeMetresAndThirtyOneDegreesApart) {
  const SimulatedMaps maps = simulateMaps(scanPairOptions());
  for (uint64_t seed : {1u, 2u}) {
    RegistrationResult result;
    const double error = alignedError(maps, RegistrationParameters(), 10.0, 0.5, seed, &result);
    EXPECT_TRUE(result.converged) << result.reason;
    EXPECT_LT(error, 0.03) << "perturbation seed " << seed;  // GICP: 2.1 cm on this pair
  }
}

// Two VLP-16 revolutions 20 m along the road and 3 m aside (scan pairs' wide_vlp16_vlp16_seed5):
// with the normal map's finest voxel at 0.15 m, voxels holding two rings of different surfaces
// tilted the target's normals and PDA ended 6.0 cm off from every perturbation (GICP: 0.8-1.3
// cm). With the finest voxel at the rings' gap (0.43 m here) it ends about 1 cm off.
TEST(ScanPair, DefaultsAlignTwoVlp16ScansTwentyMetresApart) {
  MapSimulationOptions options = scanPairOptions();
  options.seed = 5;
  options.dense_offset = Eigen::Vector3d(20.0, 3.0, 0.0);
  const SimulatedMaps maps = simulateMaps(options);
  for (uint64_t seed : {1u, 2u}) {
    RegistrationResult result;
    const double error = alignedError(maps, RegistrationParameters(), 5.0, 0.25, seed, &result);
    EXPECT_TRUE(result.converged) << result.reason;
    EXPECT_LT(error, 0.025) << "perturbation seed " << seed;
    EXPECT_GT(result.normal_voxel_size, 0.3);  // the rings' gap, not the configured 0.15 m
  }
}

// The same road, scene seed 3 (scan pairs' wide_vlp16_vlp16_seed3), where the finest voxel alone
// does not save it: with nu fixed at 5 PDA ends 9.5 cm off from every perturbation, sigma 11 cm
// (a revolution's nearest points lie on several rings; the heavy-tailed residuals pull it wide).
// With nu estimated by EM in the refine runs (nu_mode refine; it settles at 1) about 1.9 cm.
TEST(ScanPair, NuEstimatedInTheRefineRunsAlignsTwoVlp16ScansThatFixedNuMisses) {
  MapSimulationOptions options = scanPairOptions();
  options.seed = 3;
  options.dense_offset = Eigen::Vector3d(20.0, 3.0, 0.0);
  const SimulatedMaps maps = simulateMaps(options);
  RegistrationParameters fixed;
  fixed.nu_mode = NuMode::kFixed;
  RegistrationParameters refine = fixed;
  refine.nu_mode = NuMode::kRefine;
  RegistrationResult fixed_result, refine_result;
  const double fixed_error = alignedError(maps, fixed, 5.0, 0.25, 1, &fixed_result);
  const double refine_error = alignedError(maps, refine, 5.0, 0.25, 1, &refine_result);
  EXPECT_TRUE(refine_result.converged) << refine_result.reason;
  EXPECT_LT(refine_error, 0.025);
  EXPECT_GT(fixed_error, 2.0 * refine_error);
  EXPECT_LT(refine_result.nu, fixed.nu);  // estimated: heavier tails than the parameter's
}

TEST(NuMode, RefineIsTheDefaultAndFixedUntilTheRefineRuns) {
  RegistrationParameters p;
  EXPECT_EQ(p.nu_mode, NuMode::kRefine);
  EXPECT_EQ(nuModeOfRun(p, false), NuMode::kFixed);
  EXPECT_EQ(nuModeOfRun(p, true), NuMode::kEstimated);
  RegistrationParameters fixed = p, estimated = p;
  fixed.nu_mode = NuMode::kFixed;
  estimated.nu_mode = NuMode::kEstimated;
  EXPECT_EQ(nuModeOfRun(fixed, true), NuMode::kFixed);
  EXPECT_EQ(nuModeOfRun(estimated, false), NuMode::kEstimated);
  NuMode parsed = NuMode::kFixed;
  ASSERT_TRUE(parseNuMode(toString(NuMode::kRefine), &parsed));
  EXPECT_EQ(parsed, NuMode::kRefine);
  EXPECT_FALSE(parseNuMode("sometimes", &parsed));
}

// `gaussian: true` (nu = inf, the paper's eq. 19) must work without also changing nu_mode: the
// default mode keeps the Gaussian in every run; only an explicit `estimated` needs a finite start.
TEST(NuMode, AGaussianIsKeptUnderTheDefaultModeAndRefusedOnlyWhenEstimated) {
  RegistrationParameters gaussian;
  gaussian.nu = std::numeric_limits<double>::infinity();
  EXPECT_EQ(validateParameters(gaussian), "");
  EXPECT_EQ(nuModeOfRun(gaussian, true), NuMode::kFixed);
  const SimulatedMaps maps = simulateMaps(scanPairOptions());
  RegistrationResult result;
  const double error = alignedError(maps, gaussian, 5.0, 0.25, 1, &result);
  EXPECT_TRUE(result.converged) << result.reason;
  EXPECT_TRUE(std::isinf(result.nu));
  EXPECT_LT(error, 0.05);
  gaussian.nu_mode = NuMode::kEstimated;
  EXPECT_NE(validateParameters(gaussian).find("estimated"), std::string::npos);
}

// Two scans 20 m apart overlap on part of the scene only: 9 % of the source lies within 3 sigma
// of the 64-beam scan, but 17 % of the source points that have the map within radius do. The
// verdict counts support within the overlap; counted over the whole source it called this
// 2.8 mm result "unsupported" and the nodelet published nothing.
TEST(HonestVerdict, ARightAlignmentOfScansThatOverlapLittleIsConverged) {
  const SimulatedMaps maps = simulateMaps(
      testing_support::scanPairOptions(DenseSensor::kLidar64, 5, Eigen::Vector3d(20.0, 3.0, 0.0)));
  RegistrationResult result;
  const double error = alignedError(maps, RegistrationParameters(), 5.0, 0.25, 1, &result);
  EXPECT_LT(error, 0.01);
  EXPECT_TRUE(result.converged) << result.reason;
  EXPECT_LT(result.inlier_fraction, RegistrationParameters().min_support_fraction);
  EXPECT_GE(result.support_fraction, RegistrationParameters().min_support_fraction);
  EXPECT_LT(result.overlap_points, result.source_points_used * 3 / 4);
}

TEST(SimulationOptions, AKinectCannotMapTheOutdoorSceneNorServeTheSamePoseCase) {
  MapSimulationOptions options;
  options.scene = SceneKind::kOutdoor;
  EXPECT_NE(validateSimulationOptions(options), "");
  options.scene = SceneKind::kOffice;
  options.same_pose = true;
  EXPECT_NE(validateSimulationOptions(options), "");
  options.dense_sensor = DenseSensor::kVlp16;
  EXPECT_EQ(validateSimulationOptions(options), "");
  options.dense_offset_set = true;  // a scan pair's offset and the same pose exclude each other
  EXPECT_NE(validateSimulationOptions(options), "");
  options.same_pose = false;
  EXPECT_EQ(validateSimulationOptions(options), "");
  options.scan_frame = true;  // a sensor frame needs a single revolution
  EXPECT_NE(validateSimulationOptions(options), "");
  options.velodyne_revolutions = 1;
  EXPECT_EQ(validateSimulationOptions(options), "");
}

}  // namespace
}  // namespace simulation
}  // namespace pda_registration
