// pda_growing_probe: latency of the nodelet while its dense map grows like a SLAM map. The dense
// map of a case folder (target.pcd, in its stored order: pda_simulate's accumulated Kinect frames)
// or --tile N x N copies of it (the copy in place first, then the others) is published whole at
// --dense-rate Hz, --grow-step more points each time, from --grow-from up to --grow-to points
// (then held for --hold s), while the case's sparse cloud is published at --sparse-rate Hz with a
// new stamp each time, seeded on tf 3 deg / 0.15 m off the truth (--seed N draws the
// perturbation). Each ~transform is matched to its sparse cloud by stamp. Prints one JSON
// line (median_ms, p95_ms, max_dense_points, index_update_ms: the median of the nodelet's index
// updates, the answers' errors against the ground truth: median, max and how many over 5 cm, the
// points indexed (a subset when the map is thinned), folds, threads, and the latency per
// dense-map size band) and, with --samples FILE, writes one "dense_points,latency_ms,error_m"
// line per answer for the plot. Needs a running roscore and the nodelet
// (scripts/measure_latency --growing starts both). Every wait is bounded by --timeout.

#include <diagnostic_msgs/DiagnosticArray.h>
#include <geometry_msgs/TransformStamped.h>
#include <ros/ros.h>
#include <sensor_msgs/PointCloud2.h>
#include <tf2_eigen/tf2_eigen.h>
#include <tf2_msgs/TFMessage.h>

#include <algorithm>
#include <fstream>
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

int fail(const std::string& message) { return reportError("pda_growing_probe", message); }

// The case's target first (in place), then copies around it: the map grows outwards.
PointList tiledGrowingMap(const PointList& target, int tile) {
  if (tile <= 1) return target;
  const double spacing = separatedTileSpacing(target);
  PointList map = target;
  map.reserve(target.size() * static_cast<size_t>(tile * tile));
  const int half = tile / 2;
  for (int ring = 1; ring <= half; ++ring) {
    for (int i = -ring; i <= ring; ++i) {
      for (int j = -ring; j <= ring; ++j) {
        if (std::max(std::abs(i), std::abs(j)) != ring) continue;
        const Point shift(i * spacing, j * spacing, 0.0);
        for (const Point& p : target) map.push_back(p + shift);
      }
    }
  }
  return map;
}

}  // namespace

