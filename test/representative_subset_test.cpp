// The dense map's representative subset: the sample spacing of a cloud, the first point of each
// voxel (a growing map's subset extended equals the whole map's), thinning only maps much finer
// than the voxel, and the factory map thinned to its scan's spacing still registering within
// 2 mm of the ground truth; and the voxel filter (one mean per voxel) against a plain reference.
#include "pda_registration/core/representative_subset.hpp"

#include <gtest/gtest.h>

#include <map>
#include <random>
#include <set>
#include <tuple>

#include "pda_registration/core/error_metrics.hpp"
#include "pda_registration/core/pda_registration.hpp"
#include "pda_registration/core/perturbation.hpp"
#include "pda_registration/core/point_filter.hpp"
#include "pda_registration/core/voxel_cell.hpp"
#include "test_support/shared_data.hpp"

namespace pda_registration {
namespace {

// A plane sampled on a square grid of `step` (every point twice when `doubled`).
PointList grid(double step, double size, bool doubled) {
  PointList points;
  const int n = static_cast<int>(size / step);
  for (int x = 0; x < n; ++x) {
    for (int y = 0; y < n; ++y) {
      points.emplace_back(step * x + 0.3 * step, step * y + 0.3 * step, 1.0);
      if (doubled) points.push_back(points.back());
    }
  }
  return points;
}

TEST(RepresentativeSubset, SampleSpacingIgnoresDuplicates) {
  EXPECT_NEAR(sampleSpacing(grid(0.05, 2.0, true)), 0.05, 1e-9);
  EXPECT_NEAR(sampleSpacing(grid(0.01, 1.0, false)), 0.01, 1e-9);
  EXPECT_EQ(sampleSpacing(PointList{Point(1, 2, 3), Point(1, 2, 3)}), 0.0);
  EXPECT_EQ(sampleSpacing(PointList()), 0.0);
}

TEST(RepresentativeSubset, FirstPointPerVoxelAndAGrowingMapExtendsIt) {
  const PointList map = grid(0.01, 2.0, false);  // 40k points, 1 cm apart
  RepresentativeSubset whole(0.05);
  EXPECT_FALSE(whole.update(map));
  ASSERT_TRUE(whole.thinned());  // 25 points per 5 cm voxel
  EXPECT_NEAR(whole.redundancy(), 25.0, 1e-9);
  // One map point per occupied voxel, in map order.
  std::set<uint64_t> voxels;
  size_t next = 0;
  for (const Point& p : whole.points()) {
    EXPECT_TRUE(voxels.insert(voxelCellKey(voxelCellOf(p, 1.0 / 0.05))).second);
    while (next < map.size() && map[next] != p) ++next;
    ASSERT_LT(next, map.size()) << "not a map point, or out of order";
  }
  EXPECT_EQ(whole.points().size(), 1600u);
  // Grown in three steps: the same subset, each step a continuation with the old one as prefix.
  RepresentativeSubset growing(0.05);
  PointList previous;
  for (const size_t size : {size_t(10000), size_t(25000), map.size()}) {
    const bool continued = growing.update(PointList(map.begin(), map.begin() + size));
    EXPECT_EQ(continued, !previous.empty());
    ASSERT_GE(growing.points().size(), previous.size());
    EXPECT_TRUE(std::equal(previous.begin(), previous.end(), growing.points().begin()));
    previous = growing.points();
  }
  EXPECT_EQ(growing.points(), whole.points());
  // A different map is not a continuation: subset afresh.
  PointList moved = map;
  moved[3].x() += 1e-6;
  EXPECT_FALSE(growing.update(moved));
}

TEST(RepresentativeSubset, MapsNotMuchFinerThanTheVoxelStayWhole) {
  RepresentativeSubset subset(0.05);
  subset.update(grid(0.04, 2.0, false));  // about one point per voxel
  EXPECT_FALSE(subset.thinned());
  EXPECT_TRUE(subset.points().empty());
  EXPECT_LT(subset.redundancy(), kMuchFinerRedundancy);
  // Its continuation keeps the decision; a much finer new map is thinned.
  const PointList sparse = grid(0.04, 2.0, false);
  PointList grown = sparse;
  grown.emplace_back(0.5, 0.5, 1.0);
  grown.emplace_back(0.5, 0.5, 1.001);
  EXPECT_TRUE(subset.update(grown));
  EXPECT_FALSE(subset.thinned());
  EXPECT_FALSE(subset.update(grid(0.005, 0.5, false)));
  EXPECT_TRUE(subset.thinned());
  // A growing map whose first part is sparse: whole until, doubled, it is much finer; then
  // thinned afresh (not a continuation: its index is rebuilt once).
  PointList growing = grid(0.04, 2.0, false);
  RepresentativeSubset judged(0.05);
  EXPECT_FALSE(judged.update(growing));
  EXPECT_FALSE(judged.thinned());
  const PointList fine = grid(0.005, 1.0, false);
  growing.insert(growing.end(), fine.begin(), fine.begin() + 2000);
  EXPECT_TRUE(judged.update(growing));  // grown by less than double: the decision holds
  EXPECT_FALSE(judged.thinned());
  growing.insert(growing.end(), fine.begin() + 2000, fine.end());
  EXPECT_FALSE(judged.update(growing));
  EXPECT_TRUE(judged.thinned());
  RepresentativeSubset off(0.0);  // no voxel: whole
  off.update(grid(0.005, 0.5, false));
  EXPECT_FALSE(off.thinned());
}

TEST(RepresentativeSubset, FactoryMapThinnedToItsScansSpacingRegistersWithin2mm) {
  testing_support::SharedCase factory;
  std::string error;
  ASSERT_TRUE(testing_support::loadSharedCase("factory_p64", &factory, &error)) << error;
  const double spacing = sampleSpacing(factory.source);
  EXPECT_GT(spacing, 0.015);  // the 64-beam scan: ~2.5 cm between neighbours
  EXPECT_LT(spacing, 0.04);
  RepresentativeSubset subset(spacing);
  subset.update(factory.target);
  ASSERT_TRUE(subset.thinned());  // the map's rings are ~4 mm apart along the ring
  EXPECT_LT(subset.points().size(), factory.target.size() / 2);
  RegistrationParameters parameters;
  parameters.threads = 2;
  const PointList* whole = &factory.target;
  for (const PointList* target : {whole, &subset.points()}) {
    PdaRegistration registration(parameters);
    ASSERT_TRUE(registration.setTarget(*target));
    const RegistrationResult result = registration.align(
        factory.source, factory.T_target_source * randomPerturbation(3.0, 0.15, 11));
    ASSERT_TRUE(result.converged) << result.reason;
    const PoseError e = poseError(factory.source, result.T_target_source, factory.T_target_source);
    EXPECT_LT(e.mean_distance, 0.002) << (target == whole ? "whole map" : "subset");
  }
}

// The voxel filter against a plain reference (a map of cells in first-seen order): one mean per
// occupied voxel, summed in input order, whether the points come in runs of one voxel (pixel
// order) or shuffled, and on both sides of the origin.
TEST(VoxelDownsample, OneMeanPerVoxelInFirstSeenOrder) {
  std::mt19937 random(7);
  std::uniform_real_distribution<double> coordinate(-1.0, 1.0);
  PointList runs;
  for (int i = 0; i < 3000; ++i) {
    const Point centre(coordinate(random), coordinate(random), coordinate(random));
    for (int j = 0; j < 1 + i % 4; ++j) runs.push_back(centre + Point::Constant(0.001 * j));
  }
  PointList shuffled = runs;
  std::shuffle(shuffled.begin(), shuffled.end(), random);
  constexpr double kVoxel = 0.05;
  for (const PointList* points : {&runs, &shuffled}) {
    std::vector<std::tuple<int64_t, int64_t, int64_t>> order;
    std::map<std::tuple<int64_t, int64_t, int64_t>, std::pair<Point, int>> cells;
    for (const Point& p : *points) {
      const VoxelCell c = voxelCellOf(p, 1.0 / kVoxel);
      const auto key = std::make_tuple(c.x, c.y, c.z);
      auto found = cells.find(key);
      if (found == cells.end()) {
        order.push_back(key);
        cells.emplace(key, std::make_pair(p, 1));
      } else {
        found->second.first += p;
        ++found->second.second;
      }
    }
    const PointList means = voxelDownsample(*points, kVoxel);
    ASSERT_EQ(means.size(), order.size());
    for (size_t i = 0; i < order.size(); ++i) {
      const std::pair<Point, int>& cell = cells.at(order[i]);
      EXPECT_EQ(means[i], cell.first / cell.second) << "voxel " << i;
    }
  }
  EXPECT_EQ(voxelDownsample(runs, 0.0), runs);  // no voxel: the input as it is
}

}  // namespace
}  // namespace pda_registration
