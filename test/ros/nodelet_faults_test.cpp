// rostest: faults a running robot stack throws at the nodelet. tf gaps, extrapolation into the
// future and the past, a wildly wrong seed; the dense map's publisher vanishing and a rebuilt
// map arriving; a storm of live parameter changes while alignments run. After each, the nodelet
// serves the next input, and nothing it published is off the ground truth: a rejected
// alignment never reaches ~transform.
#include <gtest/gtest.h>
#include <tf2_eigen/tf2_eigen.h>
#include <tf2_ros/transform_broadcaster.h>

#include <atomic>
#include <thread>

#include "nodelet_harness.hpp"
#include "pda_registration/core/error_metrics.hpp"
#include "pda_registration/core/perturbation.hpp"
#include "pda_registration/ros/point_cloud_conversion.hpp"
#include "test_support/shared_data.hpp"

namespace pda_registration {
namespace {

using testing_support::NodeletHarness;
using testing_support::toEigen;

// The seed dense_map -> sparse_map on tf at 20 Hz, stamped now, like a localisation node would
// publish it; it can pause (a tf gap) and change.
class SeedBroadcaster {
 public:
  explicit SeedBroadcaster(const Eigen::Isometry3d& seed) : seed_(seed) {
    thread_ = std::thread([this] {
      while (!stop_) {
        if (running_) {
          geometry_msgs::TransformStamped t;
          {
            std::lock_guard<std::mutex> lock(mutex_);
            t = tf2::eigenToTransform(seed_);
          }
          t.header.stamp = ros::Time::now();
          t.header.frame_id = "dense_map";
          t.child_frame_id = "sparse_map";
          broadcaster_.sendTransform(t);
        }
        ros::WallDuration(0.05).sleep();
      }
    });
  }
  ~SeedBroadcaster() {
    stop_ = true;
    thread_.join();
  }
  void pause() { running_ = false; }
  void resume() { running_ = true; }
  void set(const Eigen::Isometry3d& seed) {
    std::lock_guard<std::mutex> lock(mutex_);
    seed_ = seed;
  }

 private:
  tf2_ros::TransformBroadcaster broadcaster_;
  std::mutex mutex_;
  Eigen::Isometry3d seed_;
  std::atomic<bool> running_{true}, stop_{false};
  std::thread thread_;
};

size_t countOf(const std::string& text, const std::string& what) {
  size_t count = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++count;
  return count;
}

// The nodelet's count of dense maps it has put in use (diagnostics "index updates"), read from a
// fresh status; -1 when none comes.
int indexUpdates(NodeletHarness* harness) {
  if (!harness->waitForFreshDiagnostics(5.0)) return -1;
  return std::stoi(harness->diagnosticValue("index updates"));
}

// Waits (bounded) until a dense map published after `before` updates is in use: maps are indexed
// on the keeper's own thread, beside the alignments, which use the newest ready map.
bool waitForIndexUpdatesBeyond(NodeletHarness* harness, int before, double timeout_s) {
  const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(timeout_s);
  while (ros::ok() && ros::WallTime::now() < end) {
    if (indexUpdates(harness) > before) return true;
  }
  return false;
}

class NodeletFaults : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    data_ = new testing_support::SharedCase;
    std::string error;
    ASSERT_TRUE(testing_support::loadSharedCase("room_scan", data_, &error)) << error;
    harness_ = new NodeletHarness("pda_registration");
    ASSERT_TRUE(harness_->waitForConnections(20.0));
    seed_ = new SeedBroadcaster(data_->T_target_source * randomPerturbation(3.0, 0.15, 7));
    harness_->publishDense(data_->target, "dense_map");
    ros::WallDuration(1.5).sleep();  // the map is indexed and tf has history
  }
  static void TearDownTestSuite() {
    delete seed_;
    delete harness_;
    delete data_;
  }

  void SetUp() override { first_transform_ = harness_->transformCount(); }

