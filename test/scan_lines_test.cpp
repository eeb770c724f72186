// Scan lines are not surfaces (docs/algorithm.md#scan-lines-are-not-surfaces): a lidar ring
// thickened by range noise lies in the laser's cone, and a normal read from it is the cone's, not
// the surface's. The normal map rejects thin strips, defers to a coarser voxel that holds several
// rings and a different plane, and its finest voxel follows the gap between the rings.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <utility>

#include "pda_registration/core/pda_registration.hpp"
#include "pda_registration/core/scan_line_scale.hpp"
#include "pda_registration/core/surface_normals.hpp"
#include "pda_registration/simulation/map_simulation.hpp"
#include "test_support/simulated_cases.hpp"

namespace pda_registration {
namespace {

using testing_support::alignedError;

TEST(SurfaceNormals, ANoiseThickenedScanLineIsNotASurfaceButAPlaneIs) {
  PointList line, plane;
  for (int i = 0; i < 1000; ++i) {
    // One scan line: 1 cm steps along x, +-1.5 cm of range noise across it, on the ground.
    line.emplace_back(0.01 * i, 0.015 * std::sin(1.7 * i), 0.0);
  }
  for (int i = 0; i < 100; ++i) {
    for (int j = 0; j < 100; ++j) plane.emplace_back(0.01 * i, 0.01 * j, 0.0);
  }
  const SurfaceNormalMap line_map(line, 0.15);
  const SurfaceNormalMap plane_map(plane, 0.15);
  EXPECT_EQ(line_map.voxelsWithNormal(), 0u);
  EXPECT_EQ(line_map.normalAt(Point(5.0, 0.0, 0.0)).norm(), 0.0);
  EXPECT_NEAR(std::abs(plane_map.normalAt(Point(0.5, 0.5, 0.0)).z()), 1.0, 1e-6);
}

// A single lidar revolution is dense along its rings and sparse across them; the normal map's
// finest voxel is raised to the gap between the rings (scan_line_scale.hpp).
TEST(ScanLineScale, IsTheGapBetweenScanLinesNotTheSpacingAlongThem) {
  PointList lines, plane;
  for (int line = 0; line < 10; ++line) {
    for (int i = 0; i < 400; ++i) lines.emplace_back(0.01 * i, 0.3 * line, 0.0);  // 30 cm apart
  }
  for (int i = 0; i < 200; ++i) {
    for (int j = 0; j < 200; ++j) plane.emplace_back(0.01 * i, 0.01 * j, 0.0);
  }
  const double line_scale = scanLineScale(TargetIndex(lines));
  EXPECT_GT(line_scale, 0.29);
  EXPECT_LT(line_scale, 0.45);
  EXPECT_LT(scanLineScale(TargetIndex(plane)), 0.05);  // a few 1-cm spacings
  // A length measured on the data: the same scene at a tenth of the size has a tenth of it.
  PointList small = lines;
  for (Point& p : small) p *= 0.1;
  EXPECT_NEAR(scanLineScale(TargetIndex(small)), 0.1 * line_scale, 1e-9);
}

// A wall 5 m from a lidar, x = 5, two rings on it 20 cm apart (z = 0.05 and 0.25), 2 cm steps
// along each, +-3 cm of range noise along the beams. Each 15-cm voxel holds one ring, a strip in
// the plane of its beam and ring (its normal near z, the cone's); the 30-cm voxel above holds
// both rings and the wall (its normal x). The wall's normal is read at the ring, not the cone's.
TEST(SurfaceNormals, ARingThickenedByRangeNoiseTakesTheWallOfItsCoarserVoxel) {
  PointList rings;
  int i = 0;
  for (double z : {0.05, 0.25}) {
    for (double y = 0.005; y < 0.3; y += 0.02, ++i) {
      const Eigen::Vector3d beam = Eigen::Vector3d(5.0, y, z).normalized();
      rings.push_back(Eigen::Vector3d(5.0, y, z) + 0.03 * std::sin(1.7 * i) * beam);
    }
  }
  const SurfaceNormalMap map(rings, 0.15);
  const Eigen::Vector3d at_ring = map.normalAt(Point(5.0, 0.07, 0.05));
  EXPECT_GT(std::abs(at_ring.x()), 0.99) << at_ring.transpose();
}

// A floor meeting a wall: the 15-cm voxel at the corner holds the floor alone, the 30-cm voxel
// around it floor and wall, which is no plane. The floor's own normal stands.
TEST(SurfaceNormals, ADetailWhoseCoarserVoxelIsNoPlaneKeepsItsNormal) {
  PointList corner;
  for (double a = 0.005; a < 0.3; a += 0.01) {
    for (double b = 0.005; b < 0.3; b += 0.01) {
      if (a < 0.2) corner.emplace_back(a, b, 0.01);  // the floor, up to the wall
      corner.emplace_back(0.2, b, a);                 // the wall at x = 0.2
    }
  }
  const SurfaceNormalMap map(corner, 0.15);
  EXPECT_GT(std::abs(map.normalAt(Point(0.07, 0.07, 0.01)).z()), 0.99);
  EXPECT_GT(std::abs(map.normalAt(Point(0.2, 0.2, 0.2)).x()), 0.99);
}

// The office mapped by a VLP-16 at the scan's own pose (scripts/benchmark's lattice_office_vlp16,
// pda_simulate --seed 3 --dense-sensor vlp16 --same-pose). From these seeds, with the rings' cone
// normals, the alignment came to rest 2 degrees off, one ring's spacing, converged with an
// expected error of 9 mm against 8.9 cm made.
TEST(LatticeCase, TheVlp16OfficeIsNotTiltedByOneRing) {
  simulation::MapSimulationOptions options;
  options.seed = 3;
  options.dense_sensor = simulation::DenseSensor::kVlp16;
  options.same_pose = true;
  options.dense_voxel_size = 0.0;  // a lidar map is kept whole, as pda_simulate keeps it
  const simulation::SimulatedMaps maps = simulation::simulateMaps(options);
  const std::pair<double, uint64_t> trials[] = {{10.0, 5}, {20.0, 5}, {20.0, 8}};
  for (const auto& [degrees, seed] : trials) {
    RegistrationResult result;
    const double error =
        alignedError(maps, RegistrationParameters(), degrees, degrees / 20.0, seed, &result);
    EXPECT_LT(error, 0.01) << degrees << " deg, seed " << seed;
    EXPECT_TRUE(result.converged) << result.reason;
  }
}

}  // namespace
}  // namespace pda_registration
