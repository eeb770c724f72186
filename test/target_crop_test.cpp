// Large targets: a map made of many copies of a real room is indexed only around the region the
// source can reach, gives exactly the answer of the single room, re-indexes only when the
// source's reach leaves the indexed region, and reports a source outside the map clearly.
#include <gtest/gtest.h>

#include "pda_registration/core/error_metrics.hpp"
#include "pda_registration/core/pda_registration.hpp"
#include "pda_registration/core/perturbation.hpp"
#include "pda_registration/core/target_map.hpp"
#include "pda_registration/tools/tiled_map.hpp"
#include "test_support/shared_data.hpp"

namespace pda_registration {
namespace {

using testing_support::loadSharedCase;
using testing_support::SharedCase;

TEST(ReachableRegion, CoversTranslationRotationAndRadius) {
  // Two points 2 m apart: centroid in the middle, farthest point 1 m from it.
  const PointList source = {Point(-1.0, 0.0, 0.0), Point(1.0, 0.0, 0.0)};
  const Eigen::Isometry3d T(Eigen::Translation3d(10.0, 0.0, 0.0));
  const AlignedBox none = reachableRegion(source, T, 0.0, 0.0, 0.0);
  EXPECT_TRUE(none.min.isApprox(Point(9.0, 0.0, 0.0)));
  EXPECT_TRUE(none.max.isApprox(Point(11.0, 0.0, 0.0)));
  // 0.5 m translation + 60 degrees (2 * 1 m * sin 30 deg = 1 m) + 0.25 m radius = 1.75 m.
  const AlignedBox reach = reachableRegion(source, T, 0.5, M_PI / 3.0, 0.25);
  EXPECT_NEAR(reach.min.x(), 9.0 - 1.75, 1e-12);
  EXPECT_NEAR(reach.max.y(), 1.75, 1e-12);
  // Every rotation of the source by up to 60 degrees about its centroid stays inside.
  for (double angle = -M_PI / 3.0; angle <= M_PI / 3.0; angle += 0.1) {
    const Eigen::Isometry3d turned = Eigen::Translation3d(10.0, 0.0, 0.0) *
                                     Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitZ()) *
                                     Eigen::Translation3d(-10.0, 0.0, 0.0) * T;
    for (const Point& p : source) EXPECT_TRUE(reach.contains(Point(turned * p)));
  }
  EXPECT_TRUE(reachableRegion(PointList(), T, 1.0, 0.1, 1.0).empty());
}

class TargetCrop : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    room_ = new SharedCase;
    std::string error;
    ASSERT_TRUE(loadSharedCase("room_scan", room_, &error)) << error;
    // 5 x 5 copies of the room, three room widths apart: the source's reach around one copy
    // (its bounds + 1 m + a 20 degree sweep + 1 m radius, + 25 % slack) holds no other copy.
    tiles_ = new TiledMap(tileCloud(room_->target, 5, 5, separatedTileSpacing(room_->target)));
  }
  static void TearDownTestSuite() {
    delete tiles_;
    delete room_;
  }

  static RegistrationParameters croppingParameters() {
    RegistrationParameters p;
    p.crop_above_points = static_cast<int>(room_->target.size());  // the tiled map is larger
    return p;
  }

  static SharedCase* room_;
  static TiledMap* tiles_;
};

SharedCase* TargetCrop::room_ = nullptr;
TiledMap* TargetCrop::tiles_ = nullptr;