  static void publishSparseStamped(const ros::Time& stamp) {
    std_msgs::Header header;
    header.frame_id = "sparse_map";
    header.stamp = stamp;
    harness_->publishRaw(toPointCloud2(data_->source, header), false);
  }

  // Publishes a sparse cloud and expects an estimate within the ground truth's tolerance.
  static void expectAligned(const ros::Time& stamp, const Eigen::Isometry3d& truth,
                            const std::string& what) {
    publishSparseStamped(stamp);
    geometry_msgs::TransformStamped result;
    ASSERT_TRUE(harness_->waitForTransformStamped(stamp, 30.0, &result))
        << what << ": no ~transform for the cloud stamped " << stamp;
    const PoseError e = poseError(data_->source, toEigen(result.transform), truth);
    EXPECT_LT(e.mean_distance, 0.03) << what;
    EXPECT_LT(e.rotation_deg, 0.75) << what;
  }

  // Every ~transform of this test is near `truth` (eq. 22 below `tolerance`): a rejected
  // result was never published.
  void expectEveryPublishedNear(const Eigen::Isometry3d& truth, double tolerance = 0.03) {
    const auto all = harness_->transforms();
    for (size_t i = first_transform_; i < all.size(); ++i) {
      const PoseError e = poseError(data_->source, toEigen(all[i].transform), truth);
      EXPECT_LT(e.mean_distance, tolerance) << "published transform " << i << " is off";
    }
  }

  size_t first_transform_ = 0;
  static testing_support::SharedCase* data_;
  static NodeletHarness* harness_;
  static SeedBroadcaster* seed_;
};

testing_support::SharedCase* NodeletFaults::data_ = nullptr;
NodeletHarness* NodeletFaults::harness_ = nullptr;
SeedBroadcaster* NodeletFaults::seed_ = nullptr;

// Runs first (gtest keeps declaration order).
TEST_F(NodeletFaults, A_TfGapsExtrapolationAndAWrongSeed) {
  const Eigen::Isometry3d truth = data_->T_target_source;
  // Clouds meant to be seeded at their stamp are stamped 0.2 s back, so the seeds on both sides
  // of the stamp are already buffered (stamped now, they hinge on the next 20 Hz seed arriving
  // within tf_timeout, 0.1 s: a loaded machine can miss that).
  const ros::Duration buffered(0.2);
  expectAligned(ros::Time::now() - buffered, truth, "tf flowing");
  EXPECT_TRUE(harness_->waitForLogContaining("seeding from tf at the cloud's stamp", 5.0));

  // A tf gap: the cloud is newer than any seed (extrapolation into the future) -> latest tf.
  seed_->pause();
  ros::WallDuration(1.0).sleep();
  expectAligned(ros::Time::now(), truth, "in a tf gap");
  EXPECT_TRUE(harness_->waitForLogContaining("seeding from latest tf", 5.0)) << harness_->logText();
  // A cloud older than tf's whole history (extrapolation into the past) -> latest tf too.
  expectAligned(ros::Time::now() - ros::Duration(3600.0), truth, "stamped an hour ago");

  // tf comes back: seeds at the cloud's stamp again.
  seed_->resume();
  ros::WallDuration(0.5).sleep();
  expectAligned(ros::Time::now() - buffered, truth, "tf back");
  EXPECT_EQ(countOf(harness_->logText(), "seeding from tf at the cloud's stamp"), 2u)
      << harness_->logText();

  // A seed 50 m off (a localisation jump): nothing to align with -> rejected, not published,
  // and tf keeps the last good estimate.
  // (With the warm start successive answers differ by ~0.1 mm: wait until tf has the last.)
  Eigen::Isometry3d good;
  ASSERT_TRUE(harness_->lastTransformOnTf(5.0, &good)) << "tf never carried the last ~transform";
  seed_->set(Eigen::Translation3d(0.0, 0.0, 50.0) * truth);
  ros::WallDuration(0.3).sleep();
  const size_t before = harness_->transformCount();
  publishSparseStamped(ros::Time::now());
  EXPECT_TRUE(harness_->waitForWarnContaining("alignment rejected", 15.0));
  ros::WallDuration(1.0).sleep();
  EXPECT_EQ(harness_->transformCount(), before) << "a rejected alignment was published";
  const Eigen::Isometry3d still = harness_->lookup("dense_map", "sparse_map_aligned", 5.0);
  EXPECT_LT((still.translation() - good.translation()).norm(), 1e-9);

  seed_->set(truth * randomPerturbation(3.0, 0.15, 8));
  ros::WallDuration(0.3).sleep();
  expectAligned(ros::Time::now(), truth, "after the wrong seed");
  expectEveryPublishedNear(truth);
}

