// rostest: the warm start (core/warm_start.hpp) in the running nodelet. With warm_start off an
// alignment starts from the seed; switched on, the next starts from the seed corrected by the
// last accepted correction, needs fewer runs and lands as close; off again, the node repeats its
// answer from the seed exactly (same map index, cloud and seed: the alignment is deterministic).
// And the deadline for warm alignments (deadline_periods).
#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "nodelet_harness.hpp"
#include "pda_registration/core/error_metrics.hpp"
#include "pda_registration/core/perturbation.hpp"
#include "test_support/shared_data.hpp"

namespace pda_registration {
namespace {

using testing_support::NodeletHarness;
using testing_support::toEigen;

struct Answer {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  int runs = 0;
  std::string warm_start;
};

// Publishes the scan, waits for its ~transform and for the diagnostics that count it.
::testing::AssertionResult alignOnce(NodeletHarness* harness, const PointList& scan,
                                     Answer* answer) {
  harness->publishSparse(scan, "sparse_map");
  if (!harness->waitForNextTransform(60.0)) return ::testing::AssertionFailure() << "no answer";
  std::string detail;
  if (!harness->waitForAcceptedToMatchTransforms(10.0, &detail))
    return ::testing::AssertionFailure() << "diagnostics never counted it: " << detail;
  answer->T = toEigen(harness->lastTransform().transform);
  answer->runs = std::stoi(harness->diagnosticValue("runs"));
  answer->warm_start = harness->diagnosticValue("warm start");
  return ::testing::AssertionSuccess();
}

// room_scan's map and a seed publisher with a constant 5 deg / 0.25 m error, the latched map and
// the static seed given time to arrive first.
::testing::AssertionResult serveRoomScan(NodeletHarness* harness,
                                         testing_support::SharedCase* data) {
  const ::testing::AssertionResult loaded = loadCaseAndConnect(harness, "room_scan", data);
  if (!loaded) return loaded;
  const Eigen::Isometry3d seed = data->T_target_source * randomPerturbation(5.0, 0.25, 4);
  if (!harness->publishSeed(seed, "dense_map", "sparse_map"))
    return ::testing::AssertionFailure() << "the seed did not reach tf";
  harness->publishDense(data->target, "dense_map");
  ros::WallDuration(0.5).sleep();
  return ::testing::AssertionSuccess();
}

TEST(NodeletWarmStart, StartsFromTheLastCorrectionUnlessSwitchedOff) {
  NodeletHarness harness("pda_registration");
  testing_support::SharedCase data;
  ASSERT_TRUE(serveRoomScan(&harness, &data));

  Answer first, cold, warm, cold_again;
  ASSERT_TRUE(alignOnce(&harness, data.source, &first));
  EXPECT_EQ(first.warm_start, "no accepted estimate yet");
  // The first sparse cloud tells the keeper its spacing, and the room's map is re-indexed as its
  // subset at that spacing: the alignments compared below all run on that index.
  const ros::WallTime until = ros::WallTime::now() + ros::WallDuration(20.0);
  while (harness.diagnosticValue("dense map subset voxel [cm]") == "0" &&
         ros::WallTime::now() < until) {
    harness.waitForFreshDiagnostics(2.0);
  }
  ASSERT_NE(harness.diagnosticValue("dense map subset voxel [cm]"), "0");

  ASSERT_TRUE(harness.reconfigure(testing_support::ParameterChange().set("warm_start", false)));
  ASSERT_TRUE(alignOnce(&harness, data.source, &cold));
  EXPECT_EQ(cold.warm_start, "off");
  ASSERT_TRUE(harness.reconfigure(testing_support::ParameterChange().set("warm_start", true)));
  ASSERT_TRUE(alignOnce(&harness, data.source, &warm));
  EXPECT_EQ(warm.warm_start, "used");
  EXPECT_LT(warm.runs, cold.runs);
  for (const Answer* answer : {&first, &cold, &warm}) {
    const PoseError e = poseError(data.source, answer->T, data.T_target_source);
    EXPECT_LT(e.translation, 0.03);
    EXPECT_LT(e.rotation_deg, 0.75);
  }
  // The two answers agree far better than either does with the (registration-made) truth.
  EXPECT_LT(poseError(data.source, warm.T, cold.T).mean_distance, 0.005);

  // Off again: the node starts from the seed and repeats its cold answer exactly.
  ASSERT_TRUE(harness.reconfigure(testing_support::ParameterChange().set("warm_start", false)));
  ASSERT_TRUE(alignOnce(&harness, data.source, &cold_again));
  EXPECT_EQ(cold_again.runs, cold.runs);
  EXPECT_TRUE(cold_again.T.isApprox(cold.T, 1e-9));
  EXPECT_EQ(harness.diagnosticValue("warm starts retried from the seed"), "0");
  EXPECT_TRUE(harness.warnings().empty()) << harness.warnings().front();
  std::printf("runs: first %d, from the seed %d, warm %d\n", first.runs, cold.runs, warm.runs);
}

// The deadline (deadline_periods): a warm alignment still moving after that many periods of the
// sparse clouds is abandoned, nothing published for its cloud, counted in the diagnostics, but
// never more than 5 in a row; 0 lifts the limit. (The launch's nodelet may hold the test above's
// warm start and counts: only differences are compared.)
TEST(NodeletWarmStart, AWarmAlignmentPastItsDeadlineIsAbandoned) {
  NodeletHarness harness("pda_registration");
  testing_support::SharedCase data;
  ASSERT_TRUE(serveRoomScan(&harness, &data));
  // 1 % of a 10 Hz period: 1 ms, less than any alignment's first run.
  ASSERT_TRUE(harness.reconfigure(
      testing_support::ParameterChange().set("warm_start", true).set("deadline_periods", 0.01)));
  const auto outOfTime = [&] {
    const std::string value = harness.diagnosticValue("warm alignments out of time");
    return value.empty() ? 0 : std::stoi(value);
  };
  ASSERT_TRUE(harness.waitForFreshDiagnostics(5.0));
  const int out_of_time_before = outOfTime();

  // Clouds at 10 Hz: the first may run from the seed (never cut); once the period is measured,
  // every warm alignment has 1 ms.
  constexpr int kClouds = 12;
  const size_t answered_before = harness.transformCount();
  for (int i = 0; i < kClouds; ++i) {
    harness.publishSparse(data.source, "sparse_map");
    ros::WallDuration(0.1).sleep();
  }
  // (Not harness.waitFor: its condition runs under the lock that diagnosticValue takes.)
  const ros::WallTime until = ros::WallTime::now() + ros::WallDuration(30.0);
  while (outOfTime() - out_of_time_before < 3 && ros::WallTime::now() < until) {
    harness.waitForFreshDiagnostics(2.0);
  }
  ASSERT_GE(outOfTime() - out_of_time_before, 3) << "warm alignments out of time";
  ros::WallDuration(1.0).sleep();  // the last cloud's alignment, whatever it does
  ASSERT_TRUE(harness.waitForFreshDiagnostics(5.0));
  const int abandoned = outOfTime() - out_of_time_before;
  const size_t answered = harness.transformCount() - answered_before;
  EXPECT_LE(answered + static_cast<size_t>(abandoned), static_cast<size_t>(kClouds));
  EXPECT_LT(answered, static_cast<size_t>(kClouds - 2));
  // Never more than 5 cut in a row: the sixth runs its course, so even a machine that never
  // meets the deadline answers.
  EXPECT_LE(static_cast<size_t>(abandoned), 5 * answered);
  EXPECT_NE(harness.logText().find("out of time"), std::string::npos);

  // No limit: the next warm alignment answers, close to the truth.
  ASSERT_TRUE(harness.reconfigure(testing_support::ParameterChange().set("deadline_periods", 0.0)));
  const size_t before_last = harness.transformCount();
  harness.publishSparse(data.source, "sparse_map");
  ASSERT_TRUE(harness.waitForTransformsBeyond(before_last, 60.0));
  ASSERT_TRUE(harness.waitForFreshDiagnostics(5.0));
  EXPECT_EQ(harness.diagnosticValue("warm start"), "used");
  EXPECT_EQ(outOfTime() - out_of_time_before, abandoned);
  const PoseError e =
      poseError(data.source, toEigen(harness.lastTransform().transform), data.T_target_source);
  EXPECT_LT(e.translation, 0.03);
  EXPECT_LT(e.rotation_deg, 0.75);
  std::printf("deadline: %zu of %d clouds answered, %d abandoned\n", answered, kClouds, abandoned);
}

}  // namespace
}  // namespace pda_registration
