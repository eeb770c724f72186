// pda_latency_probe: measures the nodelet's end-to-end latency, sparse cloud published ->
// ~transform received, on a case folder (target.pcd, source.pcd, T_target_source.txt). Publishes
// the dense map (latched) and a perturbed seed on tf once, then the sparse cloud --count times,
// each after the previous result and no sooner than a sensor at --rate Hz (10) would send it
// (the nodelet fits its source budget to that period, ros/rate_budget.hpp), and prints one JSON
// line with the median / p95 / max latency and the error of the last estimate. With --tile N the
// dense map is N x N copies of the case's target (the middle one in place; e.g. --tile 7 on
// room_scan: 5.5M points), and the JSON adds what the nodelet's diagnostics say of it: points
// indexed, cropping, resident memory. Needs a running roscore and the nodelet
// (scripts/measure_latency starts both). It cannot hang: the seed goes out once the nodelet's tf
// listener has connected to /tf_static, a cloud that got no answer within --resend-after seconds is
// sent again (counted as "resent"), and every wait ends at
// --timeout with an error naming what it waited for.

#include <diagnostic_msgs/DiagnosticArray.h>
#include <geometry_msgs/TransformStamped.h>
#include <ros/ros.h>
#include <sensor_msgs/PointCloud2.h>
#include <tf2_eigen/tf2_eigen.h>
#include <tf2_msgs/TFMessage.h>

#include <algorithm>
#include <functional>
#include <iostream>
#include <map>
#include <mutex>
#include <sstream>
#include <vector>

#include "pda_registration/core/error_metrics.hpp"
#include "pda_registration/core/perturbation.hpp"
#include "pda_registration/ros/point_cloud_conversion.hpp"
#include "pda_registration/tools/case_folder.hpp"
#include "pda_registration/tools/command_line.hpp"
#include "pda_registration/tools/json_line.hpp"
#include "pda_registration/tools/statistics.hpp"
#include "pda_registration/tools/tiled_map.hpp"

using namespace pda_registration;

namespace {

int fail(const std::string& message) { return reportError("pda_latency_probe", message); }

}  // namespace

