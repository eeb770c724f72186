// pda_bag_eval: tune PDA on a recorded bag. Every sparse map message is aligned to the latest
// dense map before it, seeded by the bag's tf, once per parameter set of a grid (--k 1,5,10
// --nu 5,inf ...). Writes every outcome as CSV and prints a markdown summary, one row per set,
// ranked best first (against the bag's ground truth when it has one).
// Exit codes: 0 evaluated, 2 bad usage, an unreadable bag or nothing to evaluate.

#include <algorithm>
#include <chrono>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <limits>
#include <sstream>
#include <vector>

#include "pda_registration/core/error_metrics.hpp"
#include "pda_registration/core/pda_registration.hpp"
#include "pda_registration/ros/point_cloud_conversion.hpp"
#include "pda_registration/tools/bag_eval_row.hpp"
#include "pda_registration/tools/bag_eval_summary.hpp"
#include "pda_registration/tools/bag_maps.hpp"
#include "pda_registration/tools/bag_parameter_grid.hpp"
#include "pda_registration/tools/bag_transforms.hpp"
#include "pda_registration/tools/command_line.hpp"
#include "pda_registration/tools/progress_line.hpp"
#include "pda_registration/tools/settings_flags.hpp"

using namespace pda_registration;

namespace {

const char* kUsage =
    "usage: pda_bag_eval --bag FILE [options] [registration flags]\n"
    "  Aligns every sparse map in the bag to the latest dense map before it, seeded by the bag's\n"
    "  tf (dense <- sparse at the sparse map's stamp, else the latest before it), once per\n"
    "  parameter set. --k, --nu, --radius and --anisotropy take comma-separated grids\n"
    "  (--k 1,5,10 --nu 5,inf): every combination is one set. Prints a markdown summary, one\n"
    "  row per set, best first.\n"
    "  --bag FILE                 the bag to read\n"
    "  --dense-topic T            dense map, sensor_msgs/PointCloud2 (/dense_map)\n"
    "  --sparse-topic T           sparse map, sensor_msgs/PointCloud2 (/sparse_map)\n"
    "  --ground-truth-topic T     geometry_msgs/TransformStamped dense <- sparse; when the bag "
    "has\n"
    "                             it, sets are ranked by success rate, then median eq. 22\n"
    "                             (/ground_truth; '' = ignore)\n"
    "  --success M                success threshold on eq. 22 [m] (0.05)\n"
    "  --csv FILE                 write one row per (parameter set, sparse map)\n"
    "  --summary FILE             also write the summary there\n"
    "  --max-messages N           evaluate only the first N sparse maps (all)\n"
    "  --help\n";

constexpr const char* kToolName = "pda_bag_eval";

int usageError(const std::string& message) { return reportError(kToolName, message); }

std::string formatStamp(const ros::Time& stamp) {
  std::ostringstream text;
  text << std::fixed << std::setprecision(3) << stamp.toSec();
  return text.str();
}

// A re-published (latched) map with the same bytes needs no new index.
bool sameCloud(const sensor_msgs::PointCloud2& a, const sensor_msgs::PointCloud2& b) {
  return a.header.frame_id == b.header.frame_id && a.width == b.width && a.height == b.height &&
         a.point_step == b.point_step && a.row_step == b.row_step &&
         a.is_bigendian == b.is_bigendian && a.fields == b.fields && a.data == b.data;
}

}  // namespace

