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
constexpr uint64_t kDenseLidarStream = 3;
constexpr uint64_t kSparseKinectStream = 4;
constexpr uint64_t kSceneChangeStream = 5;
constexpr double kOutdoorDenseLidarHeight = 1.9;   // [m] a mapping vehicle's roof
constexpr double kOutdoorSparseLidarHeight = 1.7;  // [m] a car's roof

// splitmix64's finaliser: nearby inputs give unrelated outputs.
uint64_t mix(uint64_t value) {
  value += 0x9E3779B97F4A7C15ULL;
  value = (value ^ (value >> 30)) * 0xBF58476D1CE4E5B9ULL;
  value = (value ^ (value >> 27)) * 0x94D049BB133111EBULL;
  return value ^ (value >> 31);
}

VelodyneParameters denseLidar(const MapSimulationOptions& options) {
  VelodyneParameters parameters =
      options.dense_sensor == DenseSensor::kLidar64 ? lidar64Parameters() : options.velodyne;
  parameters.noise = options.velodyne.noise;
  return parameters;
}

// The same sensor cut to its rings within +-15 degrees, as the shared factory_p64 case is made.
VelodyneParameters sameSensorSparseLidar(const MapSimulationOptions& options) {
  const VelodyneParameters dense = denseLidar(options);
  if (options.dense_sensor == DenseSensor::kLidar64) return ringSubset(dense, 16, 4, 11);
  return ringSubset(dense, 0, 2, 8);
}

// Where the sparse lidar stops (scene frame).
std::vector<Eigen::Isometry3d> sparseLidarPoses(const SimulatedMaps& maps,
                                                const MapSimulationOptions& options,
                                                const OutdoorScene& outdoor) {
  if (options.scene == SceneKind::kOffice) {
    return velodynePoses(maps.office, options.velodyne_revolutions);
  }
  std::vector<Eigen::Isometry3d> poses;
  for (int i = 0; i < options.velodyne_revolutions; ++i) {
    const Eigen::Vector2d& stop = outdoor.road_stops[i % outdoor.road_stops.size()];
    poses.push_back(sensorPose(Eigen::Vector3d(stop.x() + 2.5 * (i / outdoor.road_stops.size()),
                                               stop.y() - 1.5, kOutdoorSparseLidarHeight),
                               0.0, 0.0));
  }
  return poses;
}

// Where the dense lidar stops when it is not at the sparse scan's pose: between the sparse stops
// (office: on the walkway, shifted by half a stop; outdoor: on the other lane).
std::vector<Eigen::Isometry3d> denseLidarPoses(const SimulatedMaps& maps,
                                               const MapSimulationOptions& options,
                                               const OutdoorScene& outdoor) {
  std::vector<Eigen::Isometry3d> poses;
  for (int i = 0; i < options.dense_revolutions; ++i) {
    if (options.scene == SceneKind::kOffice) {
      const LoopPoint point = walkwayPoint(maps.office, (i + 0.8) / options.dense_revolutions);
      poses.push_back(sensorPose(Eigen::Vector3d(point.position.x(), point.position.y(), 1.2),
                                 point.heading + 0.3, 0.0));
    } else {
      const double x = -25.0 + 50.0 * (i + 0.5) / options.dense_revolutions;
      poses.push_back(
          sensorPose(Eigen::Vector3d(x, outdoor.road_stops[0].y() + 1.5, kOutdoorDenseLidarHeight),
                     0.1 * i, 0.0));
    }
  }
  return poses;
}

// The frames of a hand-held Kinect scan of `scene` at `poses`, accumulated (scene frame).
PointList kinectScan(const Scene& scene, const std::vector<Eigen::Isometry3d>& poses,
                     const MapSimulationOptions& options, uint64_t stream) {
  PointList scan;
  for (size_t i = 0; i < poses.size(); ++i) {
    const PointList frame = simulateKinectFrame(scene, poses[i], options.kinect,
                                                streamSeed(noiseSeed(options), stream, i));
    scan.insert(scan.end(), frame.begin(), frame.end());
  }
  return scan;
}

}  // namespace

std::string validateSimulationOptions(const MapSimulationOptions& options) {
  if (options.scene == SceneKind::kOutdoor && options.dense_sensor == DenseSensor::kKinect)
    return "a Kinect cannot map an outdoor scene (0.5-4.5 m range): use a lidar dense sensor";
  if (options.same_pose && options.dense_sensor == DenseSensor::kKinect)
    return "same_pose needs a lidar dense sensor (vlp16 or lidar64)";
  if (options.sparse_sensor == SparseSensor::kKinectFragment &&
      (options.scene != SceneKind::kOffice || options.dense_sensor != DenseSensor::kKinect))
    return "a Kinect fragment source needs the office scene and a Kinect dense map";
  if (options.dense_offset_set &&
      (options.same_pose || options.dense_sensor == DenseSensor::kKinect))
    return "dense_offset needs a lidar dense sensor and no same_pose";
  if (options.scan_frame &&
      (options.velodyne_revolutions != 1 || options.sparse_sensor != SparseSensor::kVlp16))
    return "scan_frame needs a single VLP-16 revolution as the sparse map";
  if (!(options.scene_change_share >= 0.0 && options.scene_change_share <= 1.0))
    return "scene_change_share must be within [0, 1]";
  if (options.dense_revolutions < 1) return "dense_revolutions must be >= 1";
  if (options.velodyne_revolutions < 1) return "velodyne_revolutions must be >= 1";
  return "";
}

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

uint64_t noiseSeed(const MapSimulationOptions& options) {
  return options.noise_seed != 0 ? options.noise_seed : options.seed;
}