TEST_F(NodeletFaults, B_DenseMapDisappearsAndARebuiltOneComesBack) {
  const Eigen::Isometry3d truth = data_->T_target_source;
  harness_->closeDense();
  ros::WallDuration(1.0).sleep();
  expectAligned(ros::Time::now(), truth, "dense publisher gone: the last map still serves");
  ASSERT_TRUE(harness_->waitForFreshDiagnostics(5.0));
  EXPECT_EQ(harness_->diagnosticValue("dense map publishers"), "0");
  EXPECT_NE(harness_->lastDiagnostics().message.find("publisher is gone"), std::string::npos)
      << harness_->lastDiagnostics().message;
  EXPECT_EQ(harness_->lastDiagnostics().level, diagnostic_msgs::DiagnosticStatus::WARN);

  // The map comes back rebuilt, 0.3 m further along x: the next estimate follows it.
  harness_->reopenDense();
  const Eigen::Isometry3d shift(Eigen::Translation3d(0.3, 0.0, 0.0));
  PointList rebuilt = data_->target;
  for (Point& p : rebuilt) p = shift * p;
  ros::WallDuration(1.0).sleep();  // the new publisher connects
  const int updates = indexUpdates(harness_);
  ASSERT_GE(updates, 1);
  harness_->publishDense(rebuilt, "dense_map");
  ASSERT_TRUE(waitForIndexUpdatesBeyond(harness_, updates, 30.0))
      << "the rebuilt map never came in use";
  seed_->set(shift * truth * randomPerturbation(3.0, 0.15, 9));
  ros::WallDuration(0.3).sleep();
  expectAligned(ros::Time::now(), shift * truth, "rebuilt map");
  ASSERT_TRUE(harness_->waitForFreshDiagnostics(5.0));
  EXPECT_EQ(harness_->lastDiagnostics().level, diagnostic_msgs::DiagnosticStatus::OK)
      << harness_->lastDiagnostics().message;

  // The same map re-published (a periodic map topic) is recognised and not re-indexed.
  const std::string unchanged_before =
      harness_->diagnosticValue("dense clouds unchanged (not re-indexed)");
  harness_->publishDense(rebuilt, "dense_map");
  ros::WallDuration(1.0).sleep();
  ASSERT_TRUE(harness_->waitForFreshDiagnostics(5.0));
  EXPECT_EQ(std::stoi(harness_->diagnosticValue("dense clouds unchanged (not re-indexed)")),
            std::stoi(unchanged_before) + 1);

  // Back to the original map for the next test.
  const int updates_before_original = indexUpdates(harness_);
  harness_->publishDense(data_->target, "dense_map");
  seed_->set(truth * randomPerturbation(3.0, 0.15, 10));
  ASSERT_TRUE(waitForIndexUpdatesBeyond(harness_, updates_before_original, 30.0))
      << "the original map never came back in use";
  ros::WallDuration(0.3).sleep();  // the new seed reaches the nodelet's tf buffer
  expectAligned(ros::Time::now(), truth, "original map again");
}

