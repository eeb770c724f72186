// The ground truth of a warped dense map (warp_rigid_fit.hpp): the best rigid fit of the known
// warp over the overlap, against the warp's fixed point (the transform before warping).
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "pda_registration/core/error_metrics.hpp"
#include "pda_registration/core/pda_registration.hpp"
#include "pda_registration/core/perturbation.hpp"
#include "pda_registration/simulation/map_simulation.hpp"
#include "pda_registration/simulation/warp_rigid_fit.hpp"

namespace pda_registration {
namespace simulation {
namespace {

using Eigen::Isometry3d;
using Eigen::Vector2d;
using Eigen::Vector3d;

// Points filling an office-sized box (12 x 8 x 3 m), in the scene frame.
PointList officeSizedCloud() {
  std::mt19937_64 random(5);
  std::uniform_real_distribution<double> x(0.0, 12.0), y(0.0, 8.0), z(0.0, 3.0);
  PointList points;
  for (int i = 0; i < 5000; ++i) points.emplace_back(x(random), y(random), z(random));
  return points;
}

double sumOfSquares(const Isometry3d& T, const DriftDistortion& warp, const PointList& points) {
  double sum = 0.0;
  for (const Point& y : points) sum += (T * y - warp.apply(y)).squaredNorm();
  return sum;
}

double meanDistance(const Isometry3d& T, const DriftDistortion& warp, const PointList& points) {
  double sum = 0.0;
  for (const Point& y : points) sum += (T * y - warp.apply(y)).norm();
  return sum / static_cast<double>(points.size());
}

// Small office options, so the library-level checks stay fast.
MapSimulationOptions smallOffice(double distortion) {
  MapSimulationOptions options;
  options.seed = 13;
  options.kinect_frames = 3;
  options.velodyne_revolutions = 1;
  options.distortion = distortion;
  return options;
}

TEST(WarpRigidFit, ZeroWarpFitsTheIdentity) {
  const PointList points = officeSizedCloud();
  const WarpRigidFit fit = fitRigidToWarp(DriftDistortion{Vector2d(6.0, 4.0), 0.0}, points);
  EXPECT_EQ(fit.overlap_points, points.size());
  EXPECT_LT((fit.T_fit.matrix() - Eigen::Matrix4d::Identity()).norm(), 1e-9);
  EXPECT_LT(fit.mean_residual_fit, 1e-9);
  EXPECT_LT(fit.mean_residual_fixed, 1e-12);  // W(y) = c + (y - c): rounding only
}

TEST(WarpRigidFit, KnownWarpFitsBetterThanTheFixedPointAndThePerturbedFit) {
  const PointList points = officeSizedCloud();
  const DriftDistortion warp{Vector2d(6.0, 4.0), 0.01};
  const WarpRigidFit fit = fitRigidToWarp(warp, points);
  EXPECT_EQ(fit.overlap_points, points.size());
  // The bend lifts the room's edges: the fit is no identity.
  EXPECT_GT(fit.T_fit.translation().norm(), 0.01);
  const double count = static_cast<double>(points.size());
  EXPECT_NEAR(fit.rms_residual_fixed,
              std::sqrt(sumOfSquares(Isometry3d::Identity(), warp, points) / count), 1e-12);
  EXPECT_NEAR(fit.rms_residual_fit, std::sqrt(sumOfSquares(fit.T_fit, warp, points) / count),
              1e-12);
  EXPECT_NEAR(fit.mean_residual_fixed, meanDistance(Isometry3d::Identity(), warp, points), 1e-12);
  EXPECT_NEAR(fit.mean_residual_fit, meanDistance(fit.T_fit, warp, points), 1e-12);
  EXPECT_LT(fit.rms_residual_fit, 0.9 * fit.rms_residual_fixed);

  // A least-squares minimum: every small rotation or translation away from it costs.
  const double best = sumOfSquares(fit.T_fit, warp, points);
  for (int axis = 0; axis < 3; ++axis) {
    for (const double sign : {-1.0, 1.0}) {
      Isometry3d turned = Isometry3d::Identity();
      turned.linear() = Eigen::AngleAxisd(sign * 1e-3, Vector3d::Unit(axis)).toRotationMatrix();
      Isometry3d shifted = Isometry3d::Identity();
      shifted.translation() = sign * 1e-3 * Vector3d::Unit(axis);
      EXPECT_GT(sumOfSquares(turned * fit.T_fit, warp, points), best) << "axis " << axis;
      EXPECT_GT(sumOfSquares(fit.T_fit * turned, warp, points), best) << "axis " << axis;
      EXPECT_GT(sumOfSquares(shifted * fit.T_fit, warp, points), best) << "axis " << axis;
    }
  }
}

TEST(WarpRigidFit, OverlapKeepsPointsNearTheReferenceOnly) {
  const PointList reference = {Point(0.0, 0.0, 0.0), Point(5.0, 0.0, 0.0)};
  const PointList points = {Point(0.05, 0.0, 0.0), Point(0.0, 0.2, 0.0), Point(5.0, 0.0, 0.09),
                            Point(2.5, 0.0, 0.0),
                            Point(std::nan(""), 0.0, 0.0)};
  const PointList inside = pointsInOverlap(points, reference, kWarpOverlapRadius);
  ASSERT_EQ(inside.size(), 2u);
  EXPECT_EQ(inside[0], points[0]);
  EXPECT_EQ(inside[1], points[2]);
  EXPECT_TRUE(pointsInOverlap(points, {}, kWarpOverlapRadius).empty());
  // Fewer than 3 points: undetermined, the fixed point stays.
  const WarpRigidFit fit = fitRigidToWarp(DriftDistortion{Vector2d::Zero(), 0.01}, inside);
  EXPECT_EQ(fit.T_fit.matrix(), Eigen::Matrix4d::Identity());
}

TEST(WarpRigidFit, SimulationWithoutDistortionKeepsTheChosenTransformExactly) {
  const SimulatedMaps maps = simulateMaps(smallOffice(0.0));
  EXPECT_EQ(maps.T_target_source.matrix(), maps.T_target_source_unwarped.matrix());
  EXPECT_EQ(maps.warp_fit.overlap_points, 0u);
  EXPECT_EQ(maps.T_target_source.matrix(),
            transformFromYawPitchRoll(25.0, 0.0, 0.0, Vector3d(1.5, -0.8, 0.1)).matrix());
}

TEST(WarpRigidFit, SimulationWithDistortionFitsTheWarpOverTheOverlap) {
  const SimulatedMaps rigid = simulateMaps(smallOffice(0.0));
  const SimulatedMaps warped = simulateMaps(smallOffice(0.01));
  // The sparse map and the chosen transform are the rigid case's; only the ground truth moves.
  EXPECT_EQ(warped.T_target_source_unwarped.matrix(), rigid.T_target_source.matrix());
  ASSERT_EQ(warped.sparse.size(), rigid.sparse.size());
  EXPECT_TRUE(warped.T_target_source.isApprox(
      warped.warp_fit.T_fit * warped.T_target_source_unwarped, 1e-15));
  // The overlap is the sparse points near the undistorted dense map: most, not all (3 Kinect
  // frames see a corner of what one lidar revolution sees).
  PointList in_scene;
  for (const Point& p : rigid.sparse) in_scene.push_back(rigid.T_target_source * p);
  const PointList overlap = pointsInOverlap(in_scene, rigid.dense, kWarpOverlapRadius);
  EXPECT_EQ(warped.warp_fit.overlap_points, overlap.size());
  EXPECT_GT(overlap.size(), 100u);
  EXPECT_LT(overlap.size(), rigid.sparse.size());
  const DriftDistortion warp{rigid.office.office.center(), 0.01};
  const WarpRigidFit direct = fitRigidToWarp(warp, overlap);
  EXPECT_TRUE(direct.T_fit.isApprox(warped.warp_fit.T_fit, 1e-9));
  // Over the office's overlap the fit lowers the mean distance to the warp as well as the RMS.
  EXPECT_LT(warped.warp_fit.rms_residual_fit, warped.warp_fit.rms_residual_fixed);
  EXPECT_LT(warped.warp_fit.mean_residual_fit, warped.warp_fit.mean_residual_fixed);
  EXPECT_FALSE(warped.T_target_source.isApprox(warped.T_target_source_unwarped, 1e-4));
}

// The benchmark's distorted office (scripts/benchmark: --seed 2 --distortion 0.01): PDA with the
// defaults lands nearer the fitted ground truth than the warp's fixed point, i.e. the fixed point
// blamed PDA for part of the warp.
TEST(WarpRigidFit, PdaOnTheDistortedOfficeLandsNearerTheFitThanTheFixedPoint) {
  MapSimulationOptions options;
  options.seed = 2;
  options.distortion = 0.01;
  const SimulatedMaps maps = simulateMaps(options);
  PdaRegistration registration((RegistrationParameters()));
  ASSERT_TRUE(registration.setTarget(maps.dense));
  for (uint64_t seed : {1u, 2u, 3u}) {
    const Isometry3d initial = maps.T_target_source * randomPerturbation(3.0, 0.15, seed);
    const RegistrationResult result = registration.align(maps.sparse, initial);
    ASSERT_TRUE(result.converged) << result.reason;
    const double to_fit =
        poseError(maps.sparse, result.T_target_source, maps.T_target_source).mean_distance;
    const double to_fixed_point =
        poseError(maps.sparse, result.T_target_source, maps.T_target_source_unwarped)
            .mean_distance;
    EXPECT_LT(to_fit, to_fixed_point) << "perturbation seed " << seed;
  }
}

}  // namespace
}  // namespace simulation
}  // namespace pda_registration
