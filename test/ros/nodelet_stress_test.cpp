// rostest: load. Sparse maps of 100k points at 20 Hz and dense maps of 1M points at 1 Hz (three
// different maps cycled, so every one is indexed from scratch) for ~duration seconds, built from
// the real factory_p64 clouds (jittered copies). The nodelet must stay responsive (its tf edge and
// diagnostics keep flowing), drop stale inputs instead of queueing them, keep latency under
// 300 ms (median) at 3 alignments a second or more, fit its source budget to the feed's rate,
// keep its memory flat, and publish only estimates on the ground truth. Prints one "stress:"
// line with the figures (RSS at start and end, latency median and p95, drops).
#include <gtest/gtest.h>
#include <tf2_msgs/TFMessage.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <random>
#include <thread>

#include "nodelet_harness.hpp"
#include "pda_registration/core/error_metrics.hpp"
#include "pda_registration/core/perturbation.hpp"
#include "pda_registration/ros/point_cloud_conversion.hpp"
#include "pda_registration/tools/statistics.hpp"
#include "test_support/shared_data.hpp"

namespace pda_registration {
namespace {

using testing_support::NodeletHarness;
using testing_support::toEigen;

// `count` points drawn cyclically from `base`, each moved by Gaussian noise: a denser cloud of
// the same scene, different for every seed.
PointList jitteredCopies(const PointList& base, size_t count, double sigma, uint32_t seed) {
  std::mt19937 random(seed);
  std::normal_distribution<double> noise(0.0, sigma);
  PointList out;
  out.reserve(count);
  for (size_t i = 0; i < count; ++i) {
    out.push_back(base[i % base.size()] + Point(noise(random), noise(random), noise(random)));
  }
  return out;
}

// Largest gap between consecutive times, and before the first / after the last within [from, to].
double longestGap(std::vector<ros::WallTime> times, ros::WallTime from, ros::WallTime to) {
  times.erase(std::remove_if(times.begin(), times.end(),
                             [&](const ros::WallTime& t) { return t < from || t > to; }),
              times.end());
  if (times.empty()) return (to - from).toSec();
  double gap = std::max((times.front() - from).toSec(), (to - times.back()).toSec());
  for (size_t i = 1; i < times.size(); ++i) gap = std::max(gap, (times[i] - times[i - 1]).toSec());
  return gap;
}

// One diagnostics status's input counters, read together so they describe the same moment.
struct InputCounts {
  double received = 0.0, dropped = 0.0, aligned = 0.0;
};

InputCounts inputCounts(const diagnostic_msgs::DiagnosticStatus& status) {
  InputCounts counts;
  for (const diagnostic_msgs::KeyValue& entry : status.values) {
    if (entry.key == "sparse clouds received") counts.received = std::stod(entry.value);
    if (entry.key == "dropped stale inputs") counts.dropped = std::stod(entry.value);
    if (entry.key == "alignments") counts.aligned = std::stod(entry.value);
  }
  return counts;
}

TEST(NodeletStress, StaysResponsiveDropsStaleInputsAndKeepsMemoryFlat) {
  ros::NodeHandle node, private_node("~");
  const double duration = private_node.param("duration", 30.0);
  NodeletHarness harness("pda_registration");
  testing_support::SharedCase data;
  ASSERT_TRUE(loadCaseAndConnect(&harness, "factory_p64", &data));

  std::mutex mutex;
  std::vector<ros::WallTime> tf_times, diagnostics_times;
  ros::Subscriber tf =
      node.subscribe<tf2_msgs::TFMessage>("/tf", 1000, [&](const tf2_msgs::TFMessage::ConstPtr& m) {
        for (const auto& t : m->transforms) {
          if (t.child_frame_id != "sparse_map_aligned") continue;
          std::lock_guard<std::mutex> lock(mutex);
          tf_times.push_back(ros::WallTime::now());
        }
      });
  ros::Subscriber diagnostics = node.subscribe<diagnostic_msgs::DiagnosticArray>(
      "/diagnostics", 100, [&](const diagnostic_msgs::DiagnosticArray::ConstPtr& m) {
        for (const auto& status : m->status) {
          if (status.name.find("pda_registration: alignment") == std::string::npos) continue;
          std::lock_guard<std::mutex> lock(mutex);
          diagnostics_times.push_back(ros::WallTime::now());
        }
      });
  std::vector<double> latencies_ms;
  ros::Subscriber transforms = node.subscribe<geometry_msgs::TransformStamped>(
      "/pda_registration/transform", 100, [&](const geometry_msgs::TransformStamped::ConstPtr& m) {
        std::lock_guard<std::mutex> lock(mutex);
        latencies_ms.push_back((ros::Time::now() - m->header.stamp).toSec() * 1000.0);
      });

  // Three different 1M-point maps, cycled, and one 100k-point sparse map. Three, not two: the
  // nodelet keeps two maps (double-buffered) and a map equal to the one two back would be found
  // already indexed; with three, every map is indexed from scratch (the worst case).
  std_msgs::Header header;
  header.frame_id = "dense_map";
  const size_t extra = 1000000 - data.target.size();
  std::vector<sensor_msgs::PointCloud2> dense_maps;
  for (uint32_t seed : {1u, 2u, 3u}) {
    PointList map = data.target;
    const PointList more = jitteredCopies(data.target, extra, 0.005, seed);
    map.insert(map.end(), more.begin(), more.end());
    dense_maps.push_back(toPointCloud2(map, header));
  }
  header.frame_id = "sparse_map";
  const sensor_msgs::PointCloud2 sparse =
      toPointCloud2(jitteredCopies(data.source, 100000, 0.01, 3), header);
  ASSERT_EQ(dense_maps[0].width, 1000000u);
  ASSERT_EQ(sparse.width, 100000u);
  ASSERT_TRUE(harness.publishSeed(data.T_target_source * randomPerturbation(2.0, 0.1, 5),
                                  "dense_map", "sparse_map"));

  std::atomic<bool> running{true};
  std::atomic<size_t> sparse_sent{0}, dense_sent{0};
  std::thread dense_feed([&] {
    for (size_t i = 0; running; ++i) {
      sensor_msgs::PointCloud2 m = dense_maps[i % dense_maps.size()];
      m.header.stamp = ros::Time::now();
      harness.publishRaw(m, true);
      ++dense_sent;
      ros::WallDuration(1.0).sleep();
    }
  });
  std::thread sparse_feed([&] {
    while (running) {
      sensor_msgs::PointCloud2 m = sparse;
      m.header.stamp = ros::Time::now();
      harness.publishRaw(m, false);
      ++sparse_sent;
      ros::WallDuration(0.05).sleep();
    }
  });

  // Warm-up until the first estimate, then the measured period.
  ASSERT_TRUE(harness.waitForTransformsBeyond(0, 60.0)) << "no alignment under load";
  ros::WallDuration(2.0).sleep();
  ASSERT_TRUE(harness.waitForFreshDiagnostics(5.0));
  const InputCounts counts_start = inputCounts(harness.lastDiagnostics());
  const double rss_start = std::stod(harness.diagnosticValue("resident memory [MB]"));
  const size_t transforms_start = harness.transformCount();
  const ros::WallTime start = ros::WallTime::now();
  // RSS every second: a leak climbs steadily; the working set of an alignment comes and goes
  // (tens of MB either way), so the halves of the run are compared by their medians.
  std::vector<double> rss_samples = {rss_start};
  while ((ros::WallTime::now() - start).toSec() < duration) {
    ros::WallDuration(std::min(1.0, duration - (ros::WallTime::now() - start).toSec())).sleep();
    rss_samples.push_back(std::stod(harness.diagnosticValue("resident memory [MB]")));
  }
  const ros::WallTime end = ros::WallTime::now();
  ASSERT_TRUE(harness.waitForFreshDiagnostics(5.0));
  const InputCounts counts_end = inputCounts(harness.lastDiagnostics());
  const double rss_end = std::stod(harness.diagnosticValue("resident memory [MB]"));
  const double budget = std::stod(harness.diagnosticValue("source budget"));
  const double period_ms = std::stod(harness.diagnosticValue("sparse cloud period [ms]"));
  rss_samples.push_back(rss_end);
  running = false;
  dense_feed.join();
  sparse_feed.join();

  const size_t aligned = harness.transformCount() - transforms_start;
  const double dropped = counts_end.dropped - counts_start.dropped;
  // Inputs received in the measured period that were neither aligned nor dropped as stale: at most
  // the one in the mailbox and the one being aligned at each end of the period.
  const double held = (counts_end.received - counts_start.received) - dropped -
                      (counts_end.aligned - counts_start.aligned);
  std::vector<double> latencies;
  double tf_gap, diagnostics_gap;
  {
    std::lock_guard<std::mutex> lock(mutex);
    latencies.assign(latencies_ms.begin() + static_cast<long>(transforms_start),
                     latencies_ms.end());
    tf_gap = longestGap(tf_times, start, end);
    diagnostics_gap = longestGap(diagnostics_times, start, end);
  }
  const size_t half = rss_samples.size() / 2;
  const double first_half_rss = percentile({rss_samples.begin(), rss_samples.begin() + half}, 0.5);
  const double second_half_rss = percentile({rss_samples.begin() + half, rss_samples.end()}, 0.5);
  std::string rss_series;
  for (size_t i = 0; i < rss_samples.size(); i += 5)
    rss_series += " " + std::to_string(static_cast<int>(rss_samples[i]));
  std::cout << "stress: " << duration << " s, sent " << sparse_sent << " sparse (100k) + "
            << dense_sent << " dense (1M); " << aligned << " alignments accepted, " << dropped
            << " stale inputs dropped, " << held << " held; latency median "
            << percentile(latencies, 0.5) << " ms, p95 " << percentile(latencies, 0.95)
            << " ms; RSS " << rss_start << " -> " << rss_end << " MB (halves' medians "
            << first_half_rss << ", " << second_half_rss << "; every 5 s:" << rss_series
            << "); longest gaps: tf " << tf_gap * 1000.0 << " ms, diagnostics "
            << diagnostics_gap * 1000.0 << " ms; source budget " << budget << " points, period "
            << period_ms << " ms" << std::endl;

  // Responsive: the 10 Hz tf re-broadcast never paused for a second, nor the 1 Hz diagnostics
  // for three.
  EXPECT_LT(tf_gap, 1.0);
  EXPECT_LT(diagnostics_gap, 3.0);
  // Not queueing: every input was either aligned or dropped as stale (how many of each depends
  // on the machine: a 2-core one drops ~80 %, a fast one under half), and latency did not pile up.
  EXPECT_LE(std::abs(held), 4.0) << "inputs received but neither aligned nor dropped";
  EXPECT_LT(percentile(latencies, 0.95), 10000.0);
  // Alignments do not wait for index builds: when each alignment waited for its map's index the
  // median was 1055 ms at 1 alignment/s; indexing beside the alignments and the source budget
  // bring it to ~270-330 ms and 3-4/s on a 2-core machine (the figure itself is measured by the
  // 120 s run in docs/hardening.md, not asserted here: it moves +-15 % with the machine). The
  // bounds catch a return of the waiting at half its cost.
  EXPECT_LE(percentile(latencies, 0.5), 600.0);
  EXPECT_GE(static_cast<double>(aligned), 2.0 * duration);
  // Keeping up (ros/rate_budget.hpp): the node measured the feed's period (a 50 ms sleep after
  // each publish) and, its alignments of the 15000-point budget taking longer than half of it,
  // shrank the budget; never below a quarter of max_source_points. The period is a running mean
  // of arrival intervals weighing the newest by 0.2, read at a moment of the run: a cloud that
  // waited behind a busy callback and arrived right after the one before pulls it 10 ms down
  // (44.8 ms once, 2026-12-06), so the bound allows two such. Unmeasured it reads 0; counted per
  // alignment instead of per arrival, 250-330 ms.
  EXPECT_GT(period_ms, 30.0);
  EXPECT_LT(period_ms, 100.0);
  EXPECT_LT(budget, 15000.0) << "alignments over half the period, yet the full budget";
  EXPECT_GE(budget, 3750.0);
  // Flat memory: the second half of the run sits no higher than the first (plus noise). Holding
  // on to every 16 MB dense map would add ~240 MB per 15 s.
  EXPECT_LT(second_half_rss, first_half_rss + 50.0) << "RSS grew:" << rss_series;
  // Every published estimate is on the ground truth (factory_p64's is exact).
  for (const geometry_msgs::TransformStamped& t : harness.transforms()) {
    EXPECT_LT(poseError(data.source, toEigen(t.transform), data.T_target_source).mean_distance,
              0.02);
  }
}

}  // namespace
}  // namespace pda_registration
