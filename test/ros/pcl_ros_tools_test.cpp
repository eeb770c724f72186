// pcl_ros's Debian tools with exactly the commands docs/tuning.md shows ("pcl_ros tools"): a PCD
// published as a latched map and as a periodic stream, a topic saved as PCD files, and a bag
// exported to PCD files that pda_align aligns to the ground truth. The commands are written once
// below, as the page writes them ($D the case folder, $W a working directory); one test checks
// that the page still shows each, the others run them with $D and $W filled in, under `timeout`.
// Every wait is bounded.
#include <gtest/gtest.h>
#include <pcl/io/pcd_io.h>
#include <pcl/point_types.h>
#include <ros/master.h>
#include <ros/ros.h>
#include <sensor_msgs/PointCloud2.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <functional>
#include <mutex>
#include <sstream>
#include <string>
#include <system_error>
#include <vector>

#include "background_command.hpp"
#include "test_support/command_run.hpp"
#include "test_support/shared_data.hpp"

namespace pda_registration {
namespace {

namespace fs = std::filesystem;
using testing_support::BackgroundCommand;
using testing_support::CommandRun;
using testing_support::jsonNumber;
using testing_support::runCommand;
using testing_support::temporaryPath;

// The commands as docs/tuning.md writes them: $D the case folder, $W a working directory.
const char* const kLatchedMap =
    "rosrun pcl_ros pcd_to_pointcloud $D/target.pcd _frame_id:=map _latch:=true "
    "cloud_pcd:=/dense_map";
const char* const kPeriodicScan =
    "rosrun pcl_ros pcd_to_pointcloud $D/source.pcd 0.5 _frame_id:=velodyne "
    "cloud_pcd:=/sparse_map __name:=sparse_map_publisher";
const char* const kSaveMap =
    "rosrun pcl_ros pointcloud_to_pcd input:=/dense_map _prefix:=$W/dense_map_ _binary:=true";
const char* const kWriteBag =
    "rosrun pda_registration pda_case_bag --case $D --bag $W/room_scan.bag --sparse-messages 1";
const char* const kExportDense = "rosrun pcl_ros bag_to_pcd $W/room_scan.bag /dense_map $W/dense";
const char* const kExportSparse =
    "rosrun pcl_ros bag_to_pcd $W/room_scan.bag /sparse_map $W/sparse";
const char* const kAlign =
    "rosrun pda_registration pda_align --target $W/dense/100.500000000.pcd "
    "--source $W/sparse/101.000000000.pcd --initial $D/T_target_source.txt --perturb 5,0.25 "
    "--seed 1 --ground-truth $D/T_target_source.txt";

// The case the page's commands use: a dense map and a sparse scan with ground truth.
std::string caseDirectory() { return testing_support::sharedDataDirectory() + "/room_scan"; }

std::string replaceAll(std::string text, const std::string& from, const std::string& to) {
  for (size_t at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size())) {
    text.replace(at, from.size(), to);
  }
  return text;
}

// A command of the page with $D (the case) and `work_directory` for $W, bounded by `timeout`.
std::string runnable(const std::string& command, const std::string& work_directory = "") {
  return "exec timeout 120 " +
         replaceAll(replaceAll(command, "$D", caseDirectory()), "$W", work_directory);
}

bool waitUntil(const std::function<bool()>& condition, double timeout_s) {
  const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(timeout_s);
  while (!condition()) {
    if (ros::WallTime::now() > deadline) return false;
    ros::WallDuration(0.05).sleep();
  }
  return true;
}

bool advertised(const std::string& topic) {
  ros::master::V_TopicInfo topics;
  ros::master::getTopics(topics);
  for (const auto& info : topics) {
    if (info.name == topic) return true;
  }
  return false;
}

// True once a binary PCD file holds all the data its header announces. pointcloud_to_pcd writes
// the file while the test polls it, and PCL's reader does not guard against a file cut short: a
// poll that read a half-written file crashed the test process (SIGSEGV, once in a CI-like run).
bool binaryPcdComplete(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::vector<size_t> sizes, counts;
  size_t points = 0;
  bool binary = false;
  for (std::string line; std::getline(in, line);) {
    std::istringstream words(line);
    std::string key;
    words >> key;
    size_t value = 0;
    if (key == "SIZE") {
      while (words >> value) sizes.push_back(value);
    } else if (key == "COUNT") {
      while (words >> value) counts.push_back(value);
    } else if (key == "POINTS") {
      words >> points;
    } else if (key == "DATA") {
      std::string kind;
      words >> kind;
      binary = kind == "binary";
      break;
    }
  }
  // A DATA line without its newline yet leaves the stream at its end: tellg() is -1 then.
  const std::streamoff header = in.tellg();
  if (!binary || header < 0 || points == 0 || sizes.empty() || sizes.size() != counts.size()) {
    return false;
  }
  size_t point_size = 0;
  for (size_t i = 0; i < sizes.size(); ++i) point_size += sizes[i] * counts[i];
  std::error_code error;
  const uintmax_t file_size = fs::file_size(path, error);
  return !error && file_size >= static_cast<uintmax_t>(header) + points * point_size;
}

size_t pcdPointCount(const std::string& path) {
  pcl::PCLPointCloud2 header;
  pcl::PCDReader reader;
  if (reader.readHeader(path, header) < 0) return 0;
  return static_cast<size_t>(header.width) * header.height;
}

// Every cloud a topic delivers to this subscriber.
class CloudInbox {
 public:
  explicit CloudInbox(const std::string& topic)
      : subscriber_(ros::NodeHandle().subscribe(topic, 10, &CloudInbox::receive, this)) {}

