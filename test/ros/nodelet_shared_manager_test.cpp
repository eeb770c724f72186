// rostest: the map-alignment nodelet shares a one-thread nodelet manager with a relay nodelet
// (the rest of the robot's perception). While the nodelet is kept busy with long alignments on
// the 453k-point factory map, the relay must deliver its 50 Hz stream without stalls: the
// alignment runs on the nodelet's own worker thread, never in the manager's callback thread.
#include <gtest/gtest.h>
#include <std_msgs/Header.h>

#include <algorithm>
#include <atomic>
#include <thread>

#include "nodelet_harness.hpp"
#include "pda_registration/core/error_metrics.hpp"
#include "pda_registration/core/perturbation.hpp"
#include "pda_registration/tools/statistics.hpp"
#include "test_support/shared_data.hpp"

namespace pda_registration {
namespace {

using testing_support::NodeletHarness;
using testing_support::toEigen;

TEST(NodeletSharedManager, OtherNodeletsKeepFlowingWhileAligning) {
  NodeletHarness harness("pda_registration");
  testing_support::SharedCase data;
  ASSERT_TRUE(loadCaseAndConnect(&harness, "factory_p64", &data));

  ros::NodeHandle node;
  ros::Publisher heartbeat = node.advertise<std_msgs::Header>("/heartbeat_relay/input", 100);
  std::mutex mutex;
  // Each beat carries its send time (wall clock): its latency through the relay is the manager's
  // delay, whatever hiccups the sending loop itself has on a loaded machine.
  std::vector<ros::WallTime> relayed;
  std::vector<double> latencies_ms;
  ros::Subscriber relay = node.subscribe<std_msgs::Header>(
      "/heartbeat_relay/output", 100, [&](const std_msgs::Header::ConstPtr& m) {
        const ros::WallTime now = ros::WallTime::now();
        std::lock_guard<std::mutex> lock(mutex);
        relayed.push_back(now);
        latencies_ms.push_back((now.toSec() - m->stamp.toSec()) * 1000.0);
      });
  const ros::WallTime connect_deadline = ros::WallTime::now() + ros::WallDuration(20.0);
  while ((heartbeat.getNumSubscribers() == 0 || relay.getNumPublishers() == 0) &&
         ros::WallTime::now() < connect_deadline) {
    ros::WallDuration(0.05).sleep();
  }
  ASSERT_GT(relay.getNumPublishers(), 0u) << "the relay nodelet did not come up";

  // Slow, exhaustive alignments (every one of the source's 24.5k points in every run, 20
  // candidates, 20 EM iterations, tight epsilons, each from the seed: no warm start; the source
  // budget not fitted to the feed's 0.3 s): a few hundred ms each, against a relay period of
  // 20 ms. (With the default budget of 15000 points they took about 150 ms once the approach
  // ended on its tail, c3f33f5: too close to the bound below.)
  ASSERT_TRUE(harness.reconfigure(testing_support::ParameterChange()
                                      .set("warm_start", false)
                                      .set("alignment_share", 0.0)
                                      .set("max_source_points", 0)
                                      .set("coarse_stride", 1)
                                      .set("k", 20)
                                      .set("em_iterations", 20)
                                      .set("translation_epsilon", 1e-6)
                                      .set("rotation_epsilon", 1e-6)));
  ASSERT_TRUE(harness.publishSeed(data.T_target_source * randomPerturbation(3.0, 0.15, 2),
                                  "dense_map", "sparse_map"));
  harness.publishDense(data.target, "dense_map");
  ros::WallDuration(2.0).sleep();

  // 10 s: the relay's stream at 50 Hz, and a sparse cloud every 0.3 s so the worker never idles.
  std::atomic<bool> running{true};
  std::thread sparse_feed([&] {
    while (running) {
      harness.publishSparse(data.source, "sparse_map");
      ros::WallDuration(0.3).sleep();
    }
  });
  const size_t transforms_before = harness.transformCount();
  {
    std::lock_guard<std::mutex> lock(mutex);
    relayed.clear();
    latencies_ms.clear();
  }
  int sent = 0;
  const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(10.0);
  while (ros::WallTime::now() < end) {
    std_msgs::Header beat;
    beat.seq = static_cast<uint32_t>(sent++);
    beat.stamp.fromSec(ros::WallTime::now().toSec());
    heartbeat.publish(beat);
    ros::WallDuration(0.02).sleep();
  }
  running = false;
  sparse_feed.join();
  ros::WallDuration(0.5).sleep();  // the last beats arrive

  // The nodelet was busy the whole time with alignments of about a second ...
  const size_t alignments = harness.transformCount() - transforms_before;
  EXPECT_GE(alignments, 3u);
  ASSERT_TRUE(harness.waitForFreshDiagnostics(5.0));
  const double alignment_ms = std::stod(harness.diagnosticValue("alignment time [ms]"));
  // A stall of one alignment must stand out from the relay's 20 ms period.
  ASSERT_GT(alignment_ms, 150.0) << "alignments too short for this test to mean anything";

  // ... and the relay was not held up for anywhere near one alignment. A manager blocked by the
  // alignments delays every beat sent during one (hundreds here), so the 95th percentile is
  // far beyond half an alignment; one scheduling hiccup of a loaded machine delays a few beats.
  std::vector<ros::WallTime> times;
  std::vector<double> latencies;
  {
    std::lock_guard<std::mutex> lock(mutex);
    times = relayed;
    latencies = latencies_ms;
  }
  EXPECT_GE(times.size(), static_cast<size_t>(0.95 * sent))
      << "relayed " << times.size() << " of " << sent;
  double longest_gap_ms = 0.0;
  for (size_t i = 1; i < times.size(); ++i) {
    longest_gap_ms = std::max(longest_gap_ms, (times[i] - times[i - 1]).toSec() * 1000.0);
  }
  const double p95_ms = percentile(latencies, 0.95), max_ms = percentile(latencies, 1.0);
  EXPECT_LT(p95_ms, 0.5 * alignment_ms) << "the relay was held up: p95 latency " << p95_ms
                                        << " ms during " << alignment_ms << " ms alignments";
  std::cout << "relay: " << times.size() << "/" << sent << " delivered, latency median "
            << percentile(latencies, 0.5) << " ms, p95 " << p95_ms << " ms, max " << max_ms
            << " ms, longest gap " << longest_gap_ms << " ms; " << alignments << " alignments of ~"
            << alignment_ms << " ms" << std::endl;

  for (const geometry_msgs::TransformStamped& t : harness.transforms()) {
    EXPECT_LT(poseError(data.source, toEigen(t.transform), data.T_target_source).mean_distance,
              0.01);
  }
}

}  // namespace
}  // namespace pda_registration
