// The scene and sensor simulation: ray casting, determinism per seed, and the Kinect 2 and VLP-16
// geometry and noise against their stated models.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <map>

#include "pda_registration/simulation/kinect_simulator.hpp"
#include "pda_registration/simulation/office_scene.hpp"
#include "pda_registration/simulation/scene.hpp"
#include "pda_registration/simulation/sensor_paths.hpp"
#include "pda_registration/simulation/velodyne_simulator.hpp"

namespace pda_registration {
namespace simulation {
namespace {

using Eigen::Vector2d;
using Eigen::Vector3d;

constexpr double kDegrees = M_PI / 180.0;
constexpr double kInfinity = std::numeric_limits<double>::infinity();

double standardDeviation(const std::vector<double>& values) {
  double sum = 0.0, sum_squares = 0.0;
  for (double v : values) sum += v;
  const double mean = sum / values.size();
  for (double v : values) sum_squares += (v - mean) * (v - mean);
  return std::sqrt(sum_squares / (values.size() - 1));
}

double mean(const std::vector<double>& values) {
  double sum = 0.0;
  for (double v : values) sum += v;
  return sum / values.size();
}

// A wall facing the camera: an x-slab spanning far beyond any field of view.
Scene wallAt(double x) {
  Scene scene;
  scene.addBox(Vector3d(x, -500.0, -500.0), Vector3d(x + 0.5, 500.0, 500.0));
  return scene;
}

// --- Scene -----------------------------------------------------------------------------------

TEST(Scene, RaysHitTheNearestSurfaceOfBoxesAndCylinders) {
  Scene scene;
  scene.addBox(Vector3d(3.0, 1.0, 1.0), Vector3d(2.0, -1.0, -1.0));  // corners in any order
  scene.addCylinder(Vector2d(5.0, 0.0), 0.5, -1.0, 1.0);
  const Vector3d x = Vector3d::UnitX(), y = Vector3d::UnitY(), z = Vector3d::UnitZ();

  EXPECT_DOUBLE_EQ(scene.castRay(Vector3d::Zero(), x), 2.0);          // box, not cylinder
  EXPECT_DOUBLE_EQ(scene.castRay(Vector3d(2.5, 0.0, 0.0), x), 0.5);   // inside: far face
  EXPECT_DOUBLE_EQ(scene.castRay(Vector3d(5.0, -3.0, 0.0), y), 2.5);  // cylinder side
  EXPECT_DOUBLE_EQ(scene.castRay(Vector3d(5.2, 0.0, 3.0), -z), 2.0);  // cylinder cap
  EXPECT_DOUBLE_EQ(scene.castRay(Vector3d(3.5, 0.0, 0.0), x), 1.0);   // between them
  EXPECT_EQ(scene.castRay(Vector3d::Zero(), -x), kInfinity);          // nothing behind
  EXPECT_EQ(scene.castRay(Vector3d(5.0, -3.0, 1.5), y), kInfinity);   // over the cylinder
  EXPECT_EQ(scene.castRay(Vector3d::Zero(), x, 1.9), kInfinity);      // beyond max range
  const Vector3d diagonal = Vector3d(1.0, 1.0, 0.0).normalized();
  EXPECT_NEAR(scene.castRay(Vector3d(0.0, -2.0, 0.0), diagonal), 2.0 * std::sqrt(2.0), 1e-12);

  EXPECT_EQ(scene.within(Vector3d::Zero(), 1.9).primitiveCount(), 0u);
  EXPECT_EQ(scene.within(Vector3d::Zero(), 2.1).primitiveCount(), 1u);
  EXPECT_EQ(scene.within(Vector3d::Zero(), 4.6).primitiveCount(), 2u);
  EXPECT_TRUE(scene.isInsideSolid(Vector3d(5.1, 0.2, 0.0)));
  EXPECT_FALSE(scene.isInsideSolid(Vector3d(4.0, 0.0, 0.0)));
}

TEST(OfficeScene, DeterministicPerSeedWithSensorsInFreeSpace) {
  const OfficeScene a = makeOfficeScene(7), b = makeOfficeScene(7), c = makeOfficeScene(8);
  ASSERT_EQ(a.scene.boxes().size(), b.scene.boxes().size());
  for (size_t i = 0; i < a.scene.boxes().size(); ++i) {
    EXPECT_EQ(a.scene.boxes()[i].min, b.scene.boxes()[i].min);
    EXPECT_EQ(a.scene.boxes()[i].max, b.scene.boxes()[i].max);
  }
  EXPECT_NE(a.office.max(), c.office.max());

  // Every seed keeps the walkway clear: no sensor inside or within 0.3 m of furniture.
  for (uint64_t seed = 1; seed <= 30; ++seed) {
    const OfficeScene office = makeOfficeScene(seed);
    EXPECT_GT(office.scene.primitiveCount(), 40u) << "seed " << seed;
    std::vector<Eigen::Isometry3d> poses = kinectTrajectory(office, 24);
    const std::vector<Eigen::Isometry3d> lidar = velodynePoses(office, 3);
    poses.insert(poses.end(), lidar.begin(), lidar.end());
    for (const Eigen::Isometry3d& pose : poses) {
      EXPECT_EQ(office.scene.within(pose.translation(), 0.3).primitiveCount(), 0u)
          << "seed " << seed << " at " << pose.translation().transpose();
    }
  }
}

// --- Kinect 2 --------------------------------------------------------------------------------

TEST(KinectSimulator, ImageCoversTheFieldOfViewAtConstantDepthOnAFacingWall) {
  KinectParameters parameters;
  parameters.noise = false;
  const PointList points =
      simulateKinectFrame(wallAt(2.0), Eigen::Isometry3d::Identity(), parameters, 1);
  ASSERT_EQ(points.size(), 512u * 424u);  // every pixel, in row order
  double max_horizontal = 0.0, max_vertical = 0.0;
  for (const Point& p : points) {
    ASSERT_NEAR(p.x(), 2.0, 1e-12);  // depth along the optical axis, not range
    max_horizontal = std::max(max_horizontal, std::atan2(std::abs(p.y()), p.x()) / kDegrees);
    max_vertical = std::max(max_vertical, std::atan2(std::abs(p.z()), p.x()) / kDegrees);
  }
  // Pixel centres reach to within half a pixel of the 70.6 x 60 degree field of view.
  EXPECT_NEAR(max_horizontal, 35.3, 0.1);
  EXPECT_LE(max_horizontal, 35.3);
  EXPECT_NEAR(max_vertical, 30.0, 0.1);
  EXPECT_LE(max_vertical, 30.0);
  // Row 0 is the top of the image, column 0 its left.
  EXPECT_GT(points.front().y(), 0.0);
  EXPECT_GT(points.front().z(), 0.0);
  EXPECT_LT(points.back().y(), 0.0);
  EXPECT_LT(points.back().z(), 0.0);

  EXPECT_EQ(simulateKinectFrame(wallAt(0.45), Eigen::Isometry3d::Identity(), parameters, 1).size(),
            0u);
  EXPECT_EQ(simulateKinectFrame(wallAt(4.55), Eigen::Isometry3d::Identity(), parameters, 1).size(),
            0u);
  EXPECT_EQ(simulateKinectFrame(wallAt(4.45), Eigen::Isometry3d::Identity(), parameters, 1).size(),
            512u * 424u);
}

TEST(KinectSimulator, OfficeFramePointsLieInTheFieldOfViewAndDepthRange) {
  const OfficeScene office = makeOfficeScene(4);
  const std::vector<Eigen::Isometry3d> poses = kinectTrajectory(office, 24);
  for (size_t frame : {0u, 1u, 2u, 13u}) {
    const PointList points = simulateKinectFrame(office.scene, poses[frame], KinectParameters(), 9);
    EXPECT_GT(points.size(), 512u * 424u / 2) << "frame " << frame;
    EXPECT_LE(points.size(), 512u * 424u);
    const Eigen::Isometry3d camera_from_world = poses[frame].inverse();
    for (const Point& world : points) {
      const Point p = camera_from_world * world;
      ASSERT_GE(p.x(), 0.5);
      ASSERT_LE(p.x(), 4.5);
      ASSERT_LE(std::atan2(std::abs(p.y()), p.x()), 35.3 * kDegrees);
      ASSERT_LE(std::atan2(std::abs(p.z()), p.x()), 30.0 * kDegrees);
    }
  }
}

TEST(KinectSimulator, DepthNoiseStdGrowsWithDepthSquaredAsStated) {
  KinectParameters parameters;
  EXPECT_DOUBLE_EQ(kinectDepthNoise(parameters, 0.4), 0.0012);
  EXPECT_DOUBLE_EQ(kinectDepthNoise(parameters, 2.4), 0.0012 + 0.0019 * 4.0);
  for (double depth : {1.0, 2.0, 3.0, 4.0}) {
    const PointList points =
        simulateKinectFrame(wallAt(depth), Eigen::Isometry3d::Identity(), parameters, 3);
    ASSERT_EQ(points.size(), 512u * 424u);
    std::vector<double> errors;
    for (const Point& p : points) errors.push_back(p.x() - depth);
    const double expected = kinectDepthNoise(parameters, depth);
    // 217k samples: the sample std is within 0.5% of the true one; allow 3%.
    EXPECT_NEAR(standardDeviation(errors), expected, 0.03 * expected) << "depth " << depth;
    EXPECT_NEAR(mean(errors), 0.0, 0.02 * expected) << "depth " << depth;
  }
}

TEST(KinectSimulator, OfficeDepthErrorsAgainstNoiseFreeRaysMatchTheModel) {
  const OfficeScene office = makeOfficeScene(5);
  const KinectParameters parameters;
  const Eigen::Isometry3d pose = kinectTrajectory(office, 24)[4];
  const PointList points = simulateKinectFrame(office.scene, pose, parameters, 21);
  // Each point stays on its pixel ray, so the exact surface is one ray cast away.
  std::vector<double> normalised;
  size_t far_off = 0;
  for (const Point& p : points) {
    const Vector3d ray = (p - pose.translation()).normalized();
    const double true_depth =
        office.scene.castRay(pose.translation(), ray) * (pose.linear().transpose() * ray).x();
    const double error = (pose.inverse() * p).x() - true_depth;
    const double sigma = kinectDepthNoise(parameters, true_depth);
    // Depth cut-offs truncate the noise: use pixels well inside the range.
    if (true_depth < 0.7 || true_depth > 4.2) continue;
    if (std::abs(error) > 8.0 * sigma) {  // a ray grazing an edge can hit another surface
      ++far_off;
      continue;
    }
    normalised.push_back(error / sigma);
  }
  ASSERT_GT(normalised.size(), 50000u);
  EXPECT_LT(far_off, normalised.size() / 1000);
  EXPECT_NEAR(standardDeviation(normalised), 1.0, 0.03);
  EXPECT_NEAR(mean(normalised), 0.0, 0.02);
}

// --- Velodyne VLP-16 -------------------------------------------------------------------------

TEST(VelodyneSimulator, NoiseFreeRevolutionHasVlp16RingsAzimuthsAndRanges) {
  const OfficeScene office = makeOfficeScene(3);
  VelodyneParameters parameters;
  parameters.noise = false;
  ASSERT_EQ(velodyneColumns(parameters), 1800);
  const Eigen::Isometry3d pose = velodynePoses(office, 3)[1];
  const PointList points = simulateVelodyneRevolution(office.scene, pose, parameters, 1);
  // A closed room: every beam returns, 16 rings x 1800 firings.
  ASSERT_EQ(points.size(), 16u * 1800u);
  std::map<int, int> points_per_ring;
  std::map<int, int> points_per_column;
  const Eigen::Isometry3d sensor_from_world = pose.inverse();
  for (const Point& world : points) {
    const Point p = sensor_from_world * world;
    const double range = p.norm();
    ASSERT_GE(range, 0.4);
    ASSERT_LE(range, 100.0);
    const double elevation = std::asin(p.z() / range) / kDegrees;
    const int ring = static_cast<int>(std::lround((elevation + 15.0) / 2.0));
    ASSERT_GE(ring, 0);
    ASSERT_LE(ring, 15);
    ASSERT_NEAR(elevation, -15.0 + 2.0 * ring, 1e-9);
    double azimuth = std::atan2(p.y(), p.x()) / kDegrees;
    if (azimuth < -1e-9) azimuth += 360.0;
    const double step = azimuth / 0.2;
    ASSERT_NEAR(step, std::round(step), 1e-6);
    ++points_per_ring[ring];
    ++points_per_column[static_cast<int>(std::lround(step)) % 1800];
  }
  EXPECT_EQ(points_per_ring.size(), 16u);
  for (const auto& ring : points_per_ring) EXPECT_EQ(ring.second, 1800) << "ring " << ring.first;
  EXPECT_EQ(points_per_column.size(), 1800u);
}

TEST(VelodyneSimulator, DropsReturnsOutsideTheRangeLimits) {
  VelodyneParameters parameters;
  parameters.noise = false;
  Scene scene;
  scene.addBox(Vector3d(50.0, -300.0, -300.0), Vector3d(51.0, 300.0, 300.0));      // in range
  scene.addBox(Vector3d(-151.0, -300.0, -300.0), Vector3d(-150.0, 300.0, 300.0));  // too far
  scene.addBox(Vector3d(-0.1, 0.2, -1.0), Vector3d(0.1, 0.3, 1.0));                // too close
  const PointList points =
      simulateVelodyneRevolution(scene, Eigen::Isometry3d::Identity(), parameters, 1);
  ASSERT_GT(points.size(), 1000u);
  for (const Point& p : points) ASSERT_NEAR(p.x(), 50.0, 1e-9);
}

TEST(VelodyneSimulator, RangeErrorsAgainstNoiseFreeRaysHaveThreeCentimetreStd) {
  const OfficeScene office = makeOfficeScene(6);
  const Eigen::Isometry3d pose = velodynePoses(office, 3)[0];
  std::vector<double> errors;
  size_t far_off = 0;
  for (uint64_t noise_seed : {1u, 2u, 3u}) {
    for (const Point& p :
         simulateVelodyneRevolution(office.scene, pose, VelodyneParameters(), noise_seed)) {
      const Vector3d beam = p - pose.translation();
      const double error =
          beam.norm() - office.scene.castRay(pose.translation(), beam.normalized());
      if (std::abs(error) > 0.3) {  // a beam grazing an edge can hit another surface
        ++far_off;
        continue;
      }
      errors.push_back(error);
    }
  }
  ASSERT_GT(errors.size(), 80000u);
  EXPECT_LT(far_off, errors.size() / 1000);
  EXPECT_NEAR(standardDeviation(errors), 0.03, 0.03 * 0.03);
  EXPECT_NEAR(mean(errors), 0.0, 0.001);
}

}  // namespace
}  // namespace simulation
}  // namespace pda_registration
