#pragma once
// The two maps a user registers, simulated end to end: an office scene, a hand-held Kinect 2
// scan accumulated into a dense map (the target) and a few Velodyne VLP-16 revolutions
// accumulated into a sparse map (the source), related by a chosen ground truth
//   p_dense = T_target_source * p_sparse.
// The dense map frame is the scene frame (floor at z = 0); the sparse map frame is placed so
// that T_target_source holds. Deterministic per seed (and independent of the thread count).

#include <Eigen/Geometry>
#include <cstdint>
#include <vector>

#include "pda_registration/core/point_list.hpp"
#include "pda_registration/simulation/kinect_simulator.hpp"
#include "pda_registration/simulation/office_scene.hpp"
#include "pda_registration/simulation/velodyne_simulator.hpp"

namespace pda_registration {
namespace simulation {

struct MapSimulationOptions {
  uint64_t seed = 1;               ///< scene layout and sensor noise
  int kinect_frames = 24;          ///< depth frames around the walkway loop
  int velodyne_revolutions = 3;    ///< lidar stops around the loop, one revolution each
  double dense_voxel_size = 0.03;  ///< [m] voxel grid of the accumulated dense map; 0 keeps all
  double distortion = 0.0;         ///< DriftDistortion::amount applied to the dense map
  // Ground truth T_target_source: rotation Rz(yaw) Ry(pitch) Rx(roll), then the translation.
  double yaw_deg = 25.0;
  double pitch_deg = 0.0;
  double roll_deg = 0.0;
  Eigen::Vector3d translation = Eigen::Vector3d(1.5, -0.8, 0.1);  ///< [m]
  KinectParameters kinect;
  VelodyneParameters velodyne;
};

struct SimulatedMaps {
  OfficeScene office;  ///< in the dense map frame, before distortion
  PointList dense;     ///< target, dense map frame
  PointList sparse;    ///< source, sparse map frame
  Eigen::Isometry3d T_target_source = Eigen::Isometry3d::Identity();
  std::vector<Eigen::Isometry3d> kinect_poses;    ///< T_dense_camera, before distortion
  std::vector<Eigen::Isometry3d> velodyne_poses;  ///< T_sparse_lidar
  size_t dense_raw_points = 0;  ///< accumulated depth points before the voxel grid
};

/// Rz(yaw) Ry(pitch) Rx(roll) with the translation.
Eigen::Isometry3d transformFromYawPitchRoll(double yaw_deg, double pitch_deg, double roll_deg,
                                            const Eigen::Vector3d& translation);

/// A well-mixed seed for one noise stream (sensor, frame) derived from the simulation seed.
uint64_t streamSeed(uint64_t seed, uint64_t stream, uint64_t index);

SimulatedMaps simulateMaps(const MapSimulationOptions& options);

}  // namespace simulation
}  // namespace pda_registration