int main(int argc, char** argv) {
  ros::init(argc, argv, "pda_latency_probe", ros::init_options::AnonymousName);
  CommandLine cl({"case", "count", "nodelet", "rate", "resend-after", "timeout", "tile"}, {"help"});
  if (!cl.parse(argc, argv)) return fail(cl.error());
  if (cl.has("help") || !cl.has("case")) {
    std::cout << "usage: pda_latency_probe --case DIR [--count 20] [--nodelet pda_registration]"
                 " [--rate 10] [--timeout 60] [--resend-after 5] [--tile N]\n";
    return cl.has("help") ? 0 : 2;
  }
  int count = 20, tile = 1;
  double timeout = 60.0, resend_after = 5.0, rate = 10.0;
  if (!cl.integer("count", &count, 1, 100000) || !cl.number("timeout", &timeout, 0.1, 3600) ||
      !cl.number("resend-after", &resend_after, 0.01, 3600) ||
      !cl.number("rate", &rate, 0.01, 1000) || !cl.integer("tile", &tile, 1, 101)) {
    return fail(cl.error());
  }
  if (tile % 2 == 0) return fail("--tile must be odd (the middle copy holds the ground truth)");
  CaseFolder loaded;
  std::string error;
  if (!loadCaseFolder(cl.text("case"), &loaded, &error)) return fail(error);
  const PointList target =
      tile == 1 ? loaded.target
                : tileCloud(loaded.target, tile, tile, separatedTileSpacing(loaded.target)).points;
  const PointList& source = loaded.source;
  const Eigen::Isometry3d truth = loaded.T_target_source;

  const std::string nodelet = cl.text("nodelet", "pda_registration");
  ros::NodeHandle node;
  ros::Publisher dense = node.advertise<sensor_msgs::PointCloud2>("dense_cloud", 1, true);
  ros::Publisher sparse = node.advertise<sensor_msgs::PointCloud2>("sparse_cloud", 1);
  // The seed goes out on our own latched /tf_static publisher, so we can see when the nodelet's
  // tf listener has connected to it (a latched message reaches a listener only once connected).
  ros::Publisher tf_static = node.advertise<tf2_msgs::TFMessage>("/tf_static", 1, true);
  // Each sparse cloud is answered by a ~transform with its stamp; an answer is matched to the
  // send it answers, so a late answer to a re-sent cloud is never taken for the next one's.
  std::map<ros::Time, ros::WallTime> sent;  // stamp -> when it was published (this cloud only)
  bool answered = false;
  double answer_ms = 0.0;
  std::vector<double> latencies;
  geometry_msgs::TransformStamped last;
  std::mutex mutex;
  ros::Subscriber results = node.subscribe<geometry_msgs::TransformStamped>(
      "/" + nodelet + "/transform", 10, [&](const geometry_msgs::TransformStamped::ConstPtr& m) {
        const ros::WallTime now = ros::WallTime::now();
        std::lock_guard<std::mutex> lock(mutex);
        const auto it = sent.find(m->header.stamp);
        if (it == sent.end() || answered) return;
        answer_ms = (now - it->second).toSec() * 1000.0;
        answered = true;
        last = *m;
      });
  // The nodelet's own view (diagnostics, 1 Hz): map size, index size, cropping, memory.
  std::map<std::string, std::string> diagnostics;
  size_t diagnostics_received = 0;
  // The alignments' thread count as each status reported it (the nodelet uses the cores other
  // processes leave idle, so a busy neighbour shows here).
  std::vector<std::string> threads_seen;
  ros::Subscriber diagnostics_subscriber = node.subscribe<diagnostic_msgs::DiagnosticArray>(
      "/diagnostics", 10, [&](const diagnostic_msgs::DiagnosticArray::ConstPtr& m) {
        for (const auto& status : m->status) {
          if (status.name.find(nodelet + ": alignment") == std::string::npos) continue;
          std::lock_guard<std::mutex> lock(mutex);
          for (const auto& entry : status.values) {
            diagnostics[entry.key] = entry.value;
            if (entry.key == "threads used") threads_seen.push_back(entry.value);
          }
          ++diagnostics_received;
        }
      });
  const auto diagnostic = [&](const std::string& key) {
    std::lock_guard<std::mutex> lock(mutex);
    const auto it = diagnostics.find(key);
    return it == diagnostics.end() ? std::string() : it->second;
  };
  ros::AsyncSpinner spinner(1);
  spinner.start();

  // Every wait below is bounded by the overall --timeout and says what it waited for.
  const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(timeout);
  const auto waitFor = [&](const std::function<bool()>& condition, const std::string& what,
                           std::string* failure) {
    while (!condition()) {
      if (!ros::ok()) {
        *failure = "interrupted while waiting for " + what;
        return false;
      }
      if (ros::WallTime::now() > deadline) {
        std::ostringstream out;
        out << "gave up after " << timeout << " s (--timeout) waiting for " << what;
        *failure = out.str();
        return false;
      }
      ros::WallDuration(0.01).sleep();
    }
    return true;
  };
  std::string failure;
  if (!waitFor([&] { return sparse.getNumSubscribers() > 0; },
               "a subscriber to " + sparse.getTopic() + " (is the nodelet running?)", &failure) ||
      !waitFor(
          [&] { return results.getNumPublishers() > 0; },
          "a publisher of " + results.getTopic() + " (is the nodelet named '" + nodelet + "'?)",
          &failure) ||
      !waitFor([&] { return tf_static.getNumSubscribers() > 0; },
               "the nodelet's tf listener to connect to /tf_static", &failure)) {
    return fail(failure);
  }
  tf2_msgs::TFMessage seed_message;
  geometry_msgs::TransformStamped seed =
      tf2::eigenToTransform(truth * randomPerturbation(3.0, 0.15, 1));
  seed.header.stamp = ros::Time::now();
  seed.header.frame_id = "dense_map";
  seed.child_frame_id = "sparse_map";
  seed_message.transforms.push_back(seed);
  tf_static.publish(seed_message);
  std_msgs::Header header;
  header.frame_id = "dense_map";
  header.stamp = ros::Time::now();
  const ros::WallTime dense_published = ros::WallTime::now();
  dense.publish(toPointCloud2(target, header));
  // The map is in place (and, unless it is large enough to crop, indexed) before the first
  // sparse cloud: wait until the diagnostics report it.
  if (!waitFor([&] { return diagnostic("dense map points") == std::to_string(target.size()); },
               "the nodelet's diagnostics to report the " + std::to_string(target.size()) +
                   "-point dense map",
               &failure)) {
    return fail(failure);
  }
  const double dense_ready_ms = (ros::WallTime::now() - dense_published).toSec() * 1000.0;

  // A cloud that got no answer within --resend-after (dropped by the nodelet, e.g. one that
  // arrived before the seed) is sent again with a new stamp; its latency counts from the re-send.
  header.frame_id = "sparse_map";
  const sensor_msgs::PointCloud2 cloud = toPointCloud2(source, header);
  int resent = 0;
  ros::WallTime last_send;
  for (int i = 0; i < count && ros::ok(); ++i) {
    // A sensor's period between clouds, even when the answer came sooner.
    if (!last_send.isZero()) {
      const ros::WallDuration wait =
          last_send + ros::WallDuration(1.0 / rate) - ros::WallTime::now();
      if (wait > ros::WallDuration(0.0)) wait.sleep();
    }
    last_send = ros::WallTime::now();
    {
      std::lock_guard<std::mutex> lock(mutex);
      sent.clear();
      answered = false;
    }
    bool done = false;
    while (!done) {
      sensor_msgs::PointCloud2 message = cloud;
      message.header.stamp = ros::Time::now();
      {
        std::lock_guard<std::mutex> lock(mutex);
        sent[message.header.stamp] = ros::WallTime::now();
      }
      sparse.publish(message);
      const ros::WallTime resend_at = ros::WallTime::now() + ros::WallDuration(resend_after);
      while (true) {
        {
          std::lock_guard<std::mutex> lock(mutex);
          if (answered) {
            latencies.push_back(answer_ms);
            done = true;
            break;
          }
        }
        if (!ros::ok()) return fail("interrupted while waiting for a ~transform");
        if (ros::WallTime::now() > deadline) {
          std::ostringstream out;
          out << "gave up after " << timeout << " s (--timeout) waiting for the ~transform of "
              << "sparse cloud " << i + 1 << " of " << count << " (sent " << resent
              << " times again, every " << resend_after << " s without an answer)";
          return fail(out.str());
        }
        if (ros::WallTime::now() > resend_at) {
          ++resent;
          break;
        }
        ros::WallDuration(0.001).sleep();
      }
    }
  }
  if (latencies.size() != static_cast<size_t>(count)) return fail("interrupted");
  // Diagnostics published after the last alignment.
  size_t seen;
  {
    std::lock_guard<std::mutex> lock(mutex);
    seen = diagnostics_received;
  }
  while (ros::ok() && ros::WallTime::now() < deadline) {
    {
      std::lock_guard<std::mutex> lock(mutex);
      if (diagnostics_received > seen) break;
    }
    ros::WallDuration(0.05).sleep();
  }
  const std::string indexed = diagnostic("indexed target points");
  const std::string cropped = diagnostic("target cropped");
  const std::string resident = diagnostic("resident memory [MB]");
  const std::string alignment_ms = diagnostic("alignment time [ms]");
  std::lock_guard<std::mutex> lock(mutex);
  const PoseError e = poseError(source, tf2::transformToEigen(last), truth);
  JsonLine json;
  json.add("case", cl.text("case")).add("count", static_cast<int>(latencies.size()));
  json.add("resent", resent);
  json.add("median_ms", percentile(latencies, 0.5)).add("p95_ms", percentile(latencies, 0.95));
  json.add("max_ms", percentile(latencies, 1.0)).add("first_ms", latencies.front());
  std::ostringstream each;
  for (size_t i = 0; i < latencies.size(); ++i) each << (i ? "," : "[") << latencies[i];
  json.addRaw("latencies_ms", each.str() + "]");
  json.add("dense_points", target.size()).add("dense_ready_ms", dense_ready_ms);
  json.addRaw("indexed_points", indexed.empty() ? "null" : indexed);
  json.add("target_cropped", cropped == "True" || cropped == "true");
  json.addRaw("last_alignment_ms", alignment_ms.empty() ? "null" : alignment_ms);
  json.addRaw("nodelet_rss_mb", resident.empty() ? "null" : resident);
  std::string threads = "[";
  for (size_t i = 0; i < threads_seen.size(); ++i) threads += (i ? "," : "") + threads_seen[i];
  json.addRaw("threads_used_1hz", threads + "]");
  json.add("mean_distance", e.mean_distance).add("rot_err_deg", e.rotation_deg);
  json.add("trans_err_m", e.translation);
  std::cout << json.str() << std::endl;
  return 0;
}
