// Every real case of ../shared/data, from seeded perturbations at docs/benchmark.md's 2°/0.10 m and
// 5°/0.25 m levels: multi-run PDA with default parameters must land within the ground truth's
// tolerance. The data must be present: a missing directory fails the test, it is not skipped.
#include "test_support/shared_data.hpp"

#include <gtest/gtest.h>

#include <initializer_list>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "pda_registration/core/error_metrics.hpp"
#include "pda_registration/core/pda_registration.hpp"
#include "pda_registration/core/perturbation.hpp"

namespace pda_registration {
namespace {

using testing_support::loadSharedCase;
using testing_support::SharedCase;

struct Tolerance {
  double translation;  ///< [m]
  double rotation_deg;
  double mean_distance;  ///< eq. 22 [m]
};

// factory_p64's ground truth is exact; the others come from registrations good to ~1-2 cm and
// 0.3-0.5 degrees (data README), so the assertions stay at 3 cm and at least 0.5 degrees.
Tolerance toleranceFor(const std::string& name) {
  if (name == "factory_p64") return {0.01, 0.1, 0.01};
  if (name == "room_scan") return {0.03, 0.75, 0.03};
  return {0.03, 0.5, 0.03};
}

// The dense-dense Kinect pair has 250k points on both sides: a 2 cm source voxel keeps the test
// fast, as docs/benchmark.md does for every method on this pair.
RegistrationParameters parametersFor(const std::string& name) {
  RegistrationParameters p;
  if (name == "kinect_pairwise") p.source_voxel_size = 0.02;
  return p;
}

// Each case is loaded and indexed once for all its trials.
struct LoadedCase {
  SharedCase data;
  std::unique_ptr<PdaRegistration> registration;
};

LoadedCase& loadedCase(const std::string& name) {
  static std::map<std::string, LoadedCase> cache;
  LoadedCase& entry = cache[name];
  if (!entry.registration) {
    std::string error;
    if (!loadSharedCase(name, &entry.data, &error)) {
      ADD_FAILURE() << "cannot read shared case '" << name << "' from "
                    << testing_support::sharedDataDirectory() << ": " << error;
      return entry;
    }
    entry.registration = std::make_unique<PdaRegistration>(parametersFor(name));
    EXPECT_TRUE(entry.registration->setTarget(entry.data.target));
  }
  return entry;
}

struct Trial {
  std::string case_name;
  double degrees, metres;
  uint64_t seed;
};

class SharedDataRegistration : public ::testing::TestWithParam<Trial> {};

TEST_P(SharedDataRegistration, MultiRunLandsWithinGroundTruthTolerance) {
  const Trial& trial = GetParam();
  LoadedCase& c = loadedCase(trial.case_name);
  ASSERT_TRUE(c.registration) << "shared data missing";
  const Eigen::Isometry3d initial =
      c.data.T_target_source * randomPerturbation(trial.degrees, trial.metres, trial.seed);
  const RegistrationResult r = c.registration->align(c.data.source, initial);
  const PoseError error = poseError(c.data.source, r.T_target_source, c.data.T_target_source);
  const PoseError initial_error = poseError(c.data.source, initial, c.data.T_target_source);
  const Tolerance tolerance = toleranceFor(trial.case_name);
  EXPECT_TRUE(r.converged) << r.reason;
  EXPECT_LT(error.translation, tolerance.translation);
  EXPECT_LT(error.rotation_deg, tolerance.rotation_deg);
  EXPECT_LT(error.mean_distance, tolerance.mean_distance);
  EXPECT_LT(error.mean_distance, 0.25 * initial_error.mean_distance);
  EXPECT_GT(r.inlier_fraction, 0.3);
  RecordProperty("eq22_error_m", std::to_string(error.mean_distance));
  RecordProperty("time_ms", std::to_string(r.time_ms));
}

std::vector<Trial> allTrials() {
  std::vector<Trial> trials;
  for (const std::string& name : testing_support::sharedCaseNames()) {
    for (const auto& level : {std::make_pair(2.0, 0.10), std::make_pair(5.0, 0.25)}) {
      for (uint64_t seed = 1; seed <= 3; ++seed) {
        trials.push_back({name, level.first, level.second, seed});
      }
    }
  }
  return trials;
}

INSTANTIATE_TEST_SUITE_P(AllCases, SharedDataRegistration, ::testing::ValuesIn(allTrials()),
                         [](const ::testing::TestParamInfo<Trial>& info) {
                           return info.param.case_name + "_" +
                                  std::to_string(static_cast<int>(info.param.degrees)) + "deg_" +
                                  std::to_string(static_cast<int>(info.param.metres * 100)) +
                                  "cm_seed" + std::to_string(info.param.seed);
                         });

// The sparse map as the target (the nodelet's target_cloud: sparse), with defaults. room_scan's
// 16-row scan cannot be the EM's target of the dense room (it diverged by 84 deg); the roles are
// swapped and the answer inverted. campus_hdl32 works in the usual direction.
TEST(SharedDataReversed, TheSparseMapAsTargetWorksWithDefaults) {
  for (const std::string name : {"room_scan", "campus_hdl32"}) {
    SharedCase c;
    std::string error;
    ASSERT_TRUE(loadSharedCase(name, &c, &error)) << error;
    PdaRegistration registration((RegistrationParameters()));
    ASSERT_TRUE(registration.setTarget(c.source));
    const Eigen::Isometry3d truth = c.T_target_source.inverse();
    for (uint64_t seed : {1u, 2u}) {
      const RegistrationResult r =
          registration.align(c.target, truth * randomPerturbation(5.0, 0.25, seed));
      const PoseError e = poseError(c.target, r.T_target_source, truth);
      EXPECT_TRUE(r.converged) << name << ": " << r.reason;
      EXPECT_LT(e.mean_distance, 0.03) << name << " seed " << seed;
      EXPECT_LT(e.rotation_deg, 0.75) << name << " seed " << seed;
      EXPECT_EQ(r.roles_swapped, name == "room_scan") << name;
    }
  }
}

// From 20 deg / 1 m (seed 7) the reversed room's first alignment rests unresolved (sigma 0.33 m)
// and the local start converges on a false fit 1.7 m off (support 0.12). It was kept, and the
// other direction, which finds the truth, never ran. Now they meet, both supports measured with
// the sparse scan's points against the dense room: the nearest sample there is a surface distance.
TEST(SharedDataReversed, TheOtherDirectionOutdoesAFalseLocalStartFromTwentyDegrees) {
  SharedCase c;
  std::string error;
  ASSERT_TRUE(loadSharedCase("room_scan", &c, &error)) << error;
  PdaRegistration registration((RegistrationParameters()));
  ASSERT_TRUE(registration.setTarget(c.source));
  const Eigen::Isometry3d truth = c.T_target_source.inverse();
  const RegistrationResult r =
      registration.align(c.target, truth * randomPerturbation(20.0, 1.0, 7));
  EXPECT_TRUE(r.converged) << r.reason;
  EXPECT_TRUE(r.roles_swapped);
  EXPECT_FALSE(r.local_start);
  EXPECT_LT(poseError(c.target, r.T_target_source, truth).mean_distance, 0.02);
}

// A shared case's source aligned to its map thinned to `voxel` [m], once per seed from a
// perturbation of `degrees` / `metres` of the ground truth (empty, with a failure, without the
// data).
struct ThinnedTrial {
  uint64_t seed;
  RegistrationResult result;
  PoseError error;
};
std::vector<ThinnedTrial> alignOnThinnedTarget(const std::string& name, double voxel,
                                               double degrees, double metres,
                                               std::initializer_list<uint64_t> seeds) {
  SharedCase c;
  std::string error;
  if (!loadSharedCase(name, &c, &error)) {
    ADD_FAILURE() << error;
    return {};
  }
  RegistrationParameters p;
  p.target_voxel_size = voxel;
  PdaRegistration registration(p);
  EXPECT_TRUE(registration.setTarget(c.target));
  std::vector<ThinnedTrial> trials;
  for (uint64_t seed : seeds) {
    const RegistrationResult r =
        registration.align(c.source, c.T_target_source * randomPerturbation(degrees, metres, seed));
    trials.push_back({seed, r, poseError(c.source, r.T_target_source, c.T_target_source)});
  }
  return trials;
}

// A coarse target: room_scan's map thinned to 0.5 m voxels (~1300 points). A few candidate sets
// flip between two neighbours from run to run and the refine runs cycle between two poses
// 0.2-0.6 mm apart; before the rest test (core/run_rest.hpp) seed 1 ran into the work bound (56
// runs) and came back "not converged" 2.6 cm from the truth. Now such runs are converged, well
// before the bound.
TEST(SharedDataThinned, RunsThatCycleOnACoarseTargetAreConverged) {
  const auto trials = alignOnThinnedTarget("room_scan", 0.5, 5.0, 0.25, {1u, 2u, 3u});
  ASSERT_EQ(trials.size(), 3u);
  for (const ThinnedTrial& t : trials) {
    EXPECT_TRUE(t.result.converged) << "seed " << t.seed << ": " << t.result.reason;
    EXPECT_LT(t.result.runs, 40) << "seed " << t.seed;
    EXPECT_LT(t.error.mean_distance, 0.04) << "seed " << t.seed;
  }
}

// A rigid lidar map, thinned: campus_hdl32 against its map at 0.5 m voxels. Its overlap's halves
// disagree by what the thinning leaves in each (its levels of the correlogram scatter), not as a
// warp; the cut test that triggers the least-squares polish (warp_polish.hpp) must not fire. Tested
// against the reported covariance (the correlogram's largest level) instead of its own wide null,
// it fired on every trial and polished the estimate 2.07 -> 2.12 cm at 1.3x the time.
TEST(SharedDataThinned, ARigidLidarMapIsNotPolished) {
  const auto trials = alignOnThinnedTarget("campus_hdl32", 0.5, 2.0, 0.1, {1u, 2u});
  ASSERT_EQ(trials.size(), 2u);
  for (const ThinnedTrial& t : trials) {
    EXPECT_TRUE(t.result.converged) << "seed " << t.seed << ": " << t.result.reason;
    EXPECT_EQ(t.result.disagreeing_halves, 0u) << "seed " << t.seed;
    EXPECT_FALSE(t.result.warp_polished) << "seed " << t.seed;
    EXPECT_LT(t.error.mean_distance, 0.03) << "seed " << t.seed;
  }
}

// The directory the tests read is reported, so a CI log shows the data was really used.
TEST(SharedData, EveryCaseIsPresent) {
  for (const std::string& name : testing_support::sharedCaseNames()) {
    SharedCase c;
    std::string error;
    EXPECT_TRUE(loadSharedCase(name, &c, &error)) << error;
    EXPECT_GT(c.target.size(), c.source.size() / 2) << name;
  }
  RecordProperty("data_dir", testing_support::sharedDataDirectory());
}

}  // namespace
}  // namespace pda_registration
