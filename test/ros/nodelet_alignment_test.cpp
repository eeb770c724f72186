// rostest: the nodelet on a real case of ../shared/data with a perturbed seed on tf. The published
// transform, pose covariance, association markers and tf edge are checked against ground truth,
// then a dynamic_reconfigure change of k must show in the next marker set.
#include <gtest/gtest.h>

#include <Eigen/Cholesky>

#include "nodelet_harness.hpp"
#include "pda_registration/core/error_metrics.hpp"
#include "pda_registration/core/perturbation.hpp"
#include "test_support/shared_data.hpp"

namespace pda_registration {
namespace {

using testing_support::groupAssociationLines;
using testing_support::NodeletHarness;

using testing_support::toEigen;

class NodeletAlignment : public ::testing::Test {
 protected:
  void SetUp() override {
    ros::NodeHandle private_node("~");
    case_name_ = private_node.param<std::string>("case", "room_scan");
    nodelet_ = private_node.param<std::string>("nodelet", "pda_registration");
    std::string error;
    ASSERT_TRUE(testing_support::loadSharedCase(case_name_, &data_, &error)) << error;
    harness_ = std::make_unique<NodeletHarness>(nodelet_);
    ASSERT_TRUE(harness_->waitForConnections(20.0)) << "nodelet did not come up";
  }

  std::string case_name_, nodelet_;
  testing_support::SharedCase data_;
  std::unique_ptr<NodeletHarness> harness_;
};

TEST_F(NodeletAlignment, ConvergesToGroundTruthAndPublishesEverything) {
  const Eigen::Isometry3d seed = data_.T_target_source * randomPerturbation(5.0, 0.25, 4);
  ASSERT_TRUE(harness_->publishSeed(seed, "dense_map", "sparse_map"));
  harness_->publishDense(data_.target, "dense_map");
  ros::WallDuration(0.5).sleep();  // let the latched map and static tf arrive first
  harness_->publishSparse(data_.source, "sparse_map");
  ASSERT_TRUE(harness_->waitForNextTransform(60.0)) << "no ~transform published";

  const geometry_msgs::TransformStamped transform = harness_->lastTransform();
  EXPECT_EQ(transform.header.frame_id, "dense_map");
  EXPECT_EQ(transform.child_frame_id, "sparse_map");
  const PoseError error =
      poseError(data_.source, toEigen(transform.transform), data_.T_target_source);
  const PoseError seed_error = poseError(data_.source, seed, data_.T_target_source);
  EXPECT_LT(error.translation, 0.03);
  EXPECT_LT(error.rotation_deg, 0.75);
  EXPECT_LT(error.mean_distance, 0.03);
  EXPECT_GT(seed_error.mean_distance, 0.2);

  // ~pose: same estimate, positive-definite covariance.
  ASSERT_TRUE(harness_->waitForPosesBeyond(0, 5.0));
  const geometry_msgs::PoseWithCovarianceStamped pose = harness_->lastPose();
  Eigen::Matrix<double, 6, 6> covariance;
  for (int i = 0; i < 36; ++i) covariance(i / 6, i % 6) = pose.pose.covariance[i];
  EXPECT_TRUE(covariance.isApprox(covariance.transpose()));
  const Eigen::LLT<Eigen::Matrix<double, 6, 6>> cholesky(covariance);
  EXPECT_EQ(cholesky.info(), Eigen::Success) << "covariance not positive definite";
  EXPECT_NEAR(pose.pose.pose.position.x, transform.transform.translation.x, 1e-9);

  // Markers: the alphas of the lines leaving each source point sum to 1 (they are P(a_jk)).
  ASSERT_TRUE(harness_->waitForMarkersBeyond(0, 5.0)) << "no ~associations while subscribed";
  const auto groups = groupAssociationLines(harness_->lastMarkers());
  ASSERT_GT(groups.lines_per_point.size(), 100u);
  size_t most_lines = 0;
  for (size_t i = 0; i < groups.lines_per_point.size(); ++i) {
    EXPECT_NEAR(groups.alpha_sum_per_point[i], 1.0, 1e-3) << "source point " << i;
    most_lines = std::max(most_lines, groups.lines_per_point[i]);
  }
  EXPECT_EQ(most_lines, 5u);  // default k

  // tf: the corrected edge dense_map -> sparse_map_aligned, next to the seed's edge.
  const Eigen::Isometry3d on_tf = harness_->lookup("dense_map", "sparse_map_aligned", 5.0);
  EXPECT_LT((on_tf.translation() - toEigen(transform.transform).translation()).norm(), 1e-4);

  // dynamic_reconfigure: k = 2 applies from the next alignment.
  ASSERT_TRUE(harness_->reconfigure(testing_support::ParameterChange().set("k", 2)));
  const size_t markers_before = harness_->markerCount();
  harness_->publishSparse(data_.source, "sparse_map");
  ASSERT_TRUE(harness_->waitForNextTransform(60.0));
  ASSERT_TRUE(harness_->waitForMarkersBeyond(markers_before, 5.0));
  const auto groups_k2 = groupAssociationLines(harness_->lastMarkers());
  size_t most_lines_k2 = 0;
  for (size_t lines : groups_k2.lines_per_point) most_lines_k2 = std::max(most_lines_k2, lines);
  EXPECT_EQ(most_lines_k2, 2u);
}

}  // namespace
}  // namespace pda_registration
