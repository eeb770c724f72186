// How far from the truth the defaults still find it, and what they say when they do not: the
// approach stage's source subset, the per-alignment source budget, the "unresolved" verdict and
// RGB-D fragment pairs (issue "Registration that holds on data it was never tuned on").

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "pda_registration/core/error_metrics.hpp"
#include "pda_registration/core/pda_registration.hpp"
#include "pda_registration/core/perturbation.hpp"
#include "pda_registration/core/source_budget.hpp"
#include "pda_registration/simulation/map_simulation.hpp"
#include "test_support/simulated_cases.hpp"

namespace pda_registration {
namespace simulation {
namespace {

using testing_support::alignedError;
using testing_support::latticeMaps;
using testing_support::rgbdFragmentOptions;

// The approach stage aligns a quarter of the source. Taken as every 4th point in storage order,
// a scan stored firing by firing (all lasers of one azimuth, then the next) gave 8 of 32 rings.
TEST(ApproachSubset, KeepsEveryRingOfAScanStoredFiringByFiring) {
  constexpr int kRings = 32, kColumns = 1000;
  PointList scan;
  for (int column = 0; column < kColumns; ++column) {
    for (int ring = 0; ring < kRings; ++ring) scan.emplace_back(column, ring, 0.0);
  }
  const PointList subset = randomSubsample(scan, scan.size() / 4);
  ASSERT_EQ(subset.size(), scan.size() / 4);
  std::vector<int> per_ring(kRings, 0);
  for (const Point& p : subset) ++per_ring[static_cast<int>(p.y())];
  for (int ring = 0; ring < kRings; ++ring) {
    EXPECT_NEAR(per_ring[ring], kColumns / 4, kColumns / 10) << "ring " << ring;
  }
}

// These seeds ended 0.76-1.17 m off (not converged after 50 runs) when the approach stage used a
// storage-order stride: the subset slid along the ground's valley for 50 runs.
TEST(Reach, TheLatticeIsFoundFromTenDegreesAndHalfAMetre) {
  for (uint64_t seed : {3u, 8u, 10u}) {
    RegistrationResult result;
    const double error = alignedError(latticeMaps(), RegistrationParameters(), 10.0, 0.5, seed,
                                      &result);
    EXPECT_TRUE(result.converged) << "seed " << seed << ": " << result.reason;
    EXPECT_LT(error, 0.01) << "seed " << seed;
  }
}

// Two clouds that agree only to the scale of the candidate radius are not a registration, however
// still the estimate has come to rest.
TEST(HonestVerdict, ResidualsAsWideAsTheSearchAreUnresolved) {
  const SimulatedMaps& maps = latticeMaps();
  SimulatedMaps blurred = maps;
  std::mt19937_64 generator(7);
  std::normal_distribution<double> noise(0.0, 0.3);
  for (Point& p : blurred.sparse) p += Point(noise(generator), noise(generator), noise(generator));
  RegistrationResult result;
  alignedError(blurred, RegistrationParameters(), 0.0, 0.0, 1, &result);
  EXPECT_FALSE(result.converged);
  EXPECT_NE(result.reason.find("unresolved"), std::string::npos) << result.reason;
  EXPECT_GE(6.0 * result.sigma, RegistrationParameters().radius);
}

// RGB-D fragments that share a third of the scene (layout 5, each 40 % of the walkway), from 2
// deg: the two thirds without a counterpart hold sigma at 0.14-0.18 m, and once a refine run's
// residuals span the search the attempt stops there, "unresolved" (it wandered 12 more runs at
// that sigma into the same verdict); the local start then finds the truth, and so does the other
// direction, which meets it (the better supported kept: here the other direction, in the PCD
// files' float precision the local start).
TEST(HonestVerdict, ARefineRunWhoseResidualsSpanTheSearchEndsItsAttempt) {
  MapSimulationOptions options = rgbdFragmentOptions(5);
  options.fragment_length = 0.4;
  const SimulatedMaps maps = simulateMaps(options);
  const RegistrationParameters p;
  PdaRegistration registration(p);
  std::vector<RunRecord> first_runs;
  std::vector<AttemptRecord> attempts;
  AlignmentTrace trace;
  trace.run = [&first_runs](const RunRecord& r) {
    if (std::string(r.attempt) == "first") first_runs.push_back(r);
  };
  trace.attempt = [&attempts](const AttemptRecord& a) { attempts.push_back(a); };
  registration.setTrace(trace);
  ASSERT_TRUE(registration.setTarget(maps.dense));
  const RegistrationResult result =
      registration.align(maps.sparse, maps.T_target_source * randomPerturbation(2.0, 0.1, 1));

  // Second starts run at nu's floor may be noted before the first attempt ends.
  const auto first = std::find_if(attempts.begin(), attempts.end(), [](const AttemptRecord& a) {
    return std::string(a.attempt) == "first";
  });
  ASSERT_TRUE(first != attempts.end());
  EXPECT_NE(first->reason.find("unresolved"), std::string::npos) << first->reason;
  ASSERT_FALSE(first_runs.empty());
  const auto spans = [&p](const RunRecord& r) {
    return std::string(r.stage) == "refine" && 6.0 * r.sigma >= p.radius;
  };
  EXPECT_TRUE(spans(first_runs.back()))
      << "the first attempt's last run, sigma " << first_runs.back().sigma;
  EXPECT_EQ(std::count_if(first_runs.begin(), first_runs.end(), spans), 1);
  ASSERT_TRUE(result.converged) << result.reason;
  EXPECT_TRUE(result.local_start || result.roles_swapped);
  EXPECT_LT(poseError(maps.sparse, result.T_target_source, maps.T_target_source).mean_distance,
            0.02);
}

// Two hand-held RGB-D fragments of one office, overlapping on two fifths of the loop, both dense
// (~300k points each): the source budget aligns 15000 of the source's points.
TEST(Reach, RgbdFragmentsAlignWithDefaultsFromTenDegrees) {
  MapSimulationOptions options;
  options.seed = 3;
  options.sparse_sensor = SparseSensor::kKinectFragment;
  options.kinect_frames = 12;
  const SimulatedMaps maps = simulateMaps(options);
  ASSERT_GT(maps.sparse.size(), 100000u);
  const RegistrationParameters defaults;
  RegistrationResult result;
  const double error = alignedError(maps, defaults, 10.0, 0.5, 1, &result);
  EXPECT_TRUE(result.converged) << result.reason;
  EXPECT_LT(error, 0.01);
  EXPECT_EQ(result.source_points_used, static_cast<size_t>(defaults.max_source_points));
}

// Seed 4's pair from this perturbation slid 2.3 m along the walkway, reported converged (rotation
// right to 0.09 deg): the approach's second run was extrapolated from one ratio of two steps as
// wide as sigma (0.38 and 0.19 m at sigma 0.32 m), past the ridge of the true basin. The approach
// now takes a tail only when three steps agree (run_extrapolation.hpp); PCL's GICP found it too.
TEST(Reach, RgbdFragmentsAreNotExtrapolatedOutOfTheirBasin) {
  const SimulatedMaps maps = simulateMaps(rgbdFragmentOptions(4));
  RegistrationResult result;
  const double error = alignedError(maps, RegistrationParameters(), 10.0, 0.5, 4, &result);
  EXPECT_TRUE(result.converged) << result.reason;
  EXPECT_LT(error, 0.01);
}

// The RGB-D fragment pair of seed 3, simulated once.
const SimulatedMaps& fragmentsOfSeed3() {
  static const SimulatedMaps maps = simulateMaps(rgbdFragmentOptions(3));
  return maps;
}

// Seed 3's pair from 20 deg / 1 m (perturbation 4): the approach turned the source right while it
// slid along the walkway by about a desk's repeat, and came to rest there 1.35 m off, converged,
// with nu at its floor. From the rotation it found, the second start reaches the right pose and is
// better supported (second_start.hpp).
TEST(Reach, RgbdFragmentsFromTwentyDegreesLeaveAFalseRestByASecondStart) {
  RegistrationResult result;
  const double error =
      alignedError(fragmentsOfSeed3(), RegistrationParameters(), 20.0, 1.0, 4, &result);
  EXPECT_TRUE(result.converged) << result.reason;
  EXPECT_LT(error, 0.01);
}

// The same pair from perturbation 1 came to rest 1.35 m off as well. Started again with the
// centroid where the seed put it (the seed's 20 deg about the source frame's origin, 6.5 m from
// the centroid, moved the points 2.2 m on average), it slid back into that rest; with the source
// frame's origin where the seed put it (off by the 1 m translation alone; the two starts 1.7 m
// apart at the centroid), it reaches the right pose (the test fails without that start: 1.35 m).
TEST(Reach, RgbdFragmentsFromTwentyDegreesLeaveAFalseRestFromTheSeedsOrigin) {
  RegistrationResult result;
  const double error =
      alignedError(fragmentsOfSeed3(), RegistrationParameters(), 20.0, 1.0, 1, &result);
  EXPECT_TRUE(result.converged) << result.reason;
  EXPECT_LT(error, 0.01);
}

// The car park of pda_simulate --scene outdoor --seed 6 (not a benchmark layout), simulated once.
const SimulatedMaps& carParkOfSeed6() {
  static const SimulatedMaps maps = [] {
    MapSimulationOptions options = testing_support::carParkOptions(DenseSensor::kLidar64, false);
    options.seed = 6;
    return simulateMaps(options);
  }();
  return maps;
}

// Its scan aligned from the ground truth perturbed by 20 deg / 1 m (perturbation 2).
RegistrationResult alignFromTwentyDegrees(const SimulatedMaps& maps, PdaRegistration* registration,
                                          Associations* associations) {
  EXPECT_TRUE(registration->setTarget(maps.dense));
  return registration->align(maps.sparse, maps.T_target_source * randomPerturbation(20.0, 1.0, 2),
                             associations);
}

// A car park scanned by a 64-beam lidar (the dense map) and a VLP-16 (pda_simulate --scene outdoor
// --seed 6, a layout the benchmark does not use), from 20 deg / 1 m (perturbation 2): the ground
// set height, roll and pitch at once, but the buildings and poles that set the yaw had moved
// beyond the 1 m radius, and the approach came to rest 11 deg short in yaw, "unresolved" (sigma
// 0.22 m). Aligned again from the seed with the radius doubled, it converges on the truth
// (wider_search.hpp).
// The user's parameters come back afterwards, and the associations are the kept result's.
TEST(Reach, ACarParkFromTwentyDegreesIsFoundByTheWiderSearch) {
  const SimulatedMaps& maps = carParkOfSeed6();
  const RegistrationParameters defaults;
  PdaRegistration registration(defaults);
  Associations associations;
  const RegistrationResult result = alignFromTwentyDegrees(maps, &registration, &associations);
  EXPECT_TRUE(result.converged) << result.reason;
  EXPECT_TRUE(result.search_widened);
  EXPECT_LT(poseError(maps.sparse, result.T_target_source, maps.T_target_source).mean_distance,
            0.01);
  EXPECT_DOUBLE_EQ(registration.parameters().radius, defaults.radius);
  EXPECT_DOUBLE_EQ(registration.parameters().time_limit_ms, defaults.time_limit_ms);
  // Each associated source point sits at the kept pose: within a few sigma of its nearest
  // candidate, which the unresolved rest (11 deg off in yaw) was not for most points.
  ASSERT_GT(associations.source_points.size(), 1000u);
  size_t near = 0;
  for (size_t j = 0; j + 1 < associations.offsets.size(); ++j) {
    double best = std::numeric_limits<double>::infinity();
    for (size_t c = associations.offsets[j]; c < associations.offsets[j + 1]; ++c) {
      best = std::min(best, (associations.candidates[c] - associations.source_points[j]).norm());
    }
    near += best < 5.0 * result.sigma ? 1 : 0;
  }
  EXPECT_GT(static_cast<double>(near),
            0.5 * static_cast<double>(associations.source_points.size()));
}

// A radius the user fixed (min_radius >= radius) bounds the wider search's final candidates too:
// only the search widens, not the radius the answer rests on.
TEST(Reach, TheWiderSearchKeepsARadiusTheUserFixed) {
  RegistrationParameters fixed;
  fixed.radius = 1.0;
  fixed.min_radius = 1.5;
  PdaRegistration registration(fixed);
  Associations associations;
  const RegistrationResult result =
      alignFromTwentyDegrees(carParkOfSeed6(), &registration, &associations);
  ASSERT_TRUE(result.search_widened) << result.reason;
  ASSERT_FALSE(associations.candidates.empty());
  double farthest = 0.0;
  for (size_t j = 0; j + 1 < associations.offsets.size(); ++j) {
    for (size_t c = associations.offsets[j]; c < associations.offsets[j + 1]; ++c) {
      farthest =
          std::max(farthest, (associations.candidates[c] - associations.source_points[j]).norm());
    }
  }
  EXPECT_LE(farthest, fixed.radius);
}

// An office whose chairs all moved before the VLP-16 scanned it (pda_simulate --seed 7
// --scene-changes 1.0, held out in docs/benchmark.md), from 20 deg / 1 m: the first alignment comes
// to rest unresolved (sigma 0.22 m), and the local start, which from that far converges as readily
// on a false fit near the seed, ended 2.16 m off with 11 % of its overlap within 3 sigma. It was
// kept, and the wider search never ran; alone, that finds the truth (3.7 mm, 73 %). A local start
// adopted where the first warranted the wider search now meets it, the better supported kept.
TEST(Reach, AnOfficeFromTwentyDegreesKeepsTheWiderSearchOverAFalseLocalStart) {
  MapSimulationOptions options;
  options.seed = 7;
  options.scene_change_share = 1.0;
  const SimulatedMaps maps = simulateMaps(options);
  RegistrationResult result;
  const double error = alignedError(maps, RegistrationParameters(), 20.0, 1.0, 1, &result);
  EXPECT_TRUE(result.converged) << result.reason;
  EXPECT_TRUE(result.search_widened);
  EXPECT_FALSE(result.local_start);
  EXPECT_LT(error, 0.01);
}

// A time limit that the car park's first alignment (unresolved, 11 deg short) fits within but its
// wider search does not: the call comes back out of time, saying the wider search was cut, so a
// caller with a deadline does not read it as the data's verdict (the nodelet would otherwise retry
// a warm attempt from the seed with no limit). An unlimited call says how long the whole takes;
// the first alignment is about 60 % of it, so 75 % cuts the wider search. The unlimited call is
// timed warm, as the limited one runs: the first call on a target fills its normal map lazily
// (the limited call then came in under 80 % of the first call's time once, on a loaded machine).
// A load that changes between the two calls can still move the cut out of the wider search: up
// to three attempts, each timed afresh; the old behaviour (out_of_time false) fails all three.
TEST(Reach, AWiderSearchCutByTheTimeLimitComesBackOutOfTime) {
  PdaRegistration registration{RegistrationParameters()};
  alignFromTwentyDegrees(carParkOfSeed6(), &registration, nullptr);  // warms the normal map
  RegistrationParameters limited;
  RegistrationResult cut;
  for (int attempt = 0; attempt < 3; ++attempt) {
    registration.setParameters(RegistrationParameters());
    const RegistrationResult whole =
        alignFromTwentyDegrees(carParkOfSeed6(), &registration, nullptr);
    ASSERT_TRUE(whole.search_widened) << whole.reason;
    limited.time_limit_ms = 0.75 * (whole.time_ms - whole.target_index_ms);
    registration.setParameters(limited);
    cut = alignFromTwentyDegrees(carParkOfSeed6(), &registration, nullptr);
    if (cut.out_of_time && cut.reason.find("a wider search was cut") != std::string::npos) break;
  }
  EXPECT_FALSE(cut.converged);
  EXPECT_TRUE(cut.out_of_time);
  EXPECT_NE(cut.reason.find("a wider search was cut by the time limit"), std::string::npos)
      << cut.reason;
  EXPECT_DOUBLE_EQ(registration.parameters().time_limit_ms, limited.time_limit_ms);
}

// A growing SLAM map's first third (the office's first 1M Kinect points, in scan order) against
// a whole VLP-16 revolution: from 0.5 deg / 3 cm the approach cycled between two poses 1.4 mm
// apart, above its 10 epsilons, until the work bound (200 runs, "not converged" 5 mm off). Runs
// that come back on themselves now end the approach as they end the refine stage.
TEST(Reach, AnApproachThatCyclesInPlaceEndsItsStage) {
  MapSimulationOptions options;
  options.dense_voxel_size = 0.0;
  options.velodyne_revolutions = 1;
  SimulatedMaps maps = simulateMaps(options);
  ASSERT_GT(maps.dense.size(), 1000000u);
  maps.dense.resize(1000000);
  RegistrationResult result;
  const double error = alignedError(maps, RegistrationParameters(), 0.5, 0.03, 1, &result);
  EXPECT_TRUE(result.converged) << result.reason;
  EXPECT_LT(error, 0.01);
  EXPECT_LT(result.runs, 50);
}

TEST(SimulationOptions, AKinectFragmentSourceNeedsTheOfficeAndAKinectMap) {
  MapSimulationOptions options;
  options.sparse_sensor = SparseSensor::kKinectFragment;
  EXPECT_EQ(validateSimulationOptions(options), "");
  options.dense_sensor = DenseSensor::kVlp16;
  EXPECT_NE(validateSimulationOptions(options), "");
}

}  // namespace
}  // namespace simulation
}  // namespace pda_registration
