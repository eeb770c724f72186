// rostest: the demo's path in short form. Waits for demo_monitor's result.json and checks that
// the nodelet's estimate beats the tf seed by a wide margin, that ~pose's covariance is
// consistent with the bag's ground truth (|error| / sigma within [0.5, 2] for translation and
// rotation, sigma = sqrt(trace) of each block), and that the pictures were written.
#include <gtest/gtest.h>
#include <ros/ros.h>

#include <filesystem>
#include <fstream>
#include <regex>

namespace {

// The value of "key": number inside the JSON object `section` (result.json is written by
// scripts/demo_monitor with fixed key names).
double numberIn(const std::string& json, const std::string& section, const std::string& key) {
  const size_t start = json.find("\"" + section + "\"");
  if (start == std::string::npos) return std::nan("");
  std::smatch match;
  const std::string rest = json.substr(start);
  if (!std::regex_search(rest, match, std::regex("\"" + key + "\": (-?[0-9.eE+-]+)"))) {
    return std::nan("");
  }
  return std::stod(match[1]);
}

TEST(DemoShort, CorrectedErrorBeatsTheSeedAndMatchesThePoseCovariance) {
  ros::NodeHandle private_node("~");
  const std::string path = private_node.param<std::string>("result", "");
  ASSERT_FALSE(path.empty());
  std::filesystem::remove(path);  // a result from an earlier run must not count
  const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(120.0);
  while (!std::filesystem::exists(path) && ros::WallTime::now() < deadline) {
    ros::WallDuration(0.2).sleep();
  }
  std::ifstream file(path);
  ASSERT_TRUE(file.good()) << "no " << path;
  const std::string json((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
  const double seed = numberIn(json, "seed_error", "mean_distance_m");
  const double corrected = numberIn(json, "corrected_error", "mean_distance_m");
  ASSERT_FALSE(std::isnan(seed) || std::isnan(corrected)) << json;
  EXPECT_GT(seed, 0.1);  // the bag's seed is 3 deg / 0.15 m off
  EXPECT_LT(corrected, 0.02);
  EXPECT_LT(corrected, 0.1 * seed);
  EXPECT_LT(numberIn(json, "corrected_error", "rot_err_deg"), 0.3);
  // The covariance published with the estimate says how far off it is: neither 3-80x too
  // confident (the inverse Hessian alone) nor uselessly wide.
  const double t_ratio = numberIn(json, "covariance_check", "trans_err_over_sigma");
  const double r_ratio = numberIn(json, "covariance_check", "rot_err_over_sigma");
  ASSERT_FALSE(std::isnan(t_ratio) || std::isnan(r_ratio)) << "no ~pose paired with ~transform\n"
                                                            << json;
  EXPECT_GE(t_ratio, 0.5) << json;
  EXPECT_LE(t_ratio, 2.0) << json;
  EXPECT_GE(r_ratio, 0.5) << json;
  EXPECT_LE(r_ratio, 2.0) << json;
  const std::filesystem::path directory = std::filesystem::path(path).parent_path();
  EXPECT_GT(std::filesystem::file_size(directory / "before_after.png"), 10000u);
  EXPECT_GT(std::filesystem::file_size(directory / "associations.png"), 10000u);
}

}  // namespace

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "demo_short_test");
  return RUN_ALL_TESTS();
}
