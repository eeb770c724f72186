// rostest: a 5.5M-point dense map (7 x 7 copies of room_scan's 113k-point target). The nodelet
// indexes only the region each sparse map can reach: its diagnostics report a cropped index of a
// few percent of the map, the estimate lands on the ground truth, and a sparse map placed on
// another copy is served by a re-crop there. After the first answer the map (many room scans
// 3-10 cm apart on the same surfaces, a 10-cm scan) is indexed as its representative subset: the
// crop then holds the room's subset.
#include <gtest/gtest.h>

#include "nodelet_harness.hpp"
#include "pda_registration/core/error_metrics.hpp"
#include "pda_registration/core/perturbation.hpp"
#include "pda_registration/core/representative_subset.hpp"
#include "pda_registration/tools/tiled_map.hpp"
#include "test_support/shared_data.hpp"

namespace pda_registration {
namespace {

using testing_support::NodeletHarness;
using testing_support::toEigen;

TEST(NodeletLargeMap, IndexesOnlyTheSparseMapsReach) {
  testing_support::SharedCase room;
  std::string error;
  ASSERT_TRUE(testing_support::loadSharedCase("room_scan", &room, &error)) << error;
  const TiledMap map = tileCloud(room.target, 7, 7, separatedTileSpacing(room.target));
  ASSERT_GT(map.points.size(), 5000000u);
  NodeletHarness harness("pda_registration");
  ASSERT_TRUE(harness.waitForConnections(20.0));
  harness.publishDense(map.points, "dense_map");
  ASSERT_TRUE(harness.waitForLogContaining("dense map from", 60.0))
      << "the 5.5M-point map never arrived";

  // On the middle copy, then on the copy two steps east: each is a separate crop.
  const std::vector<Eigen::Isometry3d> places = {
      room.T_target_source,
      Eigen::Translation3d(2.0 * map.spacing, 0.0, 0.0) * room.T_target_source};
  for (size_t i = 0; i < places.size(); ++i) {
    ASSERT_TRUE(harness.publishSeed(places[i] * randomPerturbation(3.0, 0.15, 11 + i), "dense_map",
                                    "sparse_map"));
    ros::WallDuration(0.5).sleep();
    harness.publishSparse(room.source, "sparse_map");
    ASSERT_TRUE(harness.waitForNextTransform(60.0)) << "place " << i;
    const PoseError e =
        poseError(room.source, toEigen(harness.lastTransform().transform), places[i]);
    EXPECT_LT(e.mean_distance, 0.03) << "place " << i;
    EXPECT_LT(e.rotation_deg, 0.75) << "place " << i;

    ASSERT_TRUE(harness.waitForFreshDiagnostics(5.0));
    EXPECT_EQ(harness.diagnosticValue("target cropped"), "True");
    EXPECT_EQ(std::stoul(harness.diagnosticValue("dense map points")), map.points.size());
    const double indexed = std::stod(harness.diagnosticValue("indexed target points"));
    EXPECT_LT(indexed, 0.05 * static_cast<double>(map.points.size())) << "place " << i;
    // The crop covers a room: its points, or its subset when the map is thinned.
    const double voxel = std::stod(harness.diagnosticValue("dense map subset voxel [cm]")) / 100.0;
    size_t room_points = room.target.size();
    if (voxel > 0.0) {
      RepresentativeSubset subset(voxel, 0.0);
      subset.update(room.target);
      room_points = subset.points().size();
    }
    EXPECT_GT(indexed, 0.5 * static_cast<double>(room_points))
        << "place " << i << ", voxel " << voxel;
    std::cout << "large map, place " << i << ": indexed " << indexed << " of " << map.points.size()
              << " points (subset voxel " << voxel << " m); alignment "
              << harness.diagnosticValue("alignment time [ms]") << " ms; resident "
              << harness.diagnosticValue("resident memory [MB]") << " MB" << std::endl;
  }
}

}  // namespace
}  // namespace pda_registration