uint64_t streamSeed(uint64_t seed, uint64_t stream, uint64_t index) {
  return mix(mix(mix(seed) ^ stream) ^ index);
}

SimulatedMaps simulateMaps(const MapSimulationOptions& options) {
  SimulatedMaps maps;
  OutdoorScene outdoor;
  Eigen::Vector2d distortion_centre = Eigen::Vector2d::Zero();
  if (options.scene == SceneKind::kOffice) {
    maps.office = makeOfficeScene(options.seed);
    maps.scene = maps.office.scene;
    distortion_centre = maps.office.office.center();
  } else {
    outdoor = makeOutdoorScene(options.seed);
    maps.scene = outdoor.scene;
  }
  maps.T_target_source_unwarped = transformFromYawPitchRoll(options.yaw_deg, options.pitch_deg,
                                                            options.roll_deg, options.translation);

  std::vector<Eigen::Isometry3d> lidar_poses = sparseLidarPoses(maps, options, outdoor);
  if (options.same_pose) lidar_poses.resize(1);  // one scan, re-observed by the same sensor
  if (options.scan_frame) maps.T_target_source_unwarped = lidar_poses.front();
  const VelodyneParameters sparse_lidar =
      options.same_pose ? sameSensorSparseLidar(options) : options.velodyne;

  const bool fragments = options.sparse_sensor == SparseSensor::kKinectFragment;
  PointList dense;
  if (options.dense_sensor == DenseSensor::kKinect) {
    maps.kinect_poses = fragments ? kinectTrajectory(maps.office, options.kinect_frames, 0.0,
                                                     options.fragment_length)
                                  : kinectTrajectory(maps.office, options.kinect_frames);
    dense = kinectScan(maps.scene, maps.kinect_poses, options, kKinectStream);
  } else {
    if (options.same_pose) {
      maps.dense_lidar_poses.assign(options.dense_revolutions, lidar_poses.front());
    } else if (options.dense_offset_set) {
      Eigen::Isometry3d pose = lidar_poses.front();
      pose.translation() +=
          Eigen::Vector3d(options.dense_offset.x(), options.dense_offset.y(), 0.0);
      pose.linear() =
          Eigen::AngleAxisd(options.dense_offset.z() * kDegrees, Eigen::Vector3d::UnitZ()) *
          pose.linear();
      maps.dense_lidar_poses.assign(options.dense_revolutions, pose);
    } else {
      maps.dense_lidar_poses = denseLidarPoses(maps, options, outdoor);
    }
    const VelodyneParameters dense_lidar = denseLidar(options);
    for (size_t i = 0; i < maps.dense_lidar_poses.size(); ++i) {
      const PointList revolution =
          simulateVelodyneRevolution(maps.scene, maps.dense_lidar_poses[i], dense_lidar,
                                     streamSeed(noiseSeed(options), kDenseLidarStream, i));
      dense.insert(dense.end(), revolution.begin(), revolution.end());
    }
  }
  maps.dense_raw_points = dense.size();
  maps.dense = voxelDownsample(dense, options.dense_voxel_size);

  // The lidar sees the scene (= undistorted dense frame) on its own day; its map frame is where
  // T_target_source_unwarped says.
  // What changed for it: the car park's parked cars, the office's chairs.
  const uint64_t change_seed = streamSeed(options.seed, kSceneChangeStream, 0);
  Scene sparse_scene;
  if (options.scene_change_share > 0.0) {
    sparse_scene = options.scene == SceneKind::kOutdoor
                       ? carParkAnotherDay(outdoor, options.scene_change_share, change_seed,
                                           &maps.changed_places)
                       : officeAnotherDay(maps.office, options.scene_change_share, change_seed,
                                          &maps.changed_places);
  }
  const Scene& sparse_world = options.scene_change_share > 0.0 ? sparse_scene : maps.scene;
  const Eigen::Isometry3d T_source_target = maps.T_target_source_unwarped.inverse();
  PointList sparse_in_scene;
  if (fragments) {
    lidar_poses.clear();
    const std::vector<Eigen::Isometry3d> poses =
        kinectTrajectory(maps.office, options.kinect_frames, 1.0 - options.fragment_length, 1.0);
    sparse_in_scene = voxelDownsample(kinectScan(sparse_world, poses, options, kSparseKinectStream),
                                      options.dense_voxel_size);
    for (const Point& p : sparse_in_scene) maps.sparse.push_back(T_source_target * p);
  }
  for (size_t i = 0; i < lidar_poses.size(); ++i) {
    const PointList revolution =
        simulateVelodyneRevolution(sparse_world, lidar_poses[i], sparse_lidar,
                                   streamSeed(noiseSeed(options), kVelodyneStream, i));
    sparse_in_scene.insert(sparse_in_scene.end(), revolution.begin(), revolution.end());
    for (const Point& p : revolution) maps.sparse.push_back(T_source_target * p);
    maps.velodyne_poses.push_back(T_source_target * lidar_poses[i]);
  }

  // The warped dense map's ground truth: the best rigid fit of the warp where the maps overlap
  // (warp_rigid_fit.hpp). Without distortion it is the chosen transform, bit for bit.
  const DriftDistortion distortion{distortion_centre, options.distortion};
  maps.T_target_source = maps.T_target_source_unwarped;
  if (options.distortion != 0.0) {
    maps.warp_fit = fitRigidToWarpOverOverlap(distortion, sparse_in_scene, maps.dense);
    maps.T_target_source = maps.warp_fit.T_fit * maps.T_target_source_unwarped;
  }
  applyDistortion(distortion, &maps.dense);
  return maps;
}

}  // namespace simulation
}  // namespace pda_registration
