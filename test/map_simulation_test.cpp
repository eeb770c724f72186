// The whole simulation: the drift distortion, same-seed determinism of the maps, PDA on a
// simulated pair and under the source budget. What it writes (the bag, pda_simulate's case
// folder): map_simulation_files_test.cpp.
#include "pda_registration/simulation/map_simulation.hpp"

#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <cmath>

#include "pda_registration/core/error_metrics.hpp"
#include "pda_registration/core/pda_registration.hpp"
#include "pda_registration/core/perturbation.hpp"
#include "pda_registration/core/source_budget.hpp"
#include "pda_registration/core/target_index.hpp"
#include "pda_registration/simulation/drift_distortion.hpp"
#include "pda_registration/simulation/sensor_paths.hpp"
#include "test_support/simulated_cases.hpp"

namespace pda_registration {
namespace simulation {
namespace {

using Eigen::Vector2d;
using Eigen::Vector3d;

// Small but complete maps, so the determinism tests stay fast.
using testing_support::smallOfficeOptions;

bool samePoints(const PointList& a, const PointList& b) {
  if (a.size() != b.size()) return false;
  for (size_t i = 0; i < a.size(); ++i) {
    if (a[i] != b[i]) return false;
  }
  return true;
}

// --- Distortion ------------------------------------------------------------------------------

TEST(DriftDistortion, ZeroAtTheCentreAndAmountTimesRadiusAtFiveMetres) {
  const DriftDistortion drift{Vector2d(5.0, 3.0), 0.01};
  const Point centre(5.0, 3.0, 1.2);
  EXPECT_EQ(drift.apply(centre), centre);
  // 5 m away: 5 cm outwards and 5 cm up.
  EXPECT_TRUE(drift.apply(Point(10.0, 3.0, 0.5)).isApprox(Point(10.05, 3.0, 0.55), 1e-12));
  EXPECT_TRUE(drift.apply(Point(8.0, 7.0, 0.0)).isApprox(Point(8.03, 7.04, 0.05), 1e-12));
  // Quadratic growth: a quarter of the displacement at half the distance.
  const Point half = drift.apply(Point(7.5, 3.0, 0.0));
  EXPECT_NEAR(half.x() - 7.5, 0.0125, 1e-12);
  EXPECT_NEAR(half.z(), 0.0125, 1e-12);

  PointList points = {Point(1.0, 2.0, 3.0), Point(-4.0, 8.0, 0.0)};
  const PointList original = points;
  applyDistortion(DriftDistortion{Vector2d(5.0, 3.0), 0.0}, &points);
  EXPECT_TRUE(samePoints(points, original));
}

// --- Whole simulation ------------------------------------------------------------------------

TEST(MapSimulation, SameSeedGivesIdenticalMapsAndAnotherSeedDifferentOnes) {
  const SimulatedMaps a = simulateMaps(smallOfficeOptions(11));
  const SimulatedMaps b = simulateMaps(smallOfficeOptions(11));
  const SimulatedMaps c = simulateMaps(smallOfficeOptions(12));
  ASSERT_GT(a.dense.size(), 10000u);
  ASSERT_GT(a.sparse.size(), 10000u);
  EXPECT_TRUE(samePoints(a.dense, b.dense));
  EXPECT_TRUE(samePoints(a.sparse, b.sparse));
  EXPECT_FALSE(samePoints(a.dense, c.dense));
  EXPECT_FALSE(samePoints(a.sparse, c.sparse));

  // Ray casting runs on several threads; the maps must not depend on how many.
  const int threads = omp_get_max_threads();
  omp_set_num_threads(1);
  const SimulatedMaps single = simulateMaps(smallOfficeOptions(11));
  omp_set_num_threads(std::max(2, threads));
  const SimulatedMaps several = simulateMaps(smallOfficeOptions(11));
  omp_set_num_threads(threads);
  EXPECT_TRUE(samePoints(single.dense, several.dense));
  EXPECT_TRUE(samePoints(single.sparse, a.sparse));
}

// A noise seed draws the sensor noise again on the same scene: same poses and ground truth,
// other points; the noise seed equal to the layout seed is what the layout seed alone gives.
TEST(MapSimulation, NoiseSeedRedrawsOnlyTheSensorNoise) {
  const SimulatedMaps a = simulateMaps(smallOfficeOptions(11));
  MapSimulationOptions options = smallOfficeOptions(11);
  options.noise_seed = 2;
  const SimulatedMaps b = simulateMaps(options);
  options.noise_seed = 11;
  const SimulatedMaps c = simulateMaps(options);
  EXPECT_TRUE(a.T_target_source.isApprox(b.T_target_source, 0.0));
  ASSERT_EQ(a.velodyne_poses.size(), b.velodyne_poses.size());
  for (size_t i = 0; i < a.velodyne_poses.size(); ++i)
    EXPECT_TRUE(a.velodyne_poses[i].isApprox(b.velodyne_poses[i], 0.0));
  EXPECT_FALSE(samePoints(a.dense, b.dense));
  EXPECT_FALSE(samePoints(a.sparse, b.sparse));
  // The same scene seen again: about as many points (only dropouts and voxels differ).
  EXPECT_NEAR(static_cast<double>(b.sparse.size()), static_cast<double>(a.sparse.size()),
              0.02 * a.sparse.size());
  EXPECT_NEAR(static_cast<double>(b.dense.size()), static_cast<double>(a.dense.size()),
              0.02 * a.dense.size());
  EXPECT_TRUE(samePoints(a.dense, c.dense));
  EXPECT_TRUE(samePoints(a.sparse, c.sparse));
}

// The car park on another day: the places drawn again hold other cars (or none), everything else
// is the scene itself; the dense map (the first day) is untouched and only the sparse scan sees
// the change.
TEST(CarParkAnotherDay, RedrawsOnlyTheParkingPlacesAndOnlyForTheSparseMap) {
  const OutdoorScene outdoor = makeOutdoorScene(6);
  ASSERT_GT(outdoor.slots.size(), 10u);
  size_t changed = 1;
  const Scene same = carParkAnotherDay(outdoor, 0.0, 1, &changed);
  EXPECT_EQ(changed, 0u);
  EXPECT_EQ(same.primitiveCount(), outdoor.scene.primitiveCount());

  const Scene every = carParkAnotherDay(outdoor, 1.0, 1, &changed);
  EXPECT_EQ(changed, outdoor.slots.size());
  // Ground, buildings, poles and trees are the first day's, in the same order.
  ASSERT_EQ(every.cylinders().size(), outdoor.scene.cylinders().size());
  for (size_t b = 0; b < outdoor.first_car_box; ++b) {
    EXPECT_EQ(every.boxes()[b].min, outdoor.scene.boxes()[b].min);
    EXPECT_EQ(every.boxes()[b].max, outdoor.scene.boxes()[b].max);
  }
  // Every car now stands where no first-day car stood (each moved within its place, or is new).
  size_t same_car = 0;
  for (size_t b = outdoor.first_car_box; b < every.boxes().size(); ++b) {
    for (size_t f = outdoor.first_car_box; f < outdoor.scene.boxes().size(); ++f) {
      if (every.boxes()[b].min == outdoor.scene.boxes()[f].min) ++same_car;
    }
  }
  EXPECT_EQ(same_car, 0u);

  // A share draws about that share of the places, the same ones for the same seed.
  size_t some = 0, again = 0;
  carParkAnotherDay(outdoor, 0.3, 7, &some);
  carParkAnotherDay(outdoor, 0.3, 7, &again);
  EXPECT_EQ(some, again);
  EXPECT_GT(some, 0u);
  EXPECT_LT(some, outdoor.slots.size());

  MapSimulationOptions options;
  options.seed = 6;
  options.scene = SceneKind::kOutdoor;
  options.dense_voxel_size = 0.0;
  options.velodyne_revolutions = 1;
  options.dense_revolutions = 1;
  const SimulatedMaps first_day = simulateMaps(options);
  options.scene_change_share = 0.6;
  const SimulatedMaps other_day = simulateMaps(options);
  EXPECT_GT(other_day.changed_places, 0u);
  EXPECT_EQ(first_day.changed_places, 0u);
  EXPECT_TRUE(samePoints(first_day.dense, other_day.dense));
  EXPECT_FALSE(samePoints(first_day.sparse, other_day.sparse));
  EXPECT_TRUE(other_day.T_target_source.isApprox(first_day.T_target_source, 0.0));
  options.scene_change_share = 1.5;
  EXPECT_NE(validateSimulationOptions(options), "");
}

// The office on another day: its chairs drawn again (gone, or moved along the desk and pushed in
// or pulled out), nothing else; only the sparse map sees them.
TEST(OfficeAnotherDay, RedrawsOnlyTheChairsAndOnlyForTheSparseMap) {
  const OfficeScene office = makeOfficeScene(3);
  ASSERT_GT(office.chairs.size(), 4u);
  size_t with_chair = 0;
  for (const ChairPlace& place : office.chairs) with_chair += place.seat_box >= 0 ? 1 : 0;
  ASSERT_GT(with_chair, 0u);
  size_t changed = 1;
  EXPECT_EQ(officeAnotherDay(office, 0.0, 1, &changed).primitiveCount(),
            office.scene.primitiveCount());
  EXPECT_EQ(changed, 0u);
  const Scene every = officeAnotherDay(office, 1.0, 1, &changed);
  EXPECT_EQ(changed, office.chairs.size());
  // Everything but the chairs is there as it was: as many primitives less the first day's chairs
  // (3 each) plus the new ones (3 each).
  const size_t others = office.scene.primitiveCount() - 3 * with_chair;
  EXPECT_EQ((every.primitiveCount() - others) % 3, 0u);
  for (const ChairPlace& place : office.chairs) {
    if (place.seat_box < 0) continue;
    const Box& seat = office.scene.boxes()[place.seat_box];
    for (const Box& box : every.boxes()) EXPECT_FALSE(box.min == seat.min && box.max == seat.max);
  }

  MapSimulationOptions options = smallOfficeOptions(3);
  const SimulatedMaps first_day = simulateMaps(options);
  options.scene_change_share = 1.0;
  const SimulatedMaps other_day = simulateMaps(options);
  EXPECT_EQ(other_day.changed_places, office.chairs.size());
  EXPECT_TRUE(samePoints(first_day.dense, other_day.dense));
  EXPECT_FALSE(samePoints(first_day.sparse, other_day.sparse));
  EXPECT_EQ(validateSimulationOptions(options), "");
}

TEST(MapSimulation, SparseMapIsInItsOwnFrameAndDistortionOnlyWarpsTheDenseMap) {
  MapSimulationOptions options = smallOfficeOptions(13);
  options.kinect.noise = options.velodyne.noise = false;
  const SimulatedMaps rigid = simulateMaps(options);
  const Eigen::Isometry3d expected =
      transformFromYawPitchRoll(25.0, 0.0, 0.0, Vector3d(1.5, -0.8, 0.1));
  EXPECT_TRUE(rigid.T_target_source.isApprox(expected, 1e-12));
  // Noise-free sparse points moved into the dense frame are exactly where the lidar's beams
  // first hit the scene.
  const Eigen::Isometry3d lidar_in_dense = rigid.T_target_source * rigid.velodyne_poses[0];
  size_t on_surface = 0;
  for (const Point& p : rigid.sparse) {
    const Point in_dense = rigid.T_target_source * p;
    const Vector3d towards_point = (in_dense - lidar_in_dense.translation()).normalized();
    const double range = rigid.office.scene.castRay(lidar_in_dense.translation(), towards_point);
    on_surface += std::abs(range - (in_dense - lidar_in_dense.translation()).norm()) < 1e-6;
  }
  EXPECT_EQ(on_surface, rigid.sparse.size());

  options.distortion = 0.01;
  const SimulatedMaps warped = simulateMaps(options);
  EXPECT_TRUE(samePoints(warped.sparse, rigid.sparse));
  ASSERT_EQ(warped.dense.size(), rigid.dense.size());
  const DriftDistortion drift{rigid.office.office.center(), 0.01};
  double largest_shift = 0.0;
  for (size_t i = 0; i < rigid.dense.size(); ++i) {
    ASSERT_TRUE(warped.dense[i].isApprox(drift.apply(rigid.dense[i]), 1e-12));
    largest_shift = std::max(largest_shift, (warped.dense[i] - rigid.dense[i]).norm());
  }
  EXPECT_GT(largest_shift, 0.02);
}

TEST(MapSimulation, PdaRecoversTheGroundTruthFromAPerturbedSeed) {
  const SimulatedMaps maps = simulateMaps(MapSimulationOptions());
  RegistrationParameters parameters;
  parameters.radius = 0.5;
  PdaRegistration registration(parameters);
  ASSERT_TRUE(registration.setTarget(maps.dense));
  for (uint64_t seed : {1u, 2u, 3u}) {
    const Eigen::Isometry3d initial = maps.T_target_source * randomPerturbation(3.0, 0.15, seed);
    const RegistrationResult result = registration.align(maps.sparse, initial);
    ASSERT_TRUE(result.converged) << result.reason;
    const PoseError error = poseError(maps.sparse, result.T_target_source, maps.T_target_source);
    EXPECT_LT(error.translation, 0.03) << "perturbation seed " << seed;
    EXPECT_LT(error.rotation_deg, 0.5) << "perturbation seed " << seed;
    EXPECT_LT(error.mean_distance, 0.03) << "perturbation seed " << seed;
  }
}

// Share of the source's points (moved by the ground truth) with a dense point within 5 cm.
double overlapShare(const SimulatedMaps& maps) {
  const TargetIndex dense(maps.dense);
  size_t near = 0;
  size_t index = 0;
  double squared_distance = 0.0;
  for (const Point& p : maps.sparse) {
    near +=
        dense.nearestWithinRadius(maps.T_target_source * p, 1, 0.05, &index, &squared_distance) > 0;
  }
  return static_cast<double>(near) / static_cast<double>(maps.sparse.size());
}

// RGB-D fragments that scan 55 % of the walkway each instead of 60 % share less of the scene:
// the source's points with a dense point within 5 cm fall from 54 % to 46 % (seed 5). PDA still
// recovers the pair from 5 deg / 0.25 m (the held-out set of docs/benchmark.md: PDA 1.9-6.7 mm
// to 10 deg / 0.5 m).
TEST(MapSimulation, ShorterRgbdFragmentsOverlapLessAndStillAlign) {
  MapSimulationOptions options = testing_support::rgbdFragmentOptions(5, 0.0);
  const SimulatedMaps usual = simulateMaps(options);
  options.fragment_length = 0.55;
  const SimulatedMaps shorter = simulateMaps(options);
  const double usual_share = overlapShare(usual), shorter_share = overlapShare(shorter);
  EXPECT_GT(usual_share, 0.5);
  EXPECT_LT(shorter_share, usual_share - 0.05) << "usual " << usual_share;
  EXPECT_GT(shorter_share, 0.3);

  PdaRegistration registration((RegistrationParameters()));
  ASSERT_TRUE(registration.setTarget(shorter.dense));
  for (uint64_t seed : {1u, 2u}) {
    const Eigen::Isometry3d initial = shorter.T_target_source * randomPerturbation(5.0, 0.25, seed);
    const RegistrationResult result = registration.align(shorter.sparse, initial);
    ASSERT_TRUE(result.converged) << result.reason;
    EXPECT_LT(
        poseError(shorter.sparse, result.T_target_source, shorter.T_target_source).mean_distance,
        0.01)
        << "perturbation seed " << seed;
  }
}

// RGB-D fragments that each scan 40 % of the walkway share a third of the scene (the held-out
// set of docs/benchmark.md). The two thirds without a counterpart pull the usual alignment along
// the walkway: layout 5 from 2 deg 2.6 m, not converged; layout 3 from 5 deg onto a rest one desk
// repeat along it, 2.7 m off, converged (nu at its floor). The local start with the outlier class
// (local_start.hpp) stays at the truth on layout 5 (7 mm; GICP on 0.1-m voxels 1.8 cm), and the
// other direction, which the first warranted and which meets it, finds the truth too (with an
// earlier alignment it converged 2.6 m off): here in double precision it fits more of the overlap
// and is kept; on layout 3 (1.6 cm; GICP 3.8 cm) the second start at nu's floor gets
// there first (second_start_attempts.cpp).
TEST(MapSimulation, FragmentsSharingAThirdAlignFromNearTheSeed) {
  struct Case {
    int layout;
    double degrees, metres;
    uint64_t perturbation;
  };
  for (const Case& c : {Case{5, 2.0, 0.1, 1}, Case{3, 5.0, 0.25, 3}}) {
    const SimulatedMaps maps = simulateMaps(testing_support::lowOverlapFragmentOptions(c.layout));
    EXPECT_LT(overlapShare(maps), 0.36);

    PdaRegistration registration((RegistrationParameters()));
    ASSERT_TRUE(registration.setTarget(maps.dense));
    const Eigen::Isometry3d initial =
        maps.T_target_source * randomPerturbation(c.degrees, c.metres, c.perturbation);
    const RegistrationResult result = registration.align(maps.sparse, initial);
    ASSERT_TRUE(result.converged) << "layout " << c.layout << ": " << result.reason;
    if (c.layout == 5) {
      EXPECT_TRUE(result.local_start || result.roles_swapped) << "layout " << c.layout;
    } else {
      EXPECT_FALSE(result.local_start || result.roles_swapped) << "layout " << c.layout;
    }
    EXPECT_LT(poseError(maps.sparse, result.T_target_source, maps.T_target_source).mean_distance,
              0.02)
        << "layout " << c.layout;
  }
}

// The nodelet's per-alignment source budget (max_source_points, 15000 by default) on the demo's
// scene (86k sparse points): the estimate stays within 2 mm (eq. 22) of the one on every point. A
// spatially uniform subsample failed this (2.0 -> 4.4 mm: it re-weights the map towards its
// sparse far parts; the first one, with the noise model of 2026-11-22); an unbiased one keeps the
// full cloud's objective (2.0 mm).
TEST(MapSimulation, SourceBudgetKeepsTheAccuracyOfTheWholeSparseMap) {
  const SimulatedMaps maps = simulateMaps(MapSimulationOptions());
  ASSERT_GT(maps.sparse.size(), 60000u);
  PdaRegistration registration((RegistrationParameters()));
  ASSERT_TRUE(registration.setTarget(maps.dense));
  const Eigen::Isometry3d initial = maps.T_target_source * randomPerturbation(3.0, 0.15, 1);
  const PointList budgeted = randomSubsample(maps.sparse, 15000);
  ASSERT_EQ(budgeted.size(), 15000u);
  const RegistrationResult all = registration.align(maps.sparse, initial);
  const RegistrationResult some = registration.align(budgeted, initial);
  ASSERT_TRUE(all.converged) << all.reason;
  ASSERT_TRUE(some.converged) << some.reason;
  const double all_error =
      poseError(maps.sparse, all.T_target_source, maps.T_target_source).mean_distance;
  const double some_error =
      poseError(maps.sparse, some.T_target_source, maps.T_target_source).mean_distance;
  EXPECT_LT(some_error, all_error + 0.002) << "all points " << all_error;
}

}  // namespace
}  // namespace simulation
}  // namespace pda_registration
