// Where a source point's target normal is read (em_run.hpp, NormalLookup): what lookupNormals
// returns for each choice, and what reading it at the candidate in the refine runs does end to end
// on a warped RGB-D fragment pair.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "pda_registration/core/candidate_sets.hpp"
#include "pda_registration/core/em_run.hpp"
#include "pda_registration/core/target_index.hpp"
#include "test_support/simulated_cases.hpp"

namespace pda_registration {
namespace {

// A cylinder of radius 1 m about the z axis, 1 cm apart: its normal turns from voxel to voxel.
PointList cylinder() {
  PointList points;
  for (int a = 0; a < 628; ++a) {
    const double angle = 0.01 * a;
    for (int h = 0; h < 100; ++h) {
      points.emplace_back(std::cos(angle), std::sin(angle), 0.01 * h);
    }
  }
  return points;
}

TEST(NormalLookup, ReadsAtTheNearestCandidateOrAtTheMovedPoint) {
  const PointList target = cylinder();
  const TargetIndex index(target);
  const SurfaceNormalMap normals(target, 0.15);
  // Outside the surface by 10 cm at three angles, and one point with no target within the radius.
  PointList source;
  for (const double angle : {0.3, 1.1, 2.0}) {
    source.emplace_back(1.1 * std::cos(angle), 1.1 * std::sin(angle), 0.5);
  }
  source.emplace_back(5.0, 5.0, 0.5);
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation() = Eigen::Vector3d(0.02, -0.03, 0.01);
  const CandidateSets candidates = findCandidateSets(index, source, T, 5, 0.5, 1);
  ASSERT_EQ(candidates.candidateCount(3), 0u);

  PointList at_candidate, at_point, every_point;
  lookupNormals(normals, source, T, 1, candidates, NormalLookup::kAtCandidate, false,
                &at_candidate);
  lookupNormals(normals, source, T, 1, candidates, NormalLookup::kAtPoint, false, &at_point);
  lookupNormals(normals, source, T, 1, candidates, NormalLookup::kAtCandidate, true, &every_point);
  int differ = 0;
  for (size_t j = 0; j < 3; ++j) {
    ASSERT_GT(candidates.candidateCount(j), 0u);
    const Point nearest = candidates.points[candidates.offsets[j]];
    EXPECT_EQ(at_candidate[j], normals.normalAt(nearest)) << j;
    EXPECT_EQ(at_point[j], normals.normalAt(T * source[j])) << j;
    EXPECT_EQ(every_point[j], at_candidate[j]) << j;
    // Both are the cylinder's radial direction, from different voxels.
    const Point radial = Point(nearest.x(), nearest.y(), 0.0).normalized();
    EXPECT_NEAR(std::abs(at_candidate[j].dot(radial)), 1.0, 0.02) << j;
    differ += at_candidate[j] != at_point[j] ? 1 : 0;
  }
  EXPECT_GT(differ, 0);
  // No candidates: nothing to read for a run; at the moved point for the final statistics.
  EXPECT_EQ(at_candidate[3], Point::Zero());
  EXPECT_EQ(at_point[3], Point::Zero());
  EXPECT_EQ(every_point[3], normals.normalAt(T * source[3]));
}

// A warped RGB-D fragment pair (pda_simulate --seed S --sparse-sensor kinect --distortion 0.01)
// from 5 deg / 0.25 m; the error is eq. 22 from the warp's least-squares rigid fit over the
// overlap. Read at the moved point, a point beside a surface's edge or pushed off it by the warp
// took its voxel's normal, often another surface's.
double warpedFragmentError(int layout) {
  const simulation::SimulatedMaps maps =
      simulation::simulateMaps(testing_support::rgbdFragmentOptions(layout, 0.01));
  RegistrationResult result;
  const double error =
      testing_support::alignedError(maps, RegistrationParameters(), 5.0, 0.25, 1, &result);
  EXPECT_TRUE(result.converged) << result.reason;
  std::printf("warped fragments, layout %d: %.4f m from the fit, %d runs\n", layout, error,
              result.runs);
  return error;
}

// Layout 3 is not in the benchmark: 5.9 cm with the normals read at the point, 4.3 at the
// candidate (a success by the benchmark's 5 cm); 3.7 since the polish searches within 6 sigma.
TEST(NormalLookup, RefineRunsBringAWarpedFragmentPairWithinFiveCentimetres) {
  EXPECT_LT(warpedFragmentError(3), 0.05);
}

// The benchmark's warped pair: 6.7 cm at the point, 5.1 at the candidate (4.9 since the polish
// searches within 6 sigma: warp_polish_test.cpp holds it to the 5-cm line).
TEST(NormalLookup, RefineRunsBringTheBenchmarksWarpedPairNearerItsFit) {
  EXPECT_LT(warpedFragmentError(2), 0.055);
}

}  // namespace
}  // namespace pda_registration