TEST_F(NodeletFaults, C_ParameterStormWhileAligning) {
  const Eigen::Isometry3d truth = data_->T_target_source;
  // Sparse clouds at 10 Hz keep the worker busy, so most changes land mid-alignment.
  std::atomic<bool> publishing{true};
  std::thread publisher([&publishing] {
    while (publishing) {
      publishSparseStamped(ros::Time::now());
      ros::WallDuration(0.1).sleep();
    }
  });
  const size_t before = harness_->transformCount();
  const std::vector<std::string> solvers = {"gauss_newton", "ceres"};
  // At least 30 changes, and on until 10 alignments went out during them (however slow the
  // machine), within a minute.
  const ros::WallTime give_up = ros::WallTime::now() + ros::WallDuration(60.0);
  std::string last_solver;
  for (int i = 0;
       i < 30 || (harness_->transformCount() - before < 10 && ros::WallTime::now() < give_up);
       ++i) {
    const auto change = testing_support::ParameterChange()
                            .set("k", 1 + i % 8)
                            .set("runs", 20 + i % 30)
                            .set("threads", 1 + i % 2)
                            .set("radius", 0.6 + 0.1 * (i % 6))
                            .set("nu", i % 3 == 0 ? 3.0 : 8.0)
                            .set("target_voxel_size", i % 4 == 0 ? 0.03 : 0.0)  // re-indexes
                            .set("normal_voxel_size", i % 5 == 0 ? 0.2 : 0.15)
                            .set("solver", solvers[i % 2]);
    EXPECT_TRUE(harness_->reconfigure(change)) << "reconfigure call " << i;
    last_solver = solvers[i % 2];
    ros::WallDuration(0.1).sleep();
  }
  // An impossible combination is refused and the previous parameters stay: also in what the
  // node reports back (rqt_reconfigure and dynparam show that), not only in what it runs.
  dynamic_reconfigure::Config applied;
  EXPECT_TRUE(harness_->reconfigure(testing_support::ParameterChange().set("solver", "closed_form"),
                                    &applied));
  EXPECT_TRUE(harness_->waitForWarnContaining("reconfigure refused", 5.0));
  std::string reported_solver;
  for (const dynamic_reconfigure::StrParameter& p : applied.strs) {
    if (p.name == "solver") reported_solver = p.value;
  }
  EXPECT_EQ(reported_solver, last_solver) << "the refused value is reported as in force";
  publishing = false;
  publisher.join();
  const size_t during = harness_->transformCount() - before;
  EXPECT_GE(during, 10u) << "the nodelet stopped serving during the changes";

  // Settled parameters (the defaults, but k = 3) apply to the next alignment: k shows in the
  // markers. Some storm settings are coarse enough to be rejected, so all of them are reset.
  ASSERT_TRUE(harness_->reconfigure(testing_support::ParameterChange()
                                        .set("k", 3)
                                        .set("runs", 50)
                                        .set("threads", 2)
                                        .set("radius", 1.0)
                                        .set("nu", 5.0)
                                        .set("target_voxel_size", 0.0)
                                        .set("normal_voxel_size", 0.15)
                                        .set("solver", "gauss_newton")));
  // The reply comes once the change is live, so the cloud published now is aligned with k = 3,
  // whatever storm alignment is still running.
  const ros::Time settled = ros::Time::now();
  expectAligned(settled, truth, "after the storm");
  visualization_msgs::MarkerArray markers;
  ASSERT_TRUE(harness_->waitForMarkersStamped(settled, 5.0, &markers));
  size_t most_lines = 0;
  for (size_t lines : testing_support::groupAssociationLines(markers).lines_per_point)
    most_lines = std::max(most_lines, lines);
  EXPECT_EQ(most_lines, 3u);
  // Some storm settings (k = 1, a 3 cm target voxel) are coarser: the success bound, 5 cm.
  expectEveryPublishedNear(truth, 0.05);
  // Published == accepted: diagnostics agree that nothing rejected went out.
  std::string detail;
  EXPECT_TRUE(harness_->waitForAcceptedToMatchTransforms(10.0, &detail)) << detail;
}

}  // namespace
}  // namespace pda_registration
