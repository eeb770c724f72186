// The target's side of the per-alignment budget (RegistrationParameters::target_subset): a source
// thinned to max_source_points is aligned to the target's voxel means at the thinned source's
// spacing when the target is at least twice as fine; a source aligned whole gets every target
// point. Checked on real clouds against their ground truth, and for when the index is built.
#include <gtest/gtest.h>

#include <cmath>

#include "pda_registration/core/error_metrics.hpp"
#include "pda_registration/core/pda_registration.hpp"
#include "pda_registration/core/perturbation.hpp"
#include "pda_registration/core/representative_subset.hpp"
#include "pda_registration/core/source_budget.hpp"
#include "test_support/shared_data.hpp"

namespace pda_registration {
namespace {

testing_support::SharedCase load(const std::string& name) {
  testing_support::SharedCase shared;
  std::string error;
  EXPECT_TRUE(testing_support::loadSharedCase(name, &shared, &error)) << error;
  return shared;
}

double eq22(const testing_support::SharedCase& c, const RegistrationResult& r) {
  return poseError(c.source, r.T_target_source, c.T_target_source).mean_distance;
}

// kinect_pairwise: a 250k-point frame aligned to the next one. Budgeted to 15000 points it
// samples the scene ~1 cm apart against the target's ~4 mm: the target is indexed as its 1-cm
// voxel means, and the answer stays within the whole target's (ground truth: GICP, ~1 cm).
TEST(TargetSubset, BudgetedDenseSourceGetsTheTargetsVoxelMeans) {
  const testing_support::SharedCase kinect = load("kinect_pairwise");
  ASSERT_FALSE(kinect.source.empty());
  const Eigen::Isometry3d seed = kinect.T_target_source * randomPerturbation(5.0, 0.25, 3);
  RegistrationParameters p;
  PdaRegistration subset(p);
  ASSERT_TRUE(subset.setTarget(kinect.target));
  const RegistrationResult thinned = subset.align(kinect.source, seed);
  ASSERT_TRUE(thinned.converged) << thinned.reason;
  const double expected_voxel = sampleSpacing(
      randomSubsample(kinect.source, static_cast<size_t>(p.max_source_points)));
  EXPECT_NEAR(thinned.target_subset_voxel, expected_voxel, 1e-12);
  EXPECT_GT(thinned.target_subset_voxel, 0.005);
  EXPECT_LT(thinned.target_subset_voxel, 0.03);
  EXPECT_LT(thinned.target_points_used, thinned.target_points_total / 2);

  p.target_subset = false;
  PdaRegistration whole(p);
  ASSERT_TRUE(whole.setTarget(kinect.target));
  const RegistrationResult every_point = whole.align(kinect.source, seed);
  ASSERT_TRUE(every_point.converged) << every_point.reason;
  EXPECT_EQ(every_point.target_subset_voxel, 0.0);
  EXPECT_EQ(every_point.target_points_used, every_point.target_points_total);
  EXPECT_LT(eq22(kinect, thinned), 0.01);
  EXPECT_LT(eq22(kinect, thinned), eq22(kinect, every_point) + 0.002)
      << "thinned " << eq22(kinect, thinned) << " whole " << eq22(kinect, every_point);
}

// room_scan's 3480-point scan is within the budget: a sparse sensor's points each need the map's
// full detail, so every target point is indexed.
TEST(TargetSubset, SourceWithinTheBudgetGetsEveryTargetPoint) {
  const testing_support::SharedCase room = load("room_scan");
  ASSERT_FALSE(room.source.empty());
  PdaRegistration registration;
  ASSERT_TRUE(registration.setTarget(room.target));
  const RegistrationResult r =
      registration.align(room.source, room.T_target_source * randomPerturbation(5.0, 0.25, 4));
  ASSERT_TRUE(r.converged) << r.reason;
  EXPECT_EQ(r.target_subset_voxel, 0.0);
  EXPECT_EQ(r.target_points_used, r.target_points_total);
  EXPECT_LT(eq22(room, r), 0.03);  // ground truth from a registration: ~1 cm / 0.5 deg
}

// The first source decides the index (setTarget only keeps the cloud until then); the same kind
// of source keeps it, and a later target is indexed by setTarget the same way.
TEST(TargetSubset, IndexedOnceForTheSameKindOfSource) {
  const testing_support::SharedCase kinect = load("kinect_pairwise");
  ASSERT_FALSE(kinect.source.empty());
  PdaRegistration registration;
  ASSERT_TRUE(registration.setTarget(kinect.target));
  EXPECT_EQ(registration.targetIndexBuilds(), 0u);
  EXPECT_EQ(registration.target(), nullptr);
  for (uint64_t seed = 1; seed <= 2; ++seed) {
    const RegistrationResult r = registration.align(
        kinect.source, kinect.T_target_source * randomPerturbation(2.0, 0.1, seed));
    ASSERT_TRUE(r.converged) << r.reason;
    EXPECT_GT(r.target_subset_voxel, 0.0);
  }
  EXPECT_EQ(registration.targetIndexBuilds(), 1u);
  ASSERT_TRUE(registration.setTarget(kinect.target));
  EXPECT_EQ(registration.targetIndexBuilds(), 2u) << "indexed by setTarget";
  ASSERT_NE(registration.target(), nullptr);
  EXPECT_LT(registration.target()->size(), kinect.target.size() / 2);
}

// A source beyond the budget is sampled straight from the input, non-finite points skipped: the
// same alignment as the source without them, and they are counted as dropped.
TEST(TargetSubset, BudgetedSourceWithNonFinitePointsAlignsAsWithout) {
  const testing_support::SharedCase room = load("room_scan");
  ASSERT_GT(room.source.size(), 3000u);
  RegistrationParameters p;
  p.max_source_points = 2000;
  PointList with_gaps;
  for (size_t i = 0; i < room.source.size(); ++i) {
    if (i % 100 == 0) with_gaps.push_back(Point::Constant(std::nan("")));
    with_gaps.push_back(room.source[i]);
  }
  const size_t gaps = with_gaps.size() - room.source.size();
  const Eigen::Isometry3d seed = room.T_target_source * randomPerturbation(5.0, 0.25, 2);
  PdaRegistration registration(p);
  ASSERT_TRUE(registration.setTarget(room.target));
  const RegistrationResult clean = registration.align(room.source, seed);
  const RegistrationResult gapped = registration.align(with_gaps, seed);
  ASSERT_TRUE(clean.converged) << clean.reason;
  EXPECT_EQ(clean.source_points_used, 2000u);
  EXPECT_EQ(gapped.source_points_used, 2000u);
  EXPECT_EQ(gapped.source_points_dropped, gaps);
  EXPECT_TRUE(gapped.T_target_source.isApprox(clean.T_target_source, 0.0));
  EXPECT_LT(eq22(room, gapped), 0.03);
}

}  // namespace
}  // namespace pda_registration