int main(int argc, char** argv) {
  ros::init(argc, argv, "pda_growing_probe", ros::init_options::AnonymousName);
  CommandLine cl({"case", "tile", "grow-from", "grow-to", "grow-step", "dense-rate", "sparse-rate",
                  "hold", "nodelet", "timeout", "samples", "label", "seed"},
                 {"help"});
  if (!cl.parse(argc, argv)) return fail(cl.error());
  if (cl.has("help") || !cl.has("case")) {
    std::cout << "usage: pda_growing_probe --case DIR [--tile 1] [--grow-from 100000]"
                 " [--grow-to 3000000] [--grow-step 75000] [--dense-rate 1] [--sparse-rate 10]"
                 " [--hold 5] [--nodelet pda_registration] [--timeout 60] [--samples FILE]"
                 " [--label TEXT] [--seed N]\n";
    return cl.has("help") ? 0 : 2;
  }
  int tile = 1, seed_draw = 1, grow_from = 100000, grow_to = 3000000, grow_step = 75000;
  double dense_rate = 1.0, sparse_rate = 10.0, hold = 5.0, timeout = 60.0;
  if (!cl.integer("tile", &tile, 1, 21) || !cl.integer("seed", &seed_draw, 0, 1000000) ||
      !cl.integer("grow-from", &grow_from, 1000, 100000000) ||
      !cl.integer("grow-to", &grow_to, 1000, 100000000) ||
      !cl.integer("grow-step", &grow_step, 1, 100000000) ||
      !cl.number("dense-rate", &dense_rate, 0.01, 100) ||
      !cl.number("sparse-rate", &sparse_rate, 0.01, 1000) || !cl.number("hold", &hold, 0, 3600) ||
      !cl.number("timeout", &timeout, 0.1, 3600)) {
    return fail(cl.error());
  }
  CaseFolder loaded;
  std::string error;
  if (!loadCaseFolder(cl.text("case"), &loaded, &error)) return fail(error);
  const PointList map = tiledGrowingMap(loaded.target, tile);
  if (map.size() < static_cast<size_t>(grow_to)) {
    std::ostringstream out;
    out << "the map has " << map.size() << " points, fewer than --grow-to " << grow_to
        << " (use a larger --tile)";
    return fail(out.str());
  }
  std_msgs::Header header;
  header.frame_id = "dense_map";
  const sensor_msgs::PointCloud2 whole = toPointCloud2(
      PointList(map.begin(), map.begin() + static_cast<long>(grow_to)), header);
  header.frame_id = "sparse_map";
  const sensor_msgs::PointCloud2 sparse_cloud = toPointCloud2(loaded.source, header);

  const std::string nodelet = cl.text("nodelet", "pda_registration");
  ros::NodeHandle node;
  ros::Publisher dense = node.advertise<sensor_msgs::PointCloud2>("dense_cloud", 1, true);
  ros::Publisher sparse = node.advertise<sensor_msgs::PointCloud2>("sparse_cloud", 10);
  ros::Publisher tf_static = node.advertise<tf2_msgs::TFMessage>("/tf_static", 1, true);
  std::mutex mutex;
  std::map<ros::Time, ros::WallTime> sent;  // sparse stamp -> when published
  size_t ready_points = 0;                  // the nodelet's map in use (diagnostics)
  // One per answer: the dense map in use, the latency and the answer's error (eq. 22 against
  // the case's ground truth: a fast answer that is wrong is no answer).
  struct Sample {
    size_t dense_points;
    double latency_ms, error_m;
  };
  std::vector<Sample> samples;
  std::map<size_t, std::pair<double, double>> index_updates;  // count -> wall, CPU [ms]
  // The last diagnostics' figures: points indexed (the map's subset when thinned), folds of the
  // trees, threads of the last alignment, results rejected and warm starts retried.
  size_t indexed_points = 0, folds = 0, threads_used = 0, rejected = 0, warm_start_retries = 0;
  double subset_voxel_cm = 0.0;
  ros::Subscriber results = node.subscribe<geometry_msgs::TransformStamped>(
      "/" + nodelet + "/transform", 100, [&](const geometry_msgs::TransformStamped::ConstPtr& m) {
        const ros::WallTime now = ros::WallTime::now();
        const double error_m =  // outside the lock: the diagnostics callback need not wait
            poseError(loaded.source, tf2::transformToEigen(m->transform), loaded.T_target_source)
                .mean_distance;
        std::lock_guard<std::mutex> lock(mutex);
        const auto it = sent.find(m->header.stamp);
        if (it == sent.end()) return;
        samples.push_back({ready_points, (now - it->second).toSec() * 1000.0, error_m});
        sent.erase(it);
      });
  ros::Subscriber diagnostics = node.subscribe<diagnostic_msgs::DiagnosticArray>(
      "/diagnostics", 10, [&](const diagnostic_msgs::DiagnosticArray::ConstPtr& m) {
        for (const auto& status : m->status) {
          if (status.name.find(nodelet + ": alignment") == std::string::npos) continue;
          std::map<std::string, std::string> values;
          for (const auto& entry : status.values) values[entry.key] = entry.value;
          std::lock_guard<std::mutex> lock(mutex);
          try {
            ready_points = std::stoul(values["dense map points"]);
            indexed_points = std::max<size_t>(indexed_points,
                                              std::stoul(values["indexed target points"]));
            folds = std::stoul(values["index folds"]);
            threads_used = std::stoul(values["threads used"]);
            subset_voxel_cm = std::stod(values["dense map subset voxel [cm]"]);
            const size_t count = std::stoul(values["index updates"]);
            if (count > 0) {
              index_updates[count] = {std::stod(values["index update time [ms]"]),
                                      std::stod(values["index update CPU time [ms]"])};
            }
          } catch (const std::exception&) {
            // an older nodelet without these keys: no index figures
          }
          try {
            rejected = std::stoul(values["rejected results"]);
            warm_start_retries = std::stoul(values["warm starts retried from the seed"]);
          } catch (const std::exception&) {
            // a nodelet without a warm start
          }
        }
      });
  ros::AsyncSpinner spinner(2);
  spinner.start();

  const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(timeout);
  const auto waitFor = [&](const std::function<bool()>& condition, const std::string& what) {
    while (!condition()) {
      if (!ros::ok()) {
        fail("interrupted while waiting for " + what);
        return false;
      }
      if (ros::WallTime::now() > deadline) {
        std::ostringstream out;
        out << "gave up after " << timeout << " s (--timeout) waiting for " << what;
        fail(out.str());
        return false;
      }
      ros::WallDuration(0.01).sleep();
    }
    return true;
  };
  if (!waitFor([&] { return sparse.getNumSubscribers() > 0; },
               "a subscriber to " + sparse.getTopic() + " (is the nodelet running?)") ||
      !waitFor([&] { return results.getNumPublishers() > 0; },
               "a publisher of " + results.getTopic()) ||
      !waitFor([&] { return tf_static.getNumSubscribers() > 0; },
               "the nodelet's tf listener to connect to /tf_static")) {
    return 1;
  }
  tf2_msgs::TFMessage seed_message;
  geometry_msgs::TransformStamped seed =
      tf2::eigenToTransform(loaded.T_target_source * randomPerturbation(3.0, 0.15, seed_draw));
  seed.header.stamp = ros::Time::now();
  seed.header.frame_id = "dense_map";
  seed.child_frame_id = "sparse_map";
  seed_message.transforms.push_back(seed);
  tf_static.publish(seed_message);

  // The first map, and the first alignment, before the clock starts: the nodelet is warm.
  const auto publishDense = [&](size_t points) {
    sensor_msgs::PointCloud2 message;
    message.header = whole.header;
    message.header.stamp = ros::Time::now();
    message.height = 1;
    message.width = static_cast<uint32_t>(points);
    message.fields = whole.fields;
    message.is_bigendian = whole.is_bigendian;
    message.point_step = whole.point_step;
    message.row_step = message.width * message.point_step;
    message.is_dense = whole.is_dense;
    message.data.assign(whole.data.begin(), whole.data.begin() + message.row_step);
    dense.publish(message);
  };
  size_t dense_points = static_cast<size_t>(grow_from);
  publishDense(dense_points);
  if (!waitFor(
          [&] {
            std::lock_guard<std::mutex> lock(mutex);
            return ready_points == dense_points;
          },
          "the nodelet's diagnostics to report the first " + std::to_string(dense_points) +
              "-point dense map")) {
    return 1;
  }

  const ros::WallDuration sparse_period(1.0 / sparse_rate), dense_period(1.0 / dense_rate);
  ros::WallTime next_sparse = ros::WallTime::now(), next_dense = next_sparse + dense_period;
  ros::WallTime hold_until;
  size_t sparse_sent = 0, dense_sent = 1;
  const ros::WallTime run_limit =
      ros::WallTime::now() +
      ros::WallDuration((grow_to - grow_from) / static_cast<double>(grow_step) / dense_rate + hold +
                        timeout);
  while (ros::ok()) {
    const ros::WallTime now = ros::WallTime::now();
    if (now > run_limit) return fail("the run took longer than planned plus --timeout");
    if (!hold_until.isZero() && now > hold_until) break;
    if (now >= next_sparse) {
      sensor_msgs::PointCloud2 message = sparse_cloud;
      message.header.stamp = ros::Time::now();
      {
        std::lock_guard<std::mutex> lock(mutex);
        sent[message.header.stamp] = ros::WallTime::now();
      }
      sparse.publish(message);
      ++sparse_sent;
      next_sparse += sparse_period;
    }
    if (now >= next_dense && hold_until.isZero()) {
      dense_points = std::min<size_t>(dense_points + grow_step, grow_to);
      publishDense(dense_points);
      ++dense_sent;
      next_dense += dense_period;
      if (dense_points == static_cast<size_t>(grow_to)) hold_until = now + ros::WallDuration(hold);
    }
    ros::WallDuration(0.002).sleep();
  }
  ros::WallDuration(1.0).sleep();  // answers in flight (latency p95 is well under a second)

  std::lock_guard<std::mutex> lock(mutex);
  if (samples.empty()) return fail("no sparse cloud was answered (see the nodelet's log)");
  std::vector<double> latencies, errors, updates, updates_cpu;
  size_t max_points = 0, over_5cm = 0;
  for (const Sample& s : samples) {
    latencies.push_back(s.latency_ms);
    errors.push_back(s.error_m);
    if (s.error_m > 0.05) ++over_5cm;
    max_points = std::max(max_points, s.dense_points);
  }
  for (const auto& u : index_updates) {
    updates.push_back(u.second.first);
    updates_cpu.push_back(u.second.second);
  }
  // Latency per band of dense-map size (a trend would show as rising medians).
  std::ostringstream bands;
  const size_t band = std::max<size_t>(1, (max_points + 4) / 5);
  bands << "[";
  for (size_t b = 0; b < 5; ++b) {
    std::vector<double> in_band;
    for (const Sample& s : samples) {
      if (s.dense_points >= b * band && s.dense_points < (b + 1) * band) {
        in_band.push_back(s.latency_ms);
      }
    }
    bands << (b ? "," : "") << "{\"up_to_points\":" << (b + 1) * band
          << ",\"count\":" << in_band.size() << ",\"median_ms\":"
          << (in_band.empty() ? 0.0 : percentile(in_band, 0.5)) << "}";
  }
  bands << "]";
  JsonLine json;
  json.add("label", cl.text("label", cl.text("case"))).add("sparse_points", loaded.source.size());
  json.add("sparse_sent", sparse_sent)
      .add("answered", samples.size())
      .add("dense_sent", dense_sent);
  json.add("median_ms", percentile(latencies, 0.5)).add("p95_ms", percentile(latencies, 0.95));
  json.add("max_ms", percentile(latencies, 1.0)).add("max_dense_points", max_points);
  json.add("index_update_ms", updates.empty() ? -1.0 : percentile(updates, 0.5));
  json.add("index_update_cpu_ms", updates.empty() ? -1.0 : percentile(updates_cpu, 0.5));
  json.add("index_update_max_ms", updates.empty() ? -1.0 : percentile(updates, 1.0));
  json.add("index_updates_seen", updates.size());
  json.add("max_indexed_points", indexed_points).add("subset_voxel_cm", subset_voxel_cm);
  json.add("index_folds", folds).add("threads_used", threads_used);
  json.add("error_median_m", percentile(errors, 0.5)).add("error_max_m", percentile(errors, 1.0));
  json.add("answers_over_5cm", over_5cm);
  json.add("rejected", rejected).add("warm_start_retries", warm_start_retries);
  json.addRaw("bands", bands.str());
  std::cout << json.str() << std::endl;
  if (cl.has("samples")) {
    std::ofstream out(cl.text("samples"));
    out << "dense_points,latency_ms,error_m\n";
    for (const Sample& s : samples) {
      out << s.dense_points << "," << s.latency_ms << "," << s.error_m << "\n";
    }
    if (!out) return fail("cannot write " + cl.text("samples"));
  }
  return 0;
}
