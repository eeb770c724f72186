// rostest: hostile and broken input. Each bad input gets a clear WARN and publishes nothing, and
// the nodelet keeps serving the next valid input; a rejected alignment leaves the last good
// estimate on tf.
#include <gtest/gtest.h>

#include <limits>

#include "nodelet_harness.hpp"
#include "pda_registration/core/perturbation.hpp"
#include "pda_registration/ros/point_cloud_conversion.hpp"
#include "test_support/shared_data.hpp"

namespace pda_registration {
namespace {

using testing_support::NodeletHarness;

class NodeletBadInput : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    std::string error;
    data_ = new testing_support::SharedCase;
    ASSERT_TRUE(testing_support::loadSharedCase("room_scan", data_, &error)) << error;
    harness_ = new NodeletHarness("pda_registration");
    ASSERT_TRUE(harness_->waitForConnections(20.0));
    harness_->publishDense(data_->target, "dense_map");
    ros::WallDuration(1.5).sleep();  // the map is indexed before the first sparse cloud
  }

  // A valid sparse cloud must still produce a transform.
  void expectStillServing() {
    harness_->publishSparse(data_->source, "sparse_map");
    EXPECT_TRUE(harness_->waitForNextTransform(30.0)) << "the nodelet stopped serving valid input";
  }

  // Publishes a bad input and checks: a WARN containing `warning`, and no ~transform for it.
  void expectRefused(const std::function<void()>& publish_bad, const std::string& warning) {
    const size_t before = harness_->transformCount();
    publish_bad();
    EXPECT_TRUE(harness_->waitForWarnContaining(warning, 10.0))
        << "no WARN with '" << warning << "'";
    ros::WallDuration(1.0).sleep();
    EXPECT_EQ(harness_->transformCount(), before) << "published for a bad input";
  }

  static sensor_msgs::PointCloud2 validSparse() {
    std_msgs::Header header;
    header.frame_id = "sparse_map";
    header.stamp = ros::Time::now();
    return toPointCloud2(data_->source, header);
  }

  static testing_support::SharedCase* data_;
  static NodeletHarness* harness_;
};

testing_support::SharedCase* NodeletBadInput::data_ = nullptr;
NodeletHarness* NodeletBadInput::harness_ = nullptr;

// Runs first (gtest keeps declaration order): no seed on tf and no ~initial_transform.
TEST_F(NodeletBadInput, A_MissingTfSeed) {
  expectRefused([] { harness_->publishSparse(data_->source, "sparse_map"); }, "no seed for");
  ASSERT_TRUE(harness_->publishSeed(data_->T_target_source * randomPerturbation(2.0, 0.1, 1),
                                    "dense_map", "sparse_map"));
  ros::WallDuration(0.5).sleep();
  expectStillServing();
}

TEST_F(NodeletBadInput, B_CloudInUnknownFrame) {
  expectRefused([] { harness_->publishSparse(data_->source, "nowhere"); }, "'nowhere'");
  expectStillServing();
}

TEST_F(NodeletBadInput, C_EmptyCloud) {
  expectRefused([] { harness_->publishSparse(PointList(), "sparse_map"); }, "empty cloud");
  expectStillServing();
}

TEST_F(NodeletBadInput, D_AllNaNCloud) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  expectRefused(
      [nan] { harness_->publishSparse(PointList(100, Point(nan, nan, nan)), "sparse_map"); },
      "NaN or Inf");
  expectStillServing();
}

TEST_F(NodeletBadInput, E_DataShorterThanHeaderSays) {
  expectRefused(
      [] {
        sensor_msgs::PointCloud2 cloud = validSparse();
        cloud.data.resize(cloud.data.size() / 2);
        harness_->publishRaw(cloud, false);
      },
      "data holds");
  expectStillServing();
}

TEST_F(NodeletBadInput, F_CloudWithoutXyzFields) {
  expectRefused(
      [] {
        sensor_msgs::PointCloud2 cloud = validSparse();
        for (sensor_msgs::PointField& f : cloud.fields) f.name = "intensity_" + f.name;
        harness_->publishRaw(cloud, false);
      },
      "no 'x' field");
  expectStillServing();
}

TEST_F(NodeletBadInput, G_NoOverlapIsRejectedAndTheLastGoodEstimateStays) {
  Eigen::Isometry3d good;
  ASSERT_TRUE(harness_->lastTransformOnTf(5.0, &good)) << "tf never carried the last ~transform";
  PointList far_away = data_->source;
  for (Point& p : far_away) p += Point(500.0, 0.0, 0.0);
  expectRefused([&far_away] { harness_->publishSparse(far_away, "sparse_map"); },
                "alignment rejected");
  ros::WallDuration(0.5).sleep();  // tf keeps re-broadcasting: still the good estimate
  const Eigen::Isometry3d still = harness_->lookup("dense_map", "sparse_map_aligned", 5.0);
  EXPECT_LT((still.translation() - good.translation()).norm(), 1e-9);
  EXPECT_TRUE(still.linear().isApprox(good.linear(), 1e-12));
  expectStillServing();
}

}  // namespace
}  // namespace pda_registration
