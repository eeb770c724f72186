// The per-alignment source budget: a spatial subsample spreads the source over the space it
// covers, a random one keeps every point equally likely, the source as aligned is finite,
// voxelised and budgeted in that order, and the parameter is validated.
#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <random>

#include "pda_registration/core/pda_registration.hpp"
#include "pda_registration/core/point_filter.hpp"
#include "pda_registration/core/source_budget.hpp"
#include "pda_registration/core/target_index.hpp"

namespace pda_registration {
namespace {

// 90 % of the points crowd a 10-cm cube, the rest spread over a 4 m x 4 m slab; one NaN.
PointList unevenCloud() {
  std::mt19937 random(3);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  PointList cloud;
  for (int i = 0; i < 90000; ++i)
    cloud.emplace_back(0.1 * unit(random), 0.1 * unit(random), 0.1 * unit(random));
  for (int i = 0; i < 10000; ++i)
    cloud.emplace_back(4.0 * unit(random) - 2.0, 4.0 * unit(random) - 2.0, 0.2 * unit(random));
  std::shuffle(cloud.begin(), cloud.end(), random);
  cloud[17] = Point::Constant(std::numeric_limits<double>::quiet_NaN());
  return cloud;
}

size_t pointsOutsideTheCube(const PointList& points) {
  size_t outside = 0;
  for (const Point& p : points) outside += (p.array() > 0.1).any() || (p.array() < 0.0).any();
  return outside;
}

// The budget spreads the source over the space it covers: the crowded cube, which holds 90 % of
// the points, keeps about the share of the budget its few voxels are worth, not 90 %.
TEST(SourceBudget, SpreadsTheSourceOverSpaceWithinBudget) {
  const PointList cloud = unevenCloud();
  EXPECT_TRUE(spatialSubsample(cloud, 0).empty());       // no budget
  EXPECT_TRUE(spatialSubsample(cloud, 200000).empty());  // within budget: use as is
  PointList finite;
  for (const Point& p : cloud) {
    if (p.allFinite()) finite.push_back(p);
  }
  const TargetIndex index(finite);
  for (const size_t budget : {size_t(1000), size_t(5000), size_t(30000)}) {
    const PointList kept = spatialSubsample(cloud, budget);
    EXPECT_EQ(kept.size(), budget);
    const double outside = static_cast<double>(pointsOutsideTheCube(kept));
    // The cube's 90 % of the points fill few voxels: the spread-out part, which an unbiased
    // subsample gives 10 % of the budget, gets most of it (at 30000, nearly all its 10000 points
    // and the cube the rest). Not all of it at the smaller budgets: the budget looks at a random
    // eight times its size of the points first, 10 % of them outside the cube.
    if (budget == 30000) {
      EXPECT_GT(outside, 0.85 * 10000);
    } else {
      EXPECT_GT(outside / static_cast<double>(budget), 0.7) << "budget " << budget;
    }
    // Finite input points, and the same subsample every time.
    for (const Point& p : kept) ASSERT_TRUE(p.allFinite());
    for (size_t i = 0; i < kept.size(); i += 7) {
      size_t found;
      double d;
      ASSERT_EQ(index.nearestWithinRadius(kept[i], 1, 1e-9, &found, &d), 1u);
    }
    EXPECT_EQ(spatialSubsample(cloud, budget), kept);
    // The NaN changes nothing but itself: the same subsample as the filtered copy's.
    EXPECT_EQ(spatialSubsample(finite, budget), kept);
  }
}

// The approach stage's share of a source, and the budget's first cut of a very large one: every
// point equally likely, so the crowded cube keeps its 90 %.
TEST(SourceBudget, RandomSubsampleIsUnbiased) {
  const PointList cloud = unevenCloud();
  EXPECT_TRUE(randomSubsample(cloud, 0).empty());
  EXPECT_TRUE(randomSubsample(cloud, 200000).empty());
  PointList finite;
  for (const Point& p : cloud) {
    if (p.allFinite()) finite.push_back(p);
  }
  for (const size_t budget : {size_t(1000), size_t(5000), size_t(30000)}) {
    const PointList kept = randomSubsample(cloud, budget);
    EXPECT_EQ(kept.size(), budget);
    EXPECT_NEAR(static_cast<double>(pointsOutsideTheCube(kept)) / static_cast<double>(budget), 0.1,
                0.03)
        << "budget " << budget;
    for (const Point& p : kept) ASSERT_TRUE(p.allFinite());
    EXPECT_EQ(randomSubsample(cloud, budget), kept);
    // A cloud of finite points is sampled in place: the same subsample as the filtered copy's.
    EXPECT_EQ(randomSubsample(finite, budget), kept);
  }
}

// The source as the runs align it: its finite points, voxelised when asked, then within the
// budget; the flag says whether the budget cut it (the target's index follows a budgeted
// source's spacing).
TEST(SourceBudget, AlignedSourceIsFiniteVoxelisedThenBudgeted) {
  const PointList cloud = unevenCloud();
  PointList finite;
  for (const Point& p : cloud) {
    if (p.allFinite()) finite.push_back(p);
  }
  RegistrationParameters p;
  p.max_source_points = 0;
  PointList source(5, Point::Zero());  // memory in use from an earlier alignment
  EXPECT_FALSE(prepareAlignedSource(cloud, finite.size(), p, &source));
  EXPECT_EQ(source, finite);  // no budget: every finite point, in order

  p.max_source_points = 5000;  // cut straight from the input, as a filtered copy would be
  for (const bool spread : {false, true}) {
    p.spread_source_budget = spread;
    EXPECT_TRUE(prepareAlignedSource(cloud, finite.size(), p, &source));
    EXPECT_EQ(source, spread ? spatialSubsample(finite, 5000) : randomSubsample(finite, 5000));
  }

  p.spread_source_budget = false;
  p.source_voxel_size = 0.2;  // voxelised first: the cube's 90 % become one or a few voxel means
  const PointList voxelised = voxelDownsample(finite, 0.2);
  ASSERT_LT(voxelised.size(), size_t(5000));
  ASSERT_GT(voxelised.size(), size_t(200));
  EXPECT_FALSE(prepareAlignedSource(cloud, finite.size(), p, &source));
  EXPECT_EQ(source, voxelised);
  p.max_source_points = 200;  // ... and still over the budget
  EXPECT_TRUE(prepareAlignedSource(cloud, finite.size(), p, &source));
  EXPECT_EQ(source, randomSubsample(voxelised, 200));
}

TEST(SourceBudget, ParameterIsValidated) {
  RegistrationParameters p;
  EXPECT_EQ(validateParameters(p), "");  // 0: no budget
  p.max_source_points = 30000;
  EXPECT_EQ(validateParameters(p), "");
  p.max_source_points = -1;
  EXPECT_NE(validateParameters(p).find("max_source_points"), std::string::npos);
  p.max_source_points = p.min_correspondences - 1;
  EXPECT_NE(validateParameters(p).find("max_source_points"), std::string::npos);
}

}  // namespace
}  // namespace pda_registration
