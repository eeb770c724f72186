// rostest: a bag looping on simulated time (rosbag play --loop --clock). Each loop jumps time
// back by the bag's length; the nodelet must go on aligning every pass, keep its tf edge and its
// diagnostics flowing after each jump, recognise the re-played dense map as unchanged, and never
// publish a result off the ground truth.
#include <gtest/gtest.h>
#include <rosgraph_msgs/Clock.h>

#include <atomic>

#include "nodelet_harness.hpp"
#include "pda_registration/core/error_metrics.hpp"
#include "test_support/shared_data.hpp"

namespace pda_registration {
namespace {

using testing_support::NodeletHarness;
using testing_support::toEigen;

// What had arrived when /clock jumped back.
struct Jump {
  size_t transforms;
  size_t diagnostics;
};

TEST(NodeletTimeJump, KeepsAligningAcrossLoopsOfABag) {
  ros::NodeHandle node, private_node("~");
  testing_support::SharedCase data;
  std::string error;
  ASSERT_TRUE(testing_support::loadSharedCase(private_node.param<std::string>("case", "room_scan"),
                                              &data, &error))
      << error;
  NodeletHarness harness("pda_registration");
  ASSERT_TRUE(harness.waitForOutputConnections(30.0));
  std::mutex mutex;
  std::vector<Jump> jumps;
  ros::Time last_clock;
  ros::Subscriber clock = node.subscribe<rosgraph_msgs::Clock>(
      "/clock", 100, [&](const rosgraph_msgs::Clock::ConstPtr& m) {
        std::lock_guard<std::mutex> lock(mutex);
        if (!last_clock.isZero() && m->clock + ros::Duration(0.5) < last_clock) {
          jumps.push_back({harness.transformCount(), harness.diagnosticsCount()});
        }
        last_clock = m->clock;
      });
  const auto jump_count = [&] {
    std::lock_guard<std::mutex> lock(mutex);
    return jumps.size();
  };

  // The bag waits for a subscriber on every topic it holds; this one is the test's alone.
  std::atomic<size_t> truths_heard{0};
  ros::Subscriber ground_truth = node.subscribe<geometry_msgs::TransformStamped>(
      "/ground_truth", 10,
      [&truths_heard](const geometry_msgs::TransformStamped::ConstPtr&) { ++truths_heard; });

  // Three passes of the bag: two jumps back, then the third pass's first alignment.
  const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(120.0);
  while (jump_count() < 2 && ros::WallTime::now() < deadline) ros::WallDuration(0.1).sleep();
  std::vector<Jump> seen;  // a copy: a third jump may grow `jumps` meanwhile
  {
    std::lock_guard<std::mutex> lock(mutex);
    seen = jumps;
  }
  ASSERT_GE(seen.size(), 2u) << "the bag did not loop twice (" << truths_heard
                             << " ground-truth messages heard)";
  const size_t after_second_jump = seen[1].transforms;
  ASSERT_TRUE(harness.waitForTransformsBeyond(after_second_jump, 30.0))
      << "no alignment after the clock jumped back";

  // Every pass aligned: transforms arrived before the first jump and between the jumps.
  EXPECT_GT(seen[0].transforms, 0u);
  EXPECT_GT(seen[1].transforms, seen[0].transforms) << "nothing aligned in the second pass";
  for (const geometry_msgs::TransformStamped& t : harness.transforms()) {
    const PoseError e = poseError(data.source, toEigen(t.transform), data.T_target_source);
    EXPECT_LT(e.mean_distance, 0.03);
    EXPECT_LT(e.rotation_deg, 0.75);
  }

  // Diagnostics kept flowing after the jump (they run on the wall clock) ...
  ASSERT_TRUE(harness.waitForFreshDiagnostics(5.0)) << "diagnostics stopped after the jump";
  EXPECT_GT(harness.diagnosticsCount(), seen[1].diagnostics);
  EXPECT_EQ(harness.diagnosticValue("rejected results"), "0");
  std::string detail;
  EXPECT_TRUE(harness.waitForAcceptedToMatchTransforms(10.0, &detail)) << detail;
  // ... the re-played dense map was recognised, not re-indexed every pass ...
  EXPECT_GE(std::stoi(harness.diagnosticValue("dense clouds unchanged (not re-indexed)")), 2);
  // ... and the corrected edge is on tf again in the new pass (listeners cleared theirs).
  const Eigen::Isometry3d on_tf = harness.lookup("dense_map", "sparse_map_aligned", 10.0);
  EXPECT_LT(poseError(data.source, on_tf, data.T_target_source).mean_distance, 0.03);
}

}  // namespace
}  // namespace pda_registration