  bool waitForCount(size_t count, double timeout_s) {
    return waitUntil([&] { return clouds().size() >= count; }, timeout_s);
  }
  std::vector<sensor_msgs::PointCloud2ConstPtr> clouds() {
    std::lock_guard<std::mutex> lock(mutex_);
    return clouds_;
  }

 private:
  void receive(const sensor_msgs::PointCloud2ConstPtr& cloud) {
    std::lock_guard<std::mutex> lock(mutex_);
    clouds_.push_back(cloud);
  }

  std::mutex mutex_;
  std::vector<sensor_msgs::PointCloud2ConstPtr> clouds_;
  ros::Subscriber subscriber_;  // last: unsubscribed before the rest goes
};

TEST(PclRosTools, ThePageShowsEveryCommandThisTestRuns) {
  std::ifstream file(std::string(PDA_REPO_DIR) + "/docs/tuning.md");
  std::vector<std::string> lines;
  for (std::string line; std::getline(file, line);) lines.push_back(line);
  ASSERT_FALSE(lines.empty()) << "docs/tuning.md not found";
  for (const char* command :
       {kLatchedMap, kPeriodicScan, kSaveMap, kWriteBag, kExportDense, kExportSparse, kAlign}) {
    EXPECT_TRUE(std::find(lines.begin(), lines.end(), command) != lines.end())
        << "docs/tuning.md no longer shows, on a line of its own: " << command;
  }
}

TEST(PclRosTools, PcdToPointcloudPublishesAPcdAsALatchedMap) {
  const std::string pcd = caseDirectory() + "/target.pcd";
  BackgroundCommand publisher(runnable(kLatchedMap), temporaryPath("map_publisher.log"));
  ASSERT_TRUE(waitUntil([] { return advertised("/dense_map"); }, 30))
      << "/dense_map not advertised within 30 s: " << publisher.log();
  CloudInbox first("/dense_map");
  ASSERT_TRUE(first.waitForCount(1, 30)) << "no map within 30 s: " << publisher.log();
  const sensor_msgs::PointCloud2ConstPtr map = first.clouds().front();
  EXPECT_EQ(static_cast<size_t>(map->width) * map->height, pcdPointCount(pcd));
  EXPECT_GT(map->width, 100000u);
  EXPECT_EQ(map->header.frame_id, "map");
  // Latched: a subscriber that comes after the one publication still gets the map.
  CloudInbox late("/dense_map");
  EXPECT_TRUE(late.waitForCount(1, 30)) << "a late subscriber got no map within 30 s";
  EXPECT_EQ(first.clouds().size(), 1u) << "without an interval the map is published once";
}

TEST(PclRosTools, PcdToPointcloudRepublishesAtAnInterval) {
  const std::string pcd = caseDirectory() + "/source.pcd";
  CloudInbox inbox("/sparse_map");
  BackgroundCommand publisher(runnable(kPeriodicScan), temporaryPath("scan_publisher.log"));
  ASSERT_TRUE(inbox.waitForCount(3, 30)) << "fewer than 3 clouds in 30 s: " << publisher.log();
  const auto clouds = inbox.clouds();
  for (size_t i = 0; i < clouds.size(); ++i) {
    EXPECT_EQ(static_cast<size_t>(clouds[i]->width) * clouds[i]->height, pcdPointCount(pcd));
    EXPECT_EQ(clouds[i]->header.frame_id, "velodyne");
    if (i > 0) {
      EXPECT_GT(clouds[i]->header.stamp, clouds[i - 1]->header.stamp);
    }
  }
}

TEST(PclRosTools, PointcloudToPcdSavesATopicAsPcdFiles) {
  const std::string W = temporaryPath("saved");  // the page's working directory
  fs::create_directories(W);
  BackgroundCommand publisher(runnable(kLatchedMap), temporaryPath("map_publisher.log"));
  BackgroundCommand saver(runnable(kSaveMap, W), temporaryPath("saver.log"));
  pcl::PointCloud<pcl::PointXYZ> original, saved;
  ASSERT_EQ(pcl::io::loadPCDFile(caseDirectory() + "/target.pcd", original), 0);
  // One file per message, <prefix><stamp>.pcd; polled until it holds the whole map (the writer
  // may still be filling it when it first appears).
  const auto holdsTheMap = [&] {
    for (const auto& entry : fs::directory_iterator(W)) {
      if (entry.path().filename().string().rfind("dense_map_", 0) != 0) continue;
      if (!binaryPcdComplete(entry.path().string())) continue;
      saved.clear();
      if (pcl::io::loadPCDFile(entry.path().string(), saved) != 0) continue;
      if (saved.size() != original.size()) continue;
      bool same = true;
      for (size_t i = 0; same && i < saved.size(); ++i) {
        same = saved[i].getVector3fMap() == original[i].getVector3fMap();
      }
      if (same) return true;
    }
    return false;
  };
  EXPECT_TRUE(waitUntil(holdsTheMap, 60))
      << "no dense_map_*.pcd equal to target.pcd within 60 s: " << saver.log() << publisher.log();
}

TEST(PclRosTools, BagToPcdExportsCloudsThatPdaAlignAligns) {
  const std::string W = temporaryPath("export");  // the page's working directory
  fs::create_directories(W);
  const CommandRun bag = runCommand(runnable(kWriteBag, W), "");
  ASSERT_EQ(bag.exit_code, 0) << bag.err;
  for (const char* command : {kExportDense, kExportSparse}) {
    const CommandRun exported = runCommand(runnable(command, W), "");
    ASSERT_EQ(exported.exit_code, 0) << command << ": " << exported.out << exported.err;
  }
  // One file per message, named by its stamp; pda_case_bag's stamps are fixed.
  const std::string dense = W + "/dense/100.500000000.pcd";
  const std::string sparse = W + "/sparse/101.000000000.pcd";
  EXPECT_EQ(static_cast<double>(pcdPointCount(dense)), jsonNumber(bag.out, "dense_points"));
  EXPECT_EQ(static_cast<double>(pcdPointCount(sparse)), jsonNumber(bag.out, "sparse_points"));

  const CommandRun aligned = runCommand(runnable(kAlign, W), "");
  ASSERT_EQ(aligned.exit_code, 0) << aligned.out << aligned.err;
  // room_scan's ground truth is good to ~1 cm / 0.5 deg (shared data README).
  EXPECT_GT(jsonNumber(aligned.out, "initial_mean_distance"), 0.2) << aligned.out;
  EXPECT_LT(jsonNumber(aligned.out, "mean_distance"), 0.05) << aligned.out;
  EXPECT_LT(jsonNumber(aligned.out, "trans_err_m"), 0.03) << aligned.out;
  EXPECT_LT(jsonNumber(aligned.out, "rot_err_deg"), 0.75) << aligned.out;
}

}  // namespace
}  // namespace pda_registration
