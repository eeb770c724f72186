// rostest: the nodelet publishing a correction edge, map -> odom, while odometry moves the
// sensor (odom -> sparse_map) at 0.5 m/s. The edge must hold the correction computed with
// odometry at the cloud's stamp, and keep holding it as the robot drives on: re-composing it
// with the latest odometry would pin the sensor to where it was when the cloud was taken.
#include <gtest/gtest.h>
#include <tf2_eigen/tf2_eigen.h>
#include <tf2_msgs/TFMessage.h>

#include <atomic>
#include <thread>

#include "nodelet_harness.hpp"
#include "pda_registration/core/error_metrics.hpp"
#include "pda_registration/ros/point_cloud_conversion.hpp"
#include "test_support/shared_data.hpp"

namespace pda_registration {
namespace {

using testing_support::toEigen;

// odom -> sparse_map: driving at 0.5 m/s along x and 0.1 m/s along y, turning at 2 deg/s.
// Linear in time, so tf's interpolation between samples is exact.
Eigen::Isometry3d odometryAt(const ros::Time& t, const ros::Time& start) {
  const double s = (t - start).toSec();
  return Eigen::Translation3d(0.5 * s, 0.1 * s, 0.0) *
         Eigen::AngleAxisd(s * 2.0 * M_PI / 180.0, Eigen::Vector3d::UnitZ());
}

double translationGap(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  return (a.translation() - b.translation()).norm();
}

TEST(NodeletCorrectionEdge, HoldsTheCorrectionWhileOdometryMoves) {
  testing_support::NodeletHarness harness("pda_registration");
  testing_support::SharedCase data;
  ASSERT_TRUE(testing_support::loadCaseAndConnect(&harness, "room_scan", &data));

  // map -> dense_map: the dense map placed in the robot's map frame.
  const Eigen::Isometry3d T_map_dense =
      Eigen::Translation3d(1.0, -2.0, 0.0) * Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ());
  ASSERT_TRUE(harness.publishSeed(T_map_dense, "map", "dense_map"));

  // Odometry on /tf from a publisher that both listeners (the node's and this test's) have
  // connected to first: a new publisher's messages are lost until a subscriber connects, and
  // under load that took longer than the 0.3 s before the cloud's stamp, so the node's buffer
  // had no odometry at the stamp and composed the edge with the latest (0.22 m off).
  ros::NodeHandle node;
  ros::Publisher tf_publisher = node.advertise<tf2_msgs::TFMessage>("/tf", 100);
  ASSERT_TRUE(harness.waitFor([&] { return tf_publisher.getNumSubscribers() >= 2; }, 20.0))
      << "the tf listeners did not connect to the odometry publisher within 20 s ("
      << tf_publisher.getNumSubscribers() << " connected)";
  const ros::Time start = ros::Time::now();
  std::atomic<bool> driving{true};
  std::thread odometry([&] {
    while (driving) {
      const ros::Time now = ros::Time::now();
      geometry_msgs::TransformStamped t = tf2::eigenToTransform(odometryAt(now, start));
      t.header.stamp = now;
      t.header.frame_id = "odom";
      t.child_frame_id = "sparse_map";
      tf2_msgs::TFMessage message;
      message.transforms.push_back(t);
      tf_publisher.publish(message);
      ros::WallDuration(0.02).sleep();
    }
  });
  harness.publishDense(data.target, "dense_map");
  ASSERT_TRUE(harness.waitForLogContaining("dense map from", 30.0)) << "the map never arrived";

  // The cloud was taken 0.2 s ago, with odometry buffered on both sides of its stamp.
  while ((ros::Time::now() - start).toSec() < 0.5) ros::WallDuration(0.02).sleep();
  const ros::Time taken = ros::Time::now() - ros::Duration(0.2);
  std_msgs::Header header;
  header.frame_id = "sparse_map";
  header.stamp = taken;
  harness.publishRaw(toPointCloud2(data.source, header), false);
  geometry_msgs::TransformStamped result;
  ASSERT_TRUE(harness.waitForTransformStamped(taken, 30.0, &result)) << harness.logText();
  const Eigen::Isometry3d T_dense_sparse = toEigen(result.transform);
  EXPECT_LT(poseError(data.source, T_dense_sparse, data.T_target_source).mean_distance, 0.03);

  // map <- odom = (map <- dense)(dense <- sparse)(sparse <- odom), odometry at the cloud's stamp.
  const Eigen::Isometry3d expected =
      T_map_dense * T_dense_sparse * odometryAt(taken, start).inverse();
  ros::WallDuration(0.3).sleep();
  const Eigen::Isometry3d first = harness.lookup("map", "odom", 5.0);
  EXPECT_LT(translationGap(first, expected), 1e-3);
  EXPECT_LT(Eigen::AngleAxisd(first.linear().transpose() * expected.linear()).angle(), 1e-4);
  // The node says whether odometry at the stamp went into the edge, or the latest stood in.
  ASSERT_TRUE(harness.waitForFreshDiagnostics(5.0)) << "no diagnostics within 5 s";
  EXPECT_EQ(harness.diagnosticValue("tf edges from the latest tf (none at the stamp)"), "0");

  // Two seconds (a metre) later, the re-broadcast edge is still the same correction ...
  ros::WallDuration(2.0).sleep();
  const Eigen::Isometry3d later = harness.lookup("map", "odom", 5.0);
  EXPECT_LT(translationGap(later, expected), 1e-3)
      << "the correction edge followed odometry (it moved "
      << translationGap(odometryAt(ros::Time::now(), start), odometryAt(taken, start)) << " m)";
  // ... so the sensor moves on in the map with odometry, and at the cloud's stamp it sits where
  // the alignment put it.
  const ros::Time now = ros::Time::now() - ros::Duration(0.1);
  EXPECT_LT(translationGap(harness.lookup("map", "sparse_map", 5.0, now),
                           expected * odometryAt(now, start)),
            1e-3);
  EXPECT_LT(
      translationGap(T_map_dense * T_dense_sparse, harness.lookup("map", "sparse_map", 5.0, taken)),
      1e-3);
  driving = false;
  odometry.join();
}

}  // namespace
}  // namespace pda_registration
