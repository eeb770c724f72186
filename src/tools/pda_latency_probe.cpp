// pda_latency_probe: measures the nodelet's end-to-end latency, sparse cloud published ->
// ~transform received, on a case folder (target.pcd, source.pcd, T_target_source.txt). Publishes
// the dense map (latched) and a perturbed seed on tf once, then the sparse cloud --count times,
// each after the previous result, and prints one JSON line with the median / p95 / max latency
// and the error of the last estimate. Needs a running roscore and the nodelet
// (scripts/measure_latency starts both).

#include <geometry_msgs/TransformStamped.h>
#include <ros/ros.h>
#include <sensor_msgs/PointCloud2.h>
#include <tf2_eigen/tf2_eigen.h>
#include <tf2_ros/static_transform_broadcaster.h>

#include <algorithm>
#include <atomic>
#include <iostream>
#include <vector>

#include "pda_registration/core/error_metrics.hpp"
#include "pda_registration/core/perturbation.hpp"
#include "pda_registration/ros/point_cloud_conversion.hpp"
#include "pda_registration/tools/case_folder.hpp"
#include "pda_registration/tools/command_line.hpp"
#include "pda_registration/tools/json_line.hpp"
#include "pda_registration/tools/statistics.hpp"

using namespace pda_registration;

namespace {

int fail(const std::string& message) {
  std::cerr << "pda_latency_probe: error: " << message << "\n";
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  ros::init(argc, argv, "pda_latency_probe", ros::init_options::AnonymousName);
  CommandLine cl({"case", "count", "nodelet", "timeout"}, {"help"});
  if (!cl.parse(argc, argv)) return fail(cl.error());
  if (cl.has("help") || !cl.has("case")) {
    std::cout << "usage: pda_latency_probe --case DIR [--count 20] [--nodelet pda_registration]"
                 " [--timeout 60]\n";
    return cl.has("help") ? 0 : 2;
  }
  int count = 20;
  double timeout = 60.0;
  if (!cl.integer("count", &count, 1, 100000) || !cl.number("timeout", &timeout, 0.1, 3600)) {
    return fail(cl.error());
  }
  CaseFolder loaded;
  std::string error;
  if (!loadCaseFolder(cl.text("case"), &loaded, &error)) return fail(error);
  const PointList& target = loaded.target;
  const PointList& source = loaded.source;
  const Eigen::Isometry3d truth = loaded.T_target_source;

  ros::NodeHandle node;
  ros::Publisher dense = node.advertise<sensor_msgs::PointCloud2>("dense_cloud", 1, true);
  ros::Publisher sparse = node.advertise<sensor_msgs::PointCloud2>("sparse_cloud", 1);
  std::atomic<size_t> received{0};
  ros::WallTime published;
  std::vector<double> latencies;
  geometry_msgs::TransformStamped last;
  std::mutex mutex;
  ros::Subscriber results = node.subscribe<geometry_msgs::TransformStamped>(
      "/" + cl.text("nodelet", "pda_registration") + "/transform", 10,
      [&](const geometry_msgs::TransformStamped::ConstPtr& m) {
        std::lock_guard<std::mutex> lock(mutex);
        latencies.push_back((ros::WallTime::now() - published).toSec() * 1000.0);
        last = *m;
        ++received;
      });
  ros::AsyncSpinner spinner(1);
  spinner.start();

  const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(timeout);
  while (ros::ok() && (sparse.getNumSubscribers() == 0 || results.getNumPublishers() == 0)) {
    if (ros::WallTime::now() > deadline) return fail("the nodelet did not connect");
    ros::WallDuration(0.05).sleep();
  }
  tf2_ros::StaticTransformBroadcaster seed_broadcaster;
  geometry_msgs::TransformStamped seed =
      tf2::eigenToTransform(truth * randomPerturbation(3.0, 0.15, 1));
  seed.header.stamp = ros::Time::now();
  seed.header.frame_id = "dense_map";
  seed.child_frame_id = "sparse_map";
  seed_broadcaster.sendTransform(seed);
  std_msgs::Header header;
  header.frame_id = "dense_map";
  header.stamp = ros::Time::now();
  dense.publish(toPointCloud2(target, header));
  ros::WallDuration(2.0).sleep();  // the map is indexed before the first sparse cloud

  header.frame_id = "sparse_map";
  const sensor_msgs::PointCloud2 cloud = toPointCloud2(source, header);
  for (int i = 0; i < count && ros::ok(); ++i) {
    const size_t before = received;
    sensor_msgs::PointCloud2 message = cloud;
    message.header.stamp = ros::Time::now();
    {
      std::lock_guard<std::mutex> lock(mutex);
      published = ros::WallTime::now();
    }
    sparse.publish(message);
    while (received == before) {
      if (ros::WallTime::now() > deadline || !ros::ok()) return fail("no ~transform in time");
      ros::WallDuration(0.001).sleep();
    }
  }
  std::lock_guard<std::mutex> lock(mutex);
  const PoseError e = poseError(source, tf2::transformToEigen(last), truth);
  JsonLine json;
  json.add("case", cl.text("case")).add("count", static_cast<int>(latencies.size()));
  json.add("median_ms", percentile(latencies, 0.5)).add("p95_ms", percentile(latencies, 0.95));
  json.add("max_ms", percentile(latencies, 1.0));
  json.add("mean_distance", e.mean_distance).add("rot_err_deg", e.rotation_deg);
  json.add("trans_err_m", e.translation);
  std::cout << json.str() << std::endl;
  return 0;
}