TEST_F(TargetCrop, IndexesOnlyTheReachAndMatchesTheSingleRoom) {
  const Eigen::Isometry3d seed = room_->T_target_source * randomPerturbation(5.0, 0.25, 3);
  RegistrationParameters p = croppingParameters();

  PdaRegistration single(p);
  ASSERT_TRUE(single.setTarget(room_->target));
  const RegistrationResult expected = single.align(room_->source, seed);
  ASSERT_TRUE(expected.converged) << expected.reason;
  EXPECT_FALSE(expected.target_cropped);

  PdaRegistration large(p);
  ASSERT_TRUE(large.setTarget(tiles_->points));
  EXPECT_EQ(large.targetIndexBuilds(), 0u) << "a large target is indexed by align()";
  const RegistrationResult r = large.align(room_->source, seed);
  ASSERT_TRUE(r.converged) << r.reason;
  EXPECT_TRUE(r.target_cropped);
  EXPECT_EQ(r.target_points_total, tiles_->points.size());
  // The index holds the part of the middle room within reach, nothing of the other 24.
  EXPECT_LE(r.target_points_used, room_->target.size());
  EXPECT_GT(r.target_points_used, room_->target.size() / 2);
  EXPECT_GT(r.target_index_ms, 0.0);
  // Same candidates, same answer (up to the normal map's voxels at the crop's border).
  EXPECT_LT((r.T_target_source.matrix() - expected.T_target_source.matrix()).norm(), 1e-4);
  const PoseError e = poseError(room_->source, r.T_target_source, room_->T_target_source);
  EXPECT_LT(e.mean_distance, 0.03);
}

TEST_F(TargetCrop, ReindexesOnlyWhenTheReachLeavesTheIndexedRegion) {
  PdaRegistration large(croppingParameters());
  ASSERT_TRUE(large.setTarget(tiles_->points));
  const Eigen::Isometry3d truth = room_->T_target_source;
  ASSERT_TRUE(large.align(room_->source, truth * randomPerturbation(2.0, 0.1, 1)).converged);
  EXPECT_EQ(large.targetIndexBuilds(), 1u);

  // The next scan from nearly the same place: same index.
  const RegistrationResult again =
      large.align(room_->source, truth * randomPerturbation(2.0, 0.1, 2));
  EXPECT_TRUE(again.converged) << again.reason;
  EXPECT_EQ(again.target_index_ms, 0.0);
  EXPECT_EQ(large.targetIndexBuilds(), 1u);

  // The same room one copy further east: re-cropped there, and still right.
  const Eigen::Isometry3d east = Eigen::Translation3d(tiles_->spacing, 0.0, 0.0) * truth;
  const RegistrationResult moved =
      large.align(room_->source, east * randomPerturbation(2.0, 0.1, 3));
  ASSERT_TRUE(moved.converged) << moved.reason;
  EXPECT_EQ(large.targetIndexBuilds(), 2u);
  EXPECT_LT(poseError(room_->source, moved.T_target_source, east).mean_distance, 0.03);
}

TEST_F(TargetCrop, SourceOutsideTheMapIsNoOverlap) {
  PdaRegistration large(croppingParameters());
  ASSERT_TRUE(large.setTarget(tiles_->points));
  const Eigen::Isometry3d far_away = Eigen::Translation3d(0.0, 0.0, 500.0) * room_->T_target_source;
  const RegistrationResult r = large.align(room_->source, far_away);
  EXPECT_FALSE(r.converged);
  EXPECT_NE(r.reason.find("no overlap"), std::string::npos) << r.reason;
  // ... and the map still serves a good seed afterwards.
  EXPECT_TRUE(large.align(room_->source, room_->T_target_source).converged);
}

TEST_F(TargetCrop, SmallTargetsAndDisabledCroppingIndexTheWholeCloud) {
  RegistrationParameters p = croppingParameters();
  p.crop_above_points = 0;  // never crop
  p.target_subset = false;  // every point indexed by setTarget (the subset waits for a source)
  PdaRegistration whole(p);
  ASSERT_TRUE(whole.setTarget(tiles_->points));
  EXPECT_EQ(whole.targetIndexBuilds(), 1u) << "indexed by setTarget";
  const RegistrationResult r = whole.align(room_->source, room_->T_target_source);
  EXPECT_TRUE(r.converged) << r.reason;
  EXPECT_FALSE(r.target_cropped);
  EXPECT_EQ(r.target_points_used, tiles_->points.size());
}

}  // namespace
}  // namespace pda_registration
