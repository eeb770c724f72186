// What the simulation writes: the bag (topics, counts, frames, latching, the tf seed and the
// ground truth) and pda_simulate run as a user runs it (case folder, bag, distortion, bad flags).
// The simulated maps themselves: map_simulation_test.cpp.
#include <geometry_msgs/TransformStamped.h>
#include <gtest/gtest.h>
#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <sensor_msgs/PointCloud2.h>
#include <tf2_msgs/TFMessage.h>

#include <algorithm>
#include <cstring>
#include <map>
#include <string>
#include <vector>

#include "pda_registration/core/error_metrics.hpp"
#include "pda_registration/core/perturbation.hpp"
#include "pda_registration/core/transform_io.hpp"
#include "pda_registration/simulation/map_bag_writer.hpp"
#include "pda_registration/simulation/map_simulation.hpp"
#include "pda_registration/tools/cloud_io.hpp"
#include "test_support/command_run.hpp"
#include "test_support/simulated_cases.hpp"

namespace pda_registration {
namespace simulation {
namespace {

using Eigen::Vector3d;
using testing_support::CommandRun;
using testing_support::jsonNumber;
using testing_support::runCommand;
using testing_support::smallOfficeOptions;
using testing_support::temporaryPath;

// --- Bag -------------------------------------------------------------------------------------

Eigen::Isometry3d fromTransformMessage(const geometry_msgs::Transform& t) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() =
      Eigen::Quaterniond(t.rotation.w, t.rotation.x, t.rotation.y, t.rotation.z).toRotationMatrix();
  T.translation() = Vector3d(t.translation.x, t.translation.y, t.translation.z);
  return T;
}

TEST(MapBag, HoldsTheTopicsMessageCountsFramesAndTransforms) {
  const PointList dense = {Point(1.0, 2.0, 3.0), Point(4.0, 5.0, 6.0), Point(7.0, 8.0, 9.0)};
  const PointList sparse = {Point(-1.0, 0.5, 0.25), Point(2.0, -3.0, 1.5)};
  const Eigen::Isometry3d truth = transformFromYawPitchRoll(25.0, 2.0, -1.0, Vector3d(1, 2, 3));
  const Eigen::Isometry3d seed = truth * randomPerturbation(3.0, 0.15, 4);
  const std::string path = temporaryPath("maps.bag");
  MapBagSummary summary;
  std::string error;
  ASSERT_TRUE(writeMapBag(path, dense, sparse, truth, seed, MapBagOptions(), &summary, &error))
      << error;
  EXPECT_DOUBLE_EQ(summary.duration, 6.0);

  rosbag::Bag bag(path, rosbag::bagmode::Read);
  std::map<std::string, int> counts;
  std::vector<double> sparse_stamps, tf_stamps;
  bool dense_latched = false;
  for (const rosbag::MessageInstance& message : rosbag::View(bag)) {
    ++counts[message.getTopic()];
    const double time = message.getTime().toSec();
    if (message.getTopic() == "/dense_map" || message.getTopic() == "/sparse_map") {
      const auto cloud = message.instantiate<sensor_msgs::PointCloud2>();
      ASSERT_NE(cloud, nullptr);
      const bool is_dense = message.getTopic() == "/dense_map";
      const PointList& expected = is_dense ? dense : sparse;
      EXPECT_EQ(cloud->header.frame_id, is_dense ? "dense_map" : "sparse_map");
      EXPECT_DOUBLE_EQ(cloud->header.stamp.toSec(), time);
      ASSERT_EQ(cloud->width * cloud->height, expected.size());
      ASSERT_EQ(cloud->data.size(), expected.size() * cloud->point_step);
      float last[3];
      std::memcpy(last, &cloud->data[(expected.size() - 1) * cloud->point_step], sizeof(last));
      EXPECT_FLOAT_EQ(last[2], static_cast<float>(expected.back().z()));
      if (is_dense) {
        dense_latched = message.getConnectionHeader()->count("latching") &&
                        message.getConnectionHeader()->at("latching") == "1";
      } else {
        sparse_stamps.push_back(time);
      }
    } else if (message.getTopic() == "/tf") {
      const auto tf = message.instantiate<tf2_msgs::TFMessage>();
      ASSERT_NE(tf, nullptr);
      ASSERT_EQ(tf->transforms.size(), 1u);
      EXPECT_EQ(tf->transforms[0].header.frame_id, "dense_map");
      EXPECT_EQ(tf->transforms[0].child_frame_id, "sparse_map");
      EXPECT_TRUE(fromTransformMessage(tf->transforms[0].transform).isApprox(seed, 1e-9));
      tf_stamps.push_back(time);
    } else if (message.getTopic() == "/ground_truth") {
      const auto truth_message = message.instantiate<geometry_msgs::TransformStamped>();
      ASSERT_NE(truth_message, nullptr);
      EXPECT_EQ(truth_message->header.frame_id, "dense_map");
      EXPECT_EQ(truth_message->child_frame_id, "sparse_map");
      EXPECT_TRUE(fromTransformMessage(truth_message->transform).isApprox(truth, 1e-9));
    }
  }
  EXPECT_EQ(counts.size(), 4u);
  EXPECT_EQ(counts["/dense_map"], 2);
  EXPECT_EQ(counts["/sparse_map"], 5);
  EXPECT_EQ(counts["/tf"], 61);  // 10 Hz over 6 s, both ends included
  EXPECT_EQ(counts["/ground_truth"], 7);
  EXPECT_TRUE(dense_latched);
  ASSERT_EQ(sparse_stamps.size(), 5u);
  for (size_t i = 1; i < sparse_stamps.size(); ++i) {
    EXPECT_NEAR(sparse_stamps[i] - sparse_stamps[i - 1], 1.0, 1e-9);
  }
  // The seed can be interpolated at every sparse map's stamp.
  EXPECT_LT(tf_stamps.front(), sparse_stamps.front());
  EXPECT_GT(tf_stamps.back(), sparse_stamps.back());
  EXPECT_NEAR(tf_stamps[1] - tf_stamps[0], 0.1, 1e-6);
  // The seed is the stated perturbation of the truth.
  const PoseError seed_error = poseError({Point::Zero()}, seed, truth);
  EXPECT_NEAR(seed_error.rotation_deg, 3.0, 1e-9);

  EXPECT_FALSE(writeMapBag("/nonexistent-directory/maps.bag", dense, sparse, truth, seed,
                           MapBagOptions(), nullptr, &error));
  EXPECT_NE(error.find("cannot write bag"), std::string::npos) << error;
}

// --- pda_simulate ----------------------------------------------------------------------------

CommandRun runPdaSimulate(const std::string& arguments) {
  return runCommand(PDA_SIMULATE_BINARY, arguments);
}

TEST(PdaSimulateTool, WritesACaseFolderAndABagLikeTheLibrary) {
  const std::string folder = temporaryPath("case"), bag = temporaryPath("case.bag");
  const CommandRun run = runPdaSimulate("--output " + folder + " --bag " + bag +
                                        " --seed 11 --kinect-frames 3 --velodyne-revolutions 1" +
                                        " --yaw-deg -40 --translation 0.5,2,-0.2");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_TRUE(run.err.empty()) << run.err;
  EXPECT_EQ(std::count(run.out.begin(), run.out.end(), '\n'), 1);

  MapSimulationOptions options = smallOfficeOptions(11);
  options.yaw_deg = -40.0;
  options.translation = Vector3d(0.5, 2.0, -0.2);
  const SimulatedMaps maps = simulateMaps(options);
  EXPECT_EQ(jsonNumber(run.out, "dense_points"), static_cast<double>(maps.dense.size()));
  EXPECT_EQ(jsonNumber(run.out, "sparse_points"), static_cast<double>(maps.sparse.size()));
  EXPECT_EQ(jsonNumber(run.out, "sparse_messages"), 5);

  PointList target, source;
  Eigen::Isometry3d truth;
  std::string error;
  ASSERT_TRUE(loadPointCloudFile(folder + "/target.pcd", &target, &error)) << error;
  ASSERT_TRUE(loadPointCloudFile(folder + "/source.pcd", &source, &error)) << error;
  ASSERT_TRUE(readTransformFile(folder + "/T_target_source.txt", &truth, &error)) << error;
  ASSERT_EQ(target.size(), maps.dense.size());
  ASSERT_EQ(source.size(), maps.sparse.size());
  EXPECT_TRUE(target.back().isApprox(maps.dense.back(), 1e-6));  // float precision in the file
  EXPECT_TRUE(source.front().isApprox(maps.sparse.front(), 1e-6));
  EXPECT_TRUE(truth.isApprox(maps.T_target_source, 1e-12));
  // Without distortion the warp's fixed point, written beside it, is the same transform.
  Eigen::Isometry3d unwarped;
  ASSERT_TRUE(readTransformFile(folder + "/T_target_source_unwarped.txt", &unwarped, &error))
      << error;
  EXPECT_EQ(unwarped.matrix(), truth.matrix());
  EXPECT_EQ(run.out.find("warp_fit"), std::string::npos);

  // The bag's tf seed is the default 3 degree / 15 cm perturbation of the truth.
  rosbag::Bag bag_file(bag, rosbag::bagmode::Read);
  int tf_messages = 0;
  for (const rosbag::MessageInstance& message : rosbag::View(bag_file, rosbag::TopicQuery("/tf"))) {
    const auto tf = message.instantiate<tf2_msgs::TFMessage>();
    ASSERT_NE(tf, nullptr);
    const PoseError seed_error =
        poseError({Point::Zero()}, fromTransformMessage(tf->transforms.at(0).transform), truth);
    EXPECT_NEAR(seed_error.rotation_deg, 3.0, 1e-6);
    EXPECT_NEAR(seed_error.translation, 0.15, 1e-6);
    ++tf_messages;
  }
  EXPECT_EQ(tf_messages, 61);
}

TEST(PdaSimulateTool, DistortionWritesTheFittedGroundTruthAndTheFixedPoint) {
  const std::string folder = temporaryPath("warped");
  const CommandRun run = runPdaSimulate("--output " + folder +
                                        " --seed 13 --kinect-frames 3 --velodyne-revolutions 1" +
                                        " --distortion 0.01");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  MapSimulationOptions options = smallOfficeOptions(13);
  options.distortion = 0.01;
  const SimulatedMaps maps = simulateMaps(options);
  Eigen::Isometry3d truth, unwarped;
  std::string error;
  ASSERT_TRUE(readTransformFile(folder + "/T_target_source.txt", &truth, &error)) << error;
  ASSERT_TRUE(readTransformFile(folder + "/T_target_source_unwarped.txt", &unwarped, &error))
      << error;
  EXPECT_TRUE(truth.isApprox(maps.T_target_source, 1e-12));
  EXPECT_TRUE(unwarped.isApprox(maps.T_target_source_unwarped, 1e-12));
  EXPECT_FALSE(truth.isApprox(unwarped, 1e-4));
  EXPECT_EQ(jsonNumber(run.out, "overlap_points"),
            static_cast<double>(maps.warp_fit.overlap_points));
  const PoseError moved = poseError(maps.sparse, truth, unwarped);
  EXPECT_NEAR(jsonNumber(run.out, "mean_distance_m"), moved.mean_distance, 1e-6);
  EXPECT_GT(moved.mean_distance, 0.001);
}

TEST(PdaSimulateTool, BadFlagsExitWithCodeTwoAndOneLine) {
  const std::string folder = temporaryPath("unused");
  const std::vector<std::string> bad_arguments = {"--seed 3",
                                                  "--output " + folder + " --seed -1",
                                                  "--output " + folder + " --translation 1,2",
                                                  "--output " + folder + " --kinect-frames 0",
                                                  "--output " + folder + " --distortion lots",
                                                  "--output " + folder +
                                                      " --scene outdoor --scene-changes 2",
                                                  "--output " + folder + " --colour red",
                                                  "--output /dev/null/case",
                                                  "--bag /nonexistent-directory/maps.bag",
                                                  "--bag '/nonexistent-directory/a\nb.bag'"};
  for (const std::string& arguments : bad_arguments) {
    const CommandRun run = runPdaSimulate(arguments);
    EXPECT_EQ(run.exit_code, 2) << arguments;
    EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << arguments << ": " << run.err;
    EXPECT_TRUE(run.out.empty()) << arguments;
  }
}

}  // namespace
}  // namespace simulation
}  // namespace pda_registration
