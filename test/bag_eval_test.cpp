// pda_bag_eval run as a user runs it, on a small simulated office bag: ground truth recovered on
// every message, one summary row per parameter set of a grid, skipped messages, one-line errors.
// The grid and the ranking on their own: bag_eval_grid_ranking_test.cpp.
#include <gtest/gtest.h>
#include <rosbag/bag.h>
#include <std_msgs/String.h>

#include <algorithm>
#include <map>
#include <set>

#include "pda_registration/core/error_metrics.hpp"
#include "pda_registration/core/perturbation.hpp"
#include "pda_registration/ros/point_cloud_conversion.hpp"
#include "pda_registration/simulation/map_bag_writer.hpp"
#include "pda_registration/simulation/map_simulation.hpp"
#include "test_support/bag_eval_output.hpp"
#include "test_support/command_run.hpp"

namespace pda_registration {
namespace {

using simulation::MapBagOptions;
using simulation::SimulatedMaps;
using testing_support::CommandRun;
using testing_support::Csv;
using testing_support::lineCount;
using testing_support::readCsv;
using testing_support::readFile;
using testing_support::runCommand;
using testing_support::summaryRows;
using testing_support::temporaryPath;

constexpr double kSeedErrorDeg = 3.0, kSeedErrorM = 0.15;

// One small office pair for the whole program: simulating it is the slow part.
struct SimulatedBag {
  SimulatedMaps maps;
  Eigen::Isometry3d T_seed;
  std::string path;  ///< 3 sparse messages, tf seed and ground truth throughout
};

const SimulatedBag& simulatedBag() {
  static const SimulatedBag bag = [] {
    simulation::MapSimulationOptions options;
    options.seed = 5;
    options.kinect_frames = 8;
    options.velodyne_revolutions = 2;
    SimulatedBag made{simulation::simulateMaps(options), Eigen::Isometry3d::Identity(),
                      temporaryPath("office.bag")};
    made.T_seed = made.maps.T_target_source * randomPerturbation(kSeedErrorDeg, kSeedErrorM, 5);
    MapBagOptions bag_options;
    bag_options.sparse_messages = 3;
    std::string error;
    if (!simulation::writeMapBag(made.path, made.maps.dense, made.maps.sparse,
                                 made.maps.T_target_source, made.T_seed, bag_options, nullptr,
                                 &error)) {
      ADD_FAILURE() << error;
    }
    return made;
  }();
  return bag;
}

CommandRun runBagEval(const std::string& arguments) {
  return runCommand(PDA_BAG_EVAL_BINARY, arguments);
}

// The translation of a CSV row's estimate against the simulation's ground truth: checked here,
// independently of the errors the tool computes itself.
double translationError(const Csv& csv, size_t row, const Eigen::Isometry3d& T_ground_truth) {
  const Eigen::Vector3d t(csv.number(row, "x"), csv.number(row, "y"), csv.number(row, "z"));
  return (t - T_ground_truth.translation()).norm();
}

TEST(BagEval, RecoversTheGroundTruthOnEveryMessage) {
  const SimulatedBag& bag = simulatedBag();
  const std::string csv_path = temporaryPath("default.csv");
  const std::string summary_path = temporaryPath("default.md");
  const CommandRun run = runBagEval("--bag " + bag.path + " --radius 0.5 --csv " + csv_path +
                                    " --summary " + summary_path);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_EQ(readFile(summary_path), run.out);

  const Csv csv = readCsv(csv_path);
  ASSERT_EQ(csv.rows.size(), 3u);
  for (size_t i = 0; i < csv.rows.size(); ++i) {
    SCOPED_TRACE("message " + csv.rows[i].at("message"));
    EXPECT_EQ(csv.rows[i].at("message"), std::to_string(i + 1));
    EXPECT_EQ(csv.rows[i].at("seed"), "at_stamp");
    EXPECT_EQ(csv.rows[i].at("converged"), "1") << csv.rows[i].at("reason");
    EXPECT_LT(csv.number(i, "eq22_m"), 0.03);
    // The seed really was off, and the tool measured it as the simulation made it.
    const double seed_eq22 =
        poseError(bag.maps.sparse, bag.T_seed, bag.maps.T_target_source).mean_distance;
    EXPECT_GT(csv.number(i, "seed_eq22_m"), 0.1);
    EXPECT_NEAR(csv.number(i, "seed_eq22_m"), seed_eq22, 1e-4);  // float32 in the bag
    EXPECT_LT(translationError(csv, i, bag.maps.T_target_source), 0.03);
  }
  const auto rows = summaryRows(run.out);
  ASSERT_EQ(rows.size(), 1u) << run.out;
  EXPECT_NE(rows[0][6].find("3/3"), std::string::npos) << run.out;  // success column
}

TEST(BagEval, GridGivesOneSummaryRowPerParameterSet) {
  const SimulatedBag& bag = simulatedBag();
  const std::string csv_path = temporaryPath("grid.csv");
  const CommandRun run =
      runBagEval("--bag " + bag.path + " --k 1,5 --nu 5,inf --radius 0.5 --csv " + csv_path);
  ASSERT_EQ(run.exit_code, 0) << run.err;

  const Csv csv = readCsv(csv_path);
  ASSERT_EQ(csv.rows.size(), 4u * 3u);  // sets x messages
  std::map<std::string, int> rows_per_set;
  std::set<std::string> combinations;
  for (const auto& row : csv.rows) {
    ++rows_per_set[row.at("set")];
    combinations.insert(row.at("k") + "/" + row.at("nu"));
    EXPECT_EQ(row.at("radius"), "0.5");
  }
  EXPECT_EQ(rows_per_set, (std::map<std::string, int>{{"1", 3}, {"2", 3}, {"3", 3}, {"4", 3}}));
  EXPECT_EQ(combinations, (std::set<std::string>{"1/5", "1/inf", "5/5", "5/inf"}));

  // Columns: rank, set, k, nu, radius, anisotropy, success, median eq.22, ...
  const auto rows = summaryRows(run.out);
  ASSERT_EQ(rows.size(), 4u) << run.out;
  std::set<std::string> summarized;
  for (size_t i = 0; i < rows.size(); ++i) {
    EXPECT_EQ(rows[i][0], std::to_string(i + 1));
    summarized.insert(rows[i][2] + "/" + rows[i][3]);
    if (i == 0) continue;
    const int successes = std::stoi(rows[i][6]), previous = std::stoi(rows[i - 1][6]);
    EXPECT_LE(successes, previous) << run.out;
    if (successes == previous) {
      EXPECT_GE(std::stod(rows[i][7]), std::stod(rows[i - 1][7])) << run.out;
    }
  }
  EXPECT_EQ(summarized, combinations);
}

TEST(BagEval, ReportsAndSkipsMalformedAndUnseededMessages) {
  const SimulatedBag& bag = simulatedBag();
  // One good sparse map at t = 101 s; tf and ground truth end at 102 s. Then, appended: a
  // truncated cloud, a cloud in a frame tf does not know, and a good cloud after tf has ended.
  const std::string path = temporaryPath("skips.bag");
  MapBagOptions options;
  options.sparse_messages = 1;
  std::string error;
  ASSERT_TRUE(simulation::writeMapBag(path, bag.maps.dense, bag.maps.sparse,
                                      bag.maps.T_target_source, bag.T_seed, options, nullptr,
                                      &error))
      << error;
  {
    rosbag::Bag append(path, rosbag::bagmode::Append);
    std_msgs::Header header;
    header.frame_id = options.sparse_frame;
    header.stamp = ros::Time(options.start_time + 2.5);
    sensor_msgs::PointCloud2 truncated = toPointCloud2(bag.maps.sparse, header);
    truncated.data.resize(truncated.data.size() / 2);
    append.write("/sparse_map", header.stamp, truncated);
    header.frame_id = "elsewhere";
    header.stamp = ros::Time(options.start_time + 3.0);
    append.write("/sparse_map", header.stamp, toPointCloud2(bag.maps.sparse, header));
    header.frame_id = options.sparse_frame;
    header.stamp = ros::Time(options.start_time + 4.0);
    append.write("/sparse_map", header.stamp, toPointCloud2(bag.maps.sparse, header));
  }
  const std::string csv_path = temporaryPath("skips.csv");
  const CommandRun run =
      runBagEval("--bag " + path + " --radius 0.5 --ground-truth-topic '' --csv " + csv_path);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.err.find("skipped message 2"), std::string::npos) << run.err;
  EXPECT_NE(run.err.find("malformed PointCloud2"), std::string::npos) << run.err;
  EXPECT_NE(run.err.find("skipped message 3"), std::string::npos) << run.err;
  EXPECT_NE(run.err.find("no tf seed 'dense_map' <- 'elsewhere'"), std::string::npos) << run.err;
  EXPECT_NE(run.out.find("ground truth: none"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("Skipped:"), std::string::npos) << run.out;

  const Csv csv = readCsv(csv_path);
  EXPECT_EQ(std::count(csv.header.begin(), csv.header.end(), "eq22_m"), 0);
  ASSERT_EQ(csv.rows.size(), 2u);
  EXPECT_EQ(csv.rows[0].at("message"), "1");
  EXPECT_EQ(csv.rows[0].at("seed"), "at_stamp");
  EXPECT_EQ(csv.rows[1].at("message"), "4");
  EXPECT_EQ(csv.rows[1].at("seed"), "latest");  // after tf's last message: the latest before it
  for (size_t i = 0; i < csv.rows.size(); ++i) {
    EXPECT_LT(translationError(csv, i, bag.maps.T_target_source), 0.03);
  }
  ASSERT_EQ(summaryRows(run.out).size(), 1u) << run.out;
}

TEST(BagEval, MissingTopicsAreNamed) {
  const std::string path = temporaryPath("chatter.bag");
  {
    rosbag::Bag chatter(path, rosbag::bagmode::Write);
    std_msgs::String text;
    text.data = "not a map";
    chatter.write("/chatter", ros::Time(1.0), text);
  }
  CommandRun run = runBagEval("--bag " + path);
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_EQ(lineCount(run.err), 1u) << run.err;
  EXPECT_NE(run.err.find("no topic '/dense_map'"), std::string::npos) << run.err;
  EXPECT_NE(run.err.find("/chatter (std_msgs/String)"), std::string::npos) << run.err;

  run = runBagEval("--bag " + simulatedBag().path + " --sparse-topic /velodyne_map");
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_EQ(lineCount(run.err), 1u) << run.err;
  EXPECT_NE(run.err.find("no topic '/velodyne_map'"), std::string::npos) << run.err;
  EXPECT_NE(run.err.find("/sparse_map (sensor_msgs/PointCloud2)"), std::string::npos) << run.err;
}

TEST(BagEval, BadArgumentsExitTwoWithOneLine) {
  const std::string bag = simulatedBag().path;
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"", "--bag is required"},
      {"--bag /nonexistent/maps.bag", "cannot read bag"},
      {"--bag '/nonexistent/a\rb.bag'", "cannot read bag '/nonexistent/a\\rb.bag'"},
      {"--bag " + bag + " --k 0,5", "--k: '0'"},
      {"--bag " + bag + " --nu 5,abc", "--nu: 'abc'"},
      {"--bag " + bag + " --radius 0.5,", "--radius: ''"},
      {"--bag " + bag + " --anisotropy 0.5", "--anisotropy: '0.5'"},
      {"--bag " + bag + " --success -1", "--success"},
      {"--bag " + bag + " --max-messages 0", "--max-messages"},
      {"--bag " + bag + " --bogus 1", "unknown flag '--bogus'"},
      {"--bag " + bag + " --dense-topic /tf", "is tf2_msgs/TFMessage"},
      {"--bag " + bag + " --ground-truth-topic /truth", "no topic '/truth'"},
      {"--bag " + bag + " --solver closed_form", "closed_form needs surface_anisotropy = 1"},
      {"--bag " + bag + " --csv /nonexistent/out.csv", "--csv: cannot write"},
  };
  for (const auto& [arguments, expected] : cases) {
    SCOPED_TRACE(arguments);
    const CommandRun run = runBagEval(arguments);
    EXPECT_EQ(run.exit_code, 2);
    EXPECT_EQ(lineCount(run.err), 1u) << run.err;
    EXPECT_NE(run.err.find(expected), std::string::npos) << run.err;
    EXPECT_TRUE(run.out.empty()) << run.out;
  }
}

}  // namespace
}  // namespace pda_registration
