// The scene and sensor simulation: ray casting, determinism per seed, the Kinect 2 and VLP-16
// geometry and noise, the drift distortion, PDA on a simulated pair, the bag, and pda_simulate
// run as a user runs it.
#include <geometry_msgs/TransformStamped.h>
#include <gtest/gtest.h>
#include <omp.h>
#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <sensor_msgs/PointCloud2.h>
#include <tf2_msgs/TFMessage.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <map>

#include "pda_registration/core/error_metrics.hpp"
#include "pda_registration/core/pda_registration.hpp"
#include "pda_registration/core/perturbation.hpp"
#include "pda_registration/core/source_budget.hpp"
#include "pda_registration/core/transform_io.hpp"
#include "pda_registration/simulation/drift_distortion.hpp"
#include "pda_registration/simulation/map_bag_writer.hpp"
#include "pda_registration/simulation/map_simulation.hpp"
#include "pda_registration/simulation/sensor_paths.hpp"
#include "pda_registration/tools/cloud_io.hpp"
#include "test_support/command_run.hpp"

namespace pda_registration {
namespace simulation {
namespace {

using Eigen::Vector2d;
using Eigen::Vector3d;
using testing_support::CommandRun;
using testing_support::jsonNumber;
using testing_support::runCommand;
using testing_support::temporaryPath;

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

// Small but complete maps, so the determinism tests stay fast.
MapSimulationOptions smallOptions(uint64_t seed) {
  MapSimulationOptions options;
  options.seed = seed;
  options.kinect_frames = 3;
  options.velodyne_revolutions = 1;
  return options;
}

bool samePoints(const PointList& a, const PointList& b) {
  if (a.size() != b.size()) return false;
  for (size_t i = 0; i < a.size(); ++i) {
    if (a[i] != b[i]) return false;
  }
  return true;
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

// --- Distortion ------------------------------------------------------------------------------

TEST(DriftDistortion, ZeroAtTheCentreAndAmountTimesRadiusAtFiveMetres) {
  const DriftDistortion drift{Vector2d(5.0, 3.0), 0.01};
  const Point centre(5.0, 3.0, 1.2);
  EXPECT_EQ(drift.apply(centre), centre);
  // 5 m away: 5 cm outwards and 5 cm up.
  EXPECT_TRUE(drift.apply(Point(10.0, 3.0, 0.5)).isApprox(Point(10.05, 3.0, 0.55), 1e-12));
  EXPECT_TRUE(drift.apply(Point(8.0, 7.0, 0.0)).isApprox(Point(8.03, 7.04, 0.05), 1e-12));
  // Quadratic growth: a quarter of the displacement at half the distance.
  const Point half = drift.apply(Point(7.5, 3.0, 0.0));
  EXPECT_NEAR(half.x() - 7.5, 0.0125, 1e-12);
  EXPECT_NEAR(half.z(), 0.0125, 1e-12);

  PointList points = {Point(1.0, 2.0, 3.0), Point(-4.0, 8.0, 0.0)};
  const PointList original = points;
  applyDistortion(DriftDistortion{Vector2d(5.0, 3.0), 0.0}, &points);
  EXPECT_TRUE(samePoints(points, original));
}

// --- Whole simulation ------------------------------------------------------------------------

TEST(MapSimulation, SameSeedGivesIdenticalMapsAndAnotherSeedDifferentOnes) {
  const SimulatedMaps a = simulateMaps(smallOptions(11));
  const SimulatedMaps b = simulateMaps(smallOptions(11));
  const SimulatedMaps c = simulateMaps(smallOptions(12));
  ASSERT_GT(a.dense.size(), 10000u);
  ASSERT_GT(a.sparse.size(), 10000u);
  EXPECT_TRUE(samePoints(a.dense, b.dense));
  EXPECT_TRUE(samePoints(a.sparse, b.sparse));
  EXPECT_FALSE(samePoints(a.dense, c.dense));
  EXPECT_FALSE(samePoints(a.sparse, c.sparse));

  // Ray casting runs on several threads; the maps must not depend on how many.
  const int threads = omp_get_max_threads();
  omp_set_num_threads(1);
  const SimulatedMaps single = simulateMaps(smallOptions(11));
  omp_set_num_threads(std::max(2, threads));
  const SimulatedMaps several = simulateMaps(smallOptions(11));
  omp_set_num_threads(threads);
  EXPECT_TRUE(samePoints(single.dense, several.dense));
  EXPECT_TRUE(samePoints(single.sparse, a.sparse));
}

TEST(MapSimulation, SparseMapIsInItsOwnFrameAndDistortionOnlyWarpsTheDenseMap) {
  MapSimulationOptions options = smallOptions(13);
  options.kinect.noise = options.velodyne.noise = false;
  const SimulatedMaps rigid = simulateMaps(options);
  const Eigen::Isometry3d expected =
      transformFromYawPitchRoll(25.0, 0.0, 0.0, Vector3d(1.5, -0.8, 0.1));
  EXPECT_TRUE(rigid.T_target_source.isApprox(expected, 1e-12));
  // Noise-free sparse points moved into the dense frame are exactly where the lidar's beams
  // first hit the scene.
  const Eigen::Isometry3d lidar_in_dense = rigid.T_target_source * rigid.velodyne_poses[0];
  size_t on_surface = 0;
  for (const Point& p : rigid.sparse) {
    const Point in_dense = rigid.T_target_source * p;
    const Vector3d towards_point = (in_dense - lidar_in_dense.translation()).normalized();
    const double range = rigid.office.scene.castRay(lidar_in_dense.translation(), towards_point);
    on_surface += std::abs(range - (in_dense - lidar_in_dense.translation()).norm()) < 1e-6;
  }
  EXPECT_EQ(on_surface, rigid.sparse.size());

  options.distortion = 0.01;
  const SimulatedMaps warped = simulateMaps(options);
  EXPECT_TRUE(samePoints(warped.sparse, rigid.sparse));
  ASSERT_EQ(warped.dense.size(), rigid.dense.size());
  const DriftDistortion drift{rigid.office.office.center(), 0.01};
  double largest_shift = 0.0;
  for (size_t i = 0; i < rigid.dense.size(); ++i) {
    ASSERT_TRUE(warped.dense[i].isApprox(drift.apply(rigid.dense[i]), 1e-12));
    largest_shift = std::max(largest_shift, (warped.dense[i] - rigid.dense[i]).norm());
  }
  EXPECT_GT(largest_shift, 0.02);
}

TEST(MapSimulation, PdaRecoversTheGroundTruthFromAPerturbedSeed) {
  const SimulatedMaps maps = simulateMaps(MapSimulationOptions());
  RegistrationParameters parameters;
  parameters.radius = 0.5;
  PdaRegistration registration(parameters);
  ASSERT_TRUE(registration.setTarget(maps.dense));
  for (uint64_t seed : {1u, 2u, 3u}) {
    const Eigen::Isometry3d initial = maps.T_target_source * randomPerturbation(3.0, 0.15, seed);
    const RegistrationResult result = registration.align(maps.sparse, initial);
    ASSERT_TRUE(result.converged) << result.reason;
    const PoseError error = poseError(maps.sparse, result.T_target_source, maps.T_target_source);
    EXPECT_LT(error.translation, 0.03) << "perturbation seed " << seed;
    EXPECT_LT(error.rotation_deg, 0.5) << "perturbation seed " << seed;
    EXPECT_LT(error.mean_distance, 0.03) << "perturbation seed " << seed;
  }
}

// The nodelet's per-alignment source budget (max_source_points, 15000 by default) on the demo's
// scene (86k sparse points): the estimate stays within 2 mm (eq. 22) of the one on every point. A
// spatially uniform subsample failed this (2.0 -> 4.4 mm: it re-weights the map towards its
// sparse far parts); an unbiased one keeps the full cloud's objective (2.0 mm).
TEST(MapSimulation, SourceBudgetKeepsTheAccuracyOfTheWholeSparseMap) {
  const SimulatedMaps maps = simulateMaps(MapSimulationOptions());
  ASSERT_GT(maps.sparse.size(), 60000u);
  PdaRegistration registration((RegistrationParameters()));
  ASSERT_TRUE(registration.setTarget(maps.dense));
  const Eigen::Isometry3d initial = maps.T_target_source * randomPerturbation(3.0, 0.15, 1);
  const PointList budgeted = applySourceBudget(maps.sparse, 15000);
  ASSERT_EQ(budgeted.size(), 15000u);
  const RegistrationResult all = registration.align(maps.sparse, initial);
  const RegistrationResult some = registration.align(budgeted, initial);
  ASSERT_TRUE(all.converged) << all.reason;
  ASSERT_TRUE(some.converged) << some.reason;
  const double all_error =
      poseError(maps.sparse, all.T_target_source, maps.T_target_source).mean_distance;
  const double some_error =
      poseError(maps.sparse, some.T_target_source, maps.T_target_source).mean_distance;
  EXPECT_LT(some_error, all_error + 0.002) << "all points " << all_error;
}

// --- Bag -------------------------------------------------------------------------------------

Eigen::Isometry3d fromTransformMessage(const geometry_msgs::Transform& t) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() =
      Eigen::Quaterniond(t.rotation.w, t.rotation.x, t.rotation.y, t.rotation.z).toRotationMatrix();
  T.translation() = Vector3d(t.translation.x, t.translation.y, t.translation.z);
  return T;
}

TEST(MapBag, HoldsTheTopicsMessageCountsFramesAndTransforms) {
  const PointList dense = {Point(1.0, 2.0, 3.0), Point(4.0, 5.0, 6.0), Point(7.0, 8.0, 9.0)};
  const PointList sparse = {Point(-1.0, 0.5, 0.25), Point(2.0, -3.0, 1.5)};
  const Eigen::Isometry3d truth = transformFromYawPitchRoll(25.0, 2.0, -1.0, Vector3d(1, 2, 3));
  const Eigen::Isometry3d seed = truth * randomPerturbation(3.0, 0.15, 4);
  const std::string path = temporaryPath("maps.bag");
  MapBagSummary summary;
  std::string error;
  ASSERT_TRUE(writeMapBag(path, dense, sparse, truth, seed, MapBagOptions(), &summary, &error))
      << error;
  EXPECT_DOUBLE_EQ(summary.duration, 6.0);

  rosbag::Bag bag(path, rosbag::bagmode::Read);
  std::map<std::string, int> counts;
  std::vector<double> sparse_stamps, tf_stamps;
  bool dense_latched = false;
  for (const rosbag::MessageInstance& message : rosbag::View(bag)) {
    ++counts[message.getTopic()];
    const double time = message.getTime().toSec();
    if (message.getTopic() == "/dense_map" || message.getTopic() == "/sparse_map") {
      const auto cloud = message.instantiate<sensor_msgs::PointCloud2>();
      ASSERT_NE(cloud, nullptr);
      const bool is_dense = message.getTopic() == "/dense_map";
      const PointList& expected = is_dense ? dense : sparse;
      EXPECT_EQ(cloud->header.frame_id, is_dense ? "dense_map" : "sparse_map");
      EXPECT_DOUBLE_EQ(cloud->header.stamp.toSec(), time);
      ASSERT_EQ(cloud->width * cloud->height, expected.size());
      ASSERT_EQ(cloud->data.size(), expected.size() * cloud->point_step);
      float last[3];
      std::memcpy(last, &cloud->data[(expected.size() - 1) * cloud->point_step], sizeof(last));
      EXPECT_FLOAT_EQ(last[2], static_cast<float>(expected.back().z()));
      if (is_dense) {
        dense_latched = message.getConnectionHeader()->count("latching") &&
                        message.getConnectionHeader()->at("latching") == "1";
      } else {
        sparse_stamps.push_back(time);
      }
    } else if (message.getTopic() == "/tf") {
      const auto tf = message.instantiate<tf2_msgs::TFMessage>();
      ASSERT_NE(tf, nullptr);
      ASSERT_EQ(tf->transforms.size(), 1u);
      EXPECT_EQ(tf->transforms[0].header.frame_id, "dense_map");
      EXPECT_EQ(tf->transforms[0].child_frame_id, "sparse_map");
      EXPECT_TRUE(fromTransformMessage(tf->transforms[0].transform).isApprox(seed, 1e-9));
      tf_stamps.push_back(time);
    } else if (message.getTopic() == "/ground_truth") {
      const auto truth_message = message.instantiate<geometry_msgs::TransformStamped>();
      ASSERT_NE(truth_message, nullptr);
      EXPECT_EQ(truth_message->header.frame_id, "dense_map");
      EXPECT_EQ(truth_message->child_frame_id, "sparse_map");
      EXPECT_TRUE(fromTransformMessage(truth_message->transform).isApprox(truth, 1e-9));
    }
  }
  EXPECT_EQ(counts.size(), 4u);
  EXPECT_EQ(counts["/dense_map"], 2);
  EXPECT_EQ(counts["/sparse_map"], 5);
  EXPECT_EQ(counts["/tf"], 61);  // 10 Hz over 6 s, both ends included
  EXPECT_EQ(counts["/ground_truth"], 7);
  EXPECT_TRUE(dense_latched);
  ASSERT_EQ(sparse_stamps.size(), 5u);
  for (size_t i = 1; i < sparse_stamps.size(); ++i) {
    EXPECT_NEAR(sparse_stamps[i] - sparse_stamps[i - 1], 1.0, 1e-9);
  }
  // The seed can be interpolated at every sparse map's stamp.
  EXPECT_LT(tf_stamps.front(), sparse_stamps.front());
  EXPECT_GT(tf_stamps.back(), sparse_stamps.back());
  EXPECT_NEAR(tf_stamps[1] - tf_stamps[0], 0.1, 1e-6);
  // The seed is the stated perturbation of the truth.
  const PoseError seed_error = poseError({Point::Zero()}, seed, truth);
  EXPECT_NEAR(seed_error.rotation_deg, 3.0, 1e-9);

  EXPECT_FALSE(writeMapBag("/nonexistent-directory/maps.bag", dense, sparse, truth, seed,
                           MapBagOptions(), nullptr, &error));
  EXPECT_NE(error.find("cannot write bag"), std::string::npos) << error;
}

// --- pda_simulate ----------------------------------------------------------------------------

CommandRun runPdaSimulate(const std::string& arguments) {
  return runCommand(PDA_SIMULATE_BINARY, arguments);
}

TEST(PdaSimulateTool, WritesACaseFolderAndABagLikeTheLibrary) {
  const std::string folder = temporaryPath("case"), bag = temporaryPath("case.bag");
  const CommandRun run = runPdaSimulate("--output " + folder + " --bag " + bag +
                                        " --seed 11 --kinect-frames 3 --velodyne-revolutions 1" +
                                        " --yaw-deg -40 --translation 0.5,2,-0.2");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_TRUE(run.err.empty()) << run.err;
  EXPECT_EQ(std::count(run.out.begin(), run.out.end(), '\n'), 1);

  MapSimulationOptions options = smallOptions(11);
  options.yaw_deg = -40.0;
  options.translation = Vector3d(0.5, 2.0, -0.2);
  const SimulatedMaps maps = simulateMaps(options);
  EXPECT_EQ(jsonNumber(run.out, "dense_points"), static_cast<double>(maps.dense.size()));
  EXPECT_EQ(jsonNumber(run.out, "sparse_points"), static_cast<double>(maps.sparse.size()));
  EXPECT_EQ(jsonNumber(run.out, "sparse_messages"), 5);

  PointList target, source;
  Eigen::Isometry3d truth;
  std::string error;
  ASSERT_TRUE(loadPointCloudFile(folder + "/target.pcd", &target, &error)) << error;
  ASSERT_TRUE(loadPointCloudFile(folder + "/source.pcd", &source, &error)) << error;
  ASSERT_TRUE(readTransformFile(folder + "/T_target_source.txt", &truth, &error)) << error;
  ASSERT_EQ(target.size(), maps.dense.size());
  ASSERT_EQ(source.size(), maps.sparse.size());
  EXPECT_TRUE(target.back().isApprox(maps.dense.back(), 1e-6));  // float precision in the file
  EXPECT_TRUE(source.front().isApprox(maps.sparse.front(), 1e-6));
  EXPECT_TRUE(truth.isApprox(maps.T_target_source, 1e-12));
  // Without distortion the warp's fixed point, written beside it, is the same transform.
  Eigen::Isometry3d unwarped;
  ASSERT_TRUE(readTransformFile(folder + "/T_target_source_unwarped.txt", &unwarped, &error))
      << error;
  EXPECT_EQ(unwarped.matrix(), truth.matrix());
  EXPECT_EQ(run.out.find("warp_fit"), std::string::npos);

  // The bag's tf seed is the default 3 degree / 15 cm perturbation of the truth.
  rosbag::Bag bag_file(bag, rosbag::bagmode::Read);
  int tf_messages = 0;
  for (const rosbag::MessageInstance& message : rosbag::View(bag_file, rosbag::TopicQuery("/tf"))) {
    const auto tf = message.instantiate<tf2_msgs::TFMessage>();
    ASSERT_NE(tf, nullptr);
    const PoseError seed_error =
        poseError({Point::Zero()}, fromTransformMessage(tf->transforms.at(0).transform), truth);
    EXPECT_NEAR(seed_error.rotation_deg, 3.0, 1e-6);
    EXPECT_NEAR(seed_error.translation, 0.15, 1e-6);
    ++tf_messages;
  }
  EXPECT_EQ(tf_messages, 61);
}

TEST(PdaSimulateTool, DistortionWritesTheFittedGroundTruthAndTheFixedPoint) {
  const std::string folder = temporaryPath("warped");
  const CommandRun run = runPdaSimulate("--output " + folder +
                                        " --seed 13 --kinect-frames 3 --velodyne-revolutions 1" +
                                        " --distortion 0.01");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  MapSimulationOptions options = smallOptions(13);
  options.distortion = 0.01;
  const SimulatedMaps maps = simulateMaps(options);
  Eigen::Isometry3d truth, unwarped;
  std::string error;
  ASSERT_TRUE(readTransformFile(folder + "/T_target_source.txt", &truth, &error)) << error;
  ASSERT_TRUE(readTransformFile(folder + "/T_target_source_unwarped.txt", &unwarped, &error))
      << error;
  EXPECT_TRUE(truth.isApprox(maps.T_target_source, 1e-12));
  EXPECT_TRUE(unwarped.isApprox(maps.T_target_source_unwarped, 1e-12));
  EXPECT_FALSE(truth.isApprox(unwarped, 1e-4));
  EXPECT_EQ(jsonNumber(run.out, "overlap_points"),
            static_cast<double>(maps.warp_fit.overlap_points));
  const PoseError moved = poseError(maps.sparse, truth, unwarped);
  EXPECT_NEAR(jsonNumber(run.out, "mean_distance_m"), moved.mean_distance, 1e-6);
  EXPECT_GT(moved.mean_distance, 0.001);
}

TEST(PdaSimulateTool, BadFlagsExitWithCodeTwoAndOneLine) {
  const std::string folder = temporaryPath("unused");
  const std::vector<std::string> bad_arguments = {"--seed 3",
                                                  "--output " + folder + " --seed -1",
                                                  "--output " + folder + " --translation 1,2",
                                                  "--output " + folder + " --kinect-frames 0",
                                                  "--output " + folder + " --distortion lots",
                                                  "--output " + folder + " --colour red",
                                                  "--output /dev/null/case",
                                                  "--bag /nonexistent-directory/maps.bag",
                                                  "--bag '/nonexistent-directory/a\nb.bag'"};
  for (const std::string& arguments : bad_arguments) {
    const CommandRun run = runPdaSimulate(arguments);
    EXPECT_EQ(run.exit_code, 2) << arguments;
    EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << arguments << ": " << run.err;
    EXPECT_TRUE(run.out.empty()) << arguments;
  }
}

}  // namespace
}  // namespace simulation
}  // namespace pda_registration