int main(int argc, char** argv) {
  CommandLine cl =
      commandLineWithSettings({"bag", "dense-topic", "sparse-topic", "ground-truth-topic", "csv",
                               "summary", "max-messages", "success"});
  if (!cl.parse(argc, argv)) return usageError(cl.error());
  if (cl.has("help")) {
    std::cout << kUsage << settingsFlagsHelp();
    return 0;
  }

  BagEvalOptions options;
  if (!cl.has("bag")) return usageError("--bag is required");
  options.bag_path = cl.text("bag");
  options.topics.dense = cl.text("dense-topic", options.topics.dense);
  options.topics.sparse = cl.text("sparse-topic", options.topics.sparse);
  options.ground_truth_topic_given = cl.has("ground-truth-topic");
  options.ground_truth_topic = cl.text("ground-truth-topic", options.ground_truth_topic);
  options.csv_path = cl.text("csv");
  options.summary_path = cl.text("summary");
  if (options.topics.dense.empty() || options.topics.sparse.empty()) {
    return usageError("--dense-topic and --sparse-topic must not be empty");
  }
  if (options.topics.dense == options.topics.sparse) {
    return usageError("--dense-topic and --sparse-topic must differ (both '" +
                      options.topics.dense + "')");
  }
  std::vector<ParameterSet> sets;
  if (!cl.number("success", &options.success_threshold, 0.0, 1e6) ||
      !cl.integer("max-messages", &options.max_messages, 1, std::numeric_limits<int>::max()) ||
      !readParameterGrid(&cl, &sets)) {
    return usageError(cl.error());
  }

  BagMaps bag;
  BagTransforms transforms;
  std::string error;
  if (!bag.open(options.bag_path, options.topics, &error)) return usageError(error);
  if (options.ground_truth_topic_given && !options.ground_truth_topic.empty() &&
      bag.topicType(options.ground_truth_topic).empty()) {
    return usageError("bag '" + options.bag_path + "' has no topic '" + options.ground_truth_topic +
                      "'; its topics: " + bag.describeTopics());
  }
  try {
    if (!transforms.load(bag, options.ground_truth_topic, &error)) return usageError(error);
  } catch (const std::exception& e) {
    return usageError("cannot read bag '" + options.bag_path + "': " + e.what());
  }
  // Output files are opened before the alignments, so an unusable path fails at once.
  std::ofstream csv, summary_file;
  if (cl.has("csv")) {
    csv.open(options.csv_path);
    if (!csv) return usageError("--csv: cannot write '" + options.csv_path + "'");
  }
  if (cl.has("summary")) {
    summary_file.open(options.summary_path);
    if (!summary_file) return usageError("--summary: cannot write '" + options.summary_path + "'");
  }

  const bool ground_truth = transforms.hasGroundTruth();
  if (csv.is_open()) csv << csvHeader(ground_truth) << std::flush;

  const size_t messages =
      std::min(bag.messageCount(options.topics.sparse), static_cast<size_t>(options.max_messages));
  ProgressLine progress(kToolName, sets.size() * messages, sets.size(), messages);
  PdaRegistration registration(sets.front().parameters);
  // The target is indexed lazily: a dense map replaced before any sparse map needs it costs
  // nothing, and one index serves every set and every sparse map until the next dense map.
  sensor_msgs::PointCloud2::ConstPtr pending_dense, indexed_dense;
  std::vector<EvaluationRow> rows;
  RunCounts counts;
  size_t message_index = 0;

  const auto updateTarget = [&]() {
    if (!pending_dense) return;
    const sensor_msgs::PointCloud2::ConstPtr candidate = pending_dense;
    pending_dense.reset();
    if (indexed_dense && sameCloud(*candidate, *indexed_dense)) {
      indexed_dense = candidate;
      return;
    }
    const std::string stamp = formatStamp(candidate->header.stamp);
    CloudConversion dense = fromPointCloud2(*candidate);
    if (!dense.ok()) {
      progress.note("warning: dense map at t = " + stamp + " is malformed (" + dense.error +
                    "); keeping the previous one");
      return;
    }
    const auto start = std::chrono::steady_clock::now();
    if (!registration.setTarget(std::move(dense.points))) {
      indexed_dense.reset();
      progress.note("warning: dense map at t = " + stamp + " could not be indexed");
      return;
    }
    counts.index_ms +=
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    ++counts.targets_indexed;
    indexed_dense = candidate;
  };

  // Evaluates one sparse map with every set; returns why it was skipped, empty when it was not.
  const auto evaluate = [&](const MapMessage& message) -> std::string {
    if (!message.cloud) return message.error;
    updateTarget();
    if (!indexed_dense) return "no usable dense map on " + options.topics.dense + " before it";
    const CloudConversion sparse = fromPointCloud2(*message.cloud);
    if (!sparse.ok()) return "malformed PointCloud2: " + sparse.error;
    const std::string& dense_frame = indexed_dense->header.frame_id;
    const std::string& sparse_frame = message.cloud->header.frame_id;
    const Seed seed = transforms.seed(dense_frame, sparse_frame, message.stamp);
    if (seed.source == SeedSource::kNone) {
      return "no tf seed '" + dense_frame + "' <- '" + sparse_frame + "': " + seed.detail;
    }
    ++(seed.source == SeedSource::kTfAtStamp ? counts.seeds_at_stamp : counts.seeds_latest);
    Eigen::Isometry3d T_ground_truth = Eigen::Isometry3d::Identity();
    if (ground_truth) {
      T_ground_truth = transforms.groundTruthAt(message.stamp);
      counts.seed_eq22.push_back(
          poseError(sparse.points, seed.T_dense_sparse, T_ground_truth).mean_distance);
    }
    for (size_t s = 0; s < sets.size(); ++s) {
      progress.starting(s + 1, message_index);
      EvaluationRow row;
      row.set_id = sets[s].id;
      row.message = static_cast<int>(message_index);
      row.stamp = message.stamp.toSec();
      row.seed = seed.source == SeedSource::kTfAtStamp ? "at_stamp" : "latest";
      registration.setParameters(sets[s].parameters);
      row.result = registration.align(sparse.points, seed.T_dense_sparse);
      if (ground_truth) {
        row.has_ground_truth = true;
        row.error = poseError(sparse.points, row.result.T_target_source, T_ground_truth);
        row.seed_error = poseError(sparse.points, seed.T_dense_sparse, T_ground_truth);
      }
      if (csv.is_open()) csv << csvLine(sets[s], row, ground_truth) << std::flush;
      rows.push_back(std::move(row));
    }
    ++counts.evaluated;
    return "";
  };

  try {
    bag.forEachMap([&](const MapMessage& message) {
      if (message.dense) {
        if (message.cloud) {
          pending_dense = message.cloud;
        } else {
          progress.note("warning: dense map at t = " + formatStamp(message.stamp) +
                        " is unreadable (" + message.error + "); keeping the previous one");
        }
        return true;
      }
      if (++message_index > messages) return false;
      const std::string skipped = evaluate(message);
      if (!skipped.empty()) {
        counts.skipped.push_back("message " + std::to_string(message_index) +
                                 " (t = " + formatStamp(message.stamp) + "): " + skipped);
        progress.note("warning: skipped " + counts.skipped.back());
      }
      progress.finished(sets.size(), message_index);
      return true;
    });
  } catch (const std::exception& e) {
    progress.end();
    return usageError("cannot read bag '" + options.bag_path + "': " + e.what());
  }
  progress.end();

  if (counts.evaluated == 0) {
    return usageError("no sparse map in '" + options.bag_path + "' could be evaluated (" +
                      std::to_string(counts.skipped.size()) + " skipped)");
  }
  const std::string markdown = summaryMarkdown(options, bag, transforms, cl, sets, rows, counts);
  std::cout << markdown << std::flush;
  if (summary_file.is_open()) {
    summary_file << markdown;
    summary_file.close();
    if (!summary_file) return usageError("--summary: cannot write '" + options.summary_path + "'");
  }
  if (csv.is_open()) {
    csv.close();
    if (!csv) return usageError("--csv: cannot write '" + options.csv_path + "'");
  }
  return 0;
}
