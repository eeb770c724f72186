#include "pda_registration/simulation/map_simulation.hpp"

#include <cmath>

#include "pda_registration/core/point_filter.hpp"
#include "pda_registration/simulation/drift_distortion.hpp"
#include "pda_registration/simulation/sensor_paths.hpp"

namespace pda_registration {
namespace simulation {
namespace {
constexpr double kDegrees = M_PI / 180.0;
constexpr uint64_t kKinectStream = 1;
constexpr uint64_t kVelodyneStream = 2;

// splitmix64's finaliser: nearby inputs give unrelated outputs.
uint64_t mix(uint64_t value) {
  value += 0x9E3779B97F4A7C15ULL;
  value = (value ^ (value >> 30)) * 0xBF58476D1CE4E5B9ULL;
  value = (value ^ (value >> 27)) * 0x94D049BB133111EBULL;
  return value ^ (value >> 31);
}
}  // namespace

Eigen::Isometry3d transformFromYawPitchRoll(double yaw_deg, double pitch_deg, double roll_deg,
                                            const Eigen::Vector3d& translation) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = (Eigen::AngleAxisd(yaw_deg * kDegrees, Eigen::Vector3d::UnitZ()) *
                Eigen::AngleAxisd(pitch_deg * kDegrees, Eigen::Vector3d::UnitY()) *
                Eigen::AngleAxisd(roll_deg * kDegrees, Eigen::Vector3d::UnitX()))
                   .toRotationMatrix();
  T.translation() = translation;
  return T;
}

uint64_t streamSeed(uint64_t seed, uint64_t stream, uint64_t index) {
  return mix(mix(mix(seed) ^ stream) ^ index);
}

SimulatedMaps simulateMaps(const MapSimulationOptions& options) {
  SimulatedMaps maps;
  maps.office = makeOfficeScene(options.seed);
  maps.T_target_source = transformFromYawPitchRoll(options.yaw_deg, options.pitch_deg,
                                                   options.roll_deg, options.translation);

  maps.kinect_poses = kinectTrajectory(maps.office, options.kinect_frames);
  PointList dense;
  for (size_t i = 0; i < maps.kinect_poses.size(); ++i) {
    const PointList frame =
        simulateKinectFrame(maps.office.scene, maps.kinect_poses[i], options.kinect,
                            streamSeed(options.seed, kKinectStream, i));
    dense.insert(dense.end(), frame.begin(), frame.end());
  }
  maps.dense_raw_points = dense.size();
  maps.dense = voxelDownsample(dense, options.dense_voxel_size);
  applyDistortion(DriftDistortion{maps.office.office.center(), options.distortion}, &maps.dense);

  // The lidar sees the scene (= dense frame); its map frame is where T_target_source says.
  const Eigen::Isometry3d T_source_target = maps.T_target_source.inverse();
  const std::vector<Eigen::Isometry3d> lidar_poses =
      velodynePoses(maps.office, options.velodyne_revolutions);
  for (size_t i = 0; i < lidar_poses.size(); ++i) {
    const PointList revolution =
        simulateVelodyneRevolution(maps.office.scene, lidar_poses[i], options.velodyne,
                                   streamSeed(options.seed, kVelodyneStream, i));
    for (const Point& p : revolution) maps.sparse.push_back(T_source_target * p);
    maps.velodyne_poses.push_back(T_source_target * lidar_poses[i]);
  }
  return maps;
}

}  // namespace simulation
}  // namespace pda_registration
