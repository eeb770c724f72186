// The tf edge the nodelet broadcasts (ros/tf_edge.hpp), on a tf buffer filled by hand, without a
// roscore: the default edge, a correction edge composed with odometry at the cloud's stamp, the
// latest odometry standing in when tf has none at the stamp (and the edge saying so), and tf's
// error when it has none at all.
#include <gtest/gtest.h>
#include <tf2_eigen/tf2_eigen.h>

#include <string>

#include "pda_registration/ros/tf_edge.hpp"

namespace pda_registration {
namespace {

Eigen::Isometry3d odometryAt(double s) {
  return Eigen::Translation3d(0.5 * s, 0.1 * s, 0.0) *
         Eigen::AngleAxisd(0.05 * s, Eigen::Vector3d::UnitZ());
}

void addOdometry(tf2_ros::Buffer* buffer, double s) {
  geometry_msgs::TransformStamped t = tf2::eigenToTransform(odometryAt(s));
  t.header.stamp = ros::Time(100.0 + s);
  t.header.frame_id = "odom";
  t.child_frame_id = "sparse_map";
  buffer->setTransform(t, "test");
}

double gap(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  return (a.matrix() - b.matrix()).norm();
}

class TfEdgeTest : public ::testing::Test {
 protected:
  void SetUp() override {
    ros::Time::init();
    buffer_.setUsingDedicatedThread(true);  // filled by hand here, looked up without waiting
  }
  tf2_ros::Buffer buffer_{ros::Duration(30.0)};
  const Eigen::Isometry3d T_dense_sparse_ =
      Eigen::Translation3d(0.3, -0.2, 0.1) * Eigen::AngleAxisd(0.2, Eigen::Vector3d::UnitZ());
  TfEdge edge_;
  std::string error_;

  bool correctionEdgeAt(double s) {
    return expressOnTfEdge(buffer_, T_dense_sparse_, "dense_map", "sparse_map", "", "odom",
                           ros::Time(100.0 + s), ros::Duration(0.0), &edge_, &error_);
  }
};

TEST_F(TfEdgeTest, DefaultEdgeIsTheEstimateOnTheAlignedFrame) {
  ASSERT_TRUE(expressOnTfEdge(buffer_, T_dense_sparse_, "dense_map", "sparse_map", "", "",
                              ros::Time(100.0), ros::Duration(0.0), &edge_, &error_));
  EXPECT_EQ(edge_.parent, "dense_map");
  EXPECT_EQ(edge_.child, "sparse_map_aligned");
  EXPECT_LT(gap(edge_.T_parent_child, T_dense_sparse_), 1e-12);
  EXPECT_TRUE(edge_.at_stamp);
}

TEST_F(TfEdgeTest, CorrectionEdgeUsesOdometryAtTheStamp) {
  for (double s = 0.0; s <= 4.0; s += 1.0) addOdometry(&buffer_, s);
  ASSERT_TRUE(correctionEdgeAt(2.0)) << error_;
  EXPECT_EQ(edge_.parent, "dense_map");
  EXPECT_EQ(edge_.child, "odom");
  EXPECT_LT(gap(edge_.T_parent_child, T_dense_sparse_ * odometryAt(2.0).inverse()), 1e-9);
  EXPECT_TRUE(edge_.at_stamp);
}

// A cloud stamped before the odometry tf keeps (e.g. a late cloud): the latest odometry stands
// in, and the edge says so, for the nodelet's log and diagnostics.
TEST_F(TfEdgeTest, LatestOdometryStandsInAndTheEdgeSaysSo) {
  for (double s = 0.0; s <= 4.0; s += 1.0) addOdometry(&buffer_, s);
  ASSERT_TRUE(correctionEdgeAt(-5.0)) << error_;
  EXPECT_LT(gap(edge_.T_parent_child, T_dense_sparse_ * odometryAt(4.0).inverse()), 1e-9);
  EXPECT_FALSE(edge_.at_stamp);
  // The next edge at a stamp tf has is marked at the stamp again.
  ASSERT_TRUE(correctionEdgeAt(3.0)) << error_;
  EXPECT_TRUE(edge_.at_stamp);
}

TEST_F(TfEdgeTest, NoOdometryAtAllIsTfsError) {
  EXPECT_FALSE(correctionEdgeAt(0.0));
  EXPECT_NE(error_.find("sparse_map"), std::string::npos) << error_;
}

}  // namespace
}  // namespace pda_registration
