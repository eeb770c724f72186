#pragma once
// The two maps a user registers, simulated end to end: an office scene, a hand-held Kinect 2
// scan accumulated into a dense map (the target) and a few Velodyne VLP-16 revolutions
// accumulated into a sparse map (the source), related by a chosen rigid transform
//   p_scene = T_target_source_unwarped * p_sparse.
// The dense map frame is the scene frame (floor at z = 0); the sparse map frame is placed so
// that this holds. Without distortion the ground truth T_target_source is that transform; with
// distortion the dense map is warped non-rigidly and the ground truth is the best rigid fit of
// the warp over the overlap (warp_rigid_fit.hpp) times it. Deterministic per seed and noise seed
// (and independent of the thread count).

#include <Eigen/Geometry>
#include <cstdint>
#include <string>
#include <vector>

#include "pda_registration/core/point_list.hpp"
#include "pda_registration/simulation/kinect_simulator.hpp"
#include "pda_registration/simulation/office_scene.hpp"
#include "pda_registration/simulation/outdoor_scene.hpp"
#include "pda_registration/simulation/velodyne_simulator.hpp"
#include "pda_registration/simulation/warp_rigid_fit.hpp"

namespace pda_registration {
namespace simulation {

/// What is scanned.
enum class SceneKind {
  kOffice,   ///< office_scene.hpp: rooms, furniture, a corridor (sensors on the walkway loop)
  kOutdoor,  ///< outdoor_scene.hpp: a car park dominated by its ground (sensors on the road)
};

/// What builds the dense map (the target).
enum class DenseSensor {
  kKinect,   ///< a hand-held Kinect 2 around the walkway (office only)
  kVlp16,    ///< revolutions of a VLP-16
  kLidar64,  ///< revolutions of a 64-beam lidar (lidar64Parameters)
};

/// What builds the sparse map (the source).
enum class SparseSensor {
  kVlp16,  ///< revolutions of a VLP-16 (or, with same_pose, the dense lidar cut to +-15 deg)
  /// A second hand-held Kinect fragment (office only): the dense map is the Kinect scan of the
  /// first 60 % of the walkway loop, the source the scan of the last 60 %, both on the same voxel
  /// grid. They overlap on two fifths of the loop: the RGB-D fragment pairs of indoor mapping.
  kKinectFragment,
};

struct MapSimulationOptions {
  uint64_t seed = 1;  ///< scene layout (and sensor noise, unless noise_seed is set)
  /// Sensor noise alone: the same scene, poses and ground truth with another draw of the range
  /// and depth noise (independent draws of one case, for calibration). 0 = from `seed`.
  uint64_t noise_seed = 0;
  SceneKind scene = SceneKind::kOffice;
  DenseSensor dense_sensor = DenseSensor::kKinect;
  SparseSensor sparse_sensor = SparseSensor::kVlp16;
  /// Lidar dense sensors: revolutions accumulated into the dense map.
  int dense_revolutions = 4;
  /// Lidar dense sensors only: the dense revolutions are taken from the sparse scan's own pose,
  /// by the same sensor on the same azimuth grid, and the sparse map is one more revolution cut
  /// to the rings within +-15 degrees (every other ring of a VLP-16, 11 rings of the 64-beam).
  /// Every sparse return then lies on the dense map's sampling lattice: the case where a yaw of
  /// whole azimuth steps fits the ground almost as well as the truth.
  bool same_pose = false;
  /// Lidar dense sensors only (and not with same_pose): the dense revolutions are taken from the
  /// sparse scan's (first) pose moved by (x, y) metres and turned by z degrees about the vertical:
  /// a scan pair, e.g. two sparse scans a few metres and a few tens of degrees apart.
  bool dense_offset_set = false;
  Eigen::Vector3d dense_offset = Eigen::Vector3d::Zero();  ///< (x [m], y [m], yaw [deg])
  /// One VLP-16 revolution expressed in its sensor's own frame, as a real scan comes:
  /// T_target_source is then the sensor's pose in the dense map (yaw/pitch/roll/translation are
  /// not used), so a perturbation turns the scan about its sensor, as a seed's error would.
  bool scan_frame = false;
  /// RGB-D fragment pairs: the share of the walkway loop each fragment scans (the dense map the
  /// first, the source the last). Below 0.5 a stretch of the loop lies between them and they
  /// share only what both see across the room (0.4: about 30 % of the source's points within
  /// 5 cm of the map, against 54 % at 0.6).
  double fragment_length = 0.6;
  int kinect_frames = 24;          ///< depth frames around the walkway loop (per fragment)
  int velodyne_revolutions = 3;    ///< lidar stops around the loop, one revolution each
  double dense_voxel_size = 0.03;  ///< [m] voxel grid of the accumulated dense map; 0 keeps all
  double distortion = 0.0;         ///< DriftDistortion::amount applied to the dense map
  /// The sparse map is scanned on another day, with this share of the car park's parking places
  /// (carParkAnotherDay: cars gone, come or moved) or of the office's chairs (officeAnotherDay)
  /// drawn again; the dense map is the first day's.
  double scene_change_share = 0.0;
  // T_target_source_unwarped (the ground truth without distortion): rotation Rz(yaw) Ry(pitch)
  // Rx(roll), then the translation.
  double yaw_deg = 25.0;
  double pitch_deg = 0.0;
  double roll_deg = 0.0;
  Eigen::Vector3d translation = Eigen::Vector3d(1.5, -0.8, 0.1);  ///< [m]
  KinectParameters kinect;
  VelodyneParameters velodyne;
};

struct SimulatedMaps {
  Scene scene;         ///< what was scanned, in the dense map frame, before distortion
  OfficeScene office;  ///< the office (office scenes only)
  PointList dense;     ///< target, dense map frame
  PointList sparse;    ///< source, sparse map frame
  /// The ground truth, p_dense ~ T_target_source * p_sparse: warp_fit.T_fit *
  /// T_target_source_unwarped (exactly T_target_source_unwarped without distortion).
  Eigen::Isometry3d T_target_source = Eigen::Isometry3d::Identity();
  /// The chosen rigid transform, p_scene = T * p_sparse: the warp's fixed point.
  Eigen::Isometry3d T_target_source_unwarped = Eigen::Isometry3d::Identity();
  WarpRigidFit warp_fit;                             ///< identity, no points, without distortion
  std::vector<Eigen::Isometry3d> kinect_poses;       ///< T_dense_camera, before distortion
  std::vector<Eigen::Isometry3d> dense_lidar_poses;  ///< T_dense_lidar (lidar dense sensors)
  std::vector<Eigen::Isometry3d> velodyne_poses;     ///< T_sparse_lidar
  size_t dense_raw_points = 0;  ///< accumulated depth points before the voxel grid
  size_t changed_places = 0;    ///< parking places or chairs drawn again for the sparse map's day
};

/// Empty when the options can be simulated, otherwise why not (e.g. a Kinect outdoors).
std::string validateSimulationOptions(const MapSimulationOptions& options);

/// Rz(yaw) Ry(pitch) Rx(roll) with the translation.
Eigen::Isometry3d transformFromYawPitchRoll(double yaw_deg, double pitch_deg, double roll_deg,
                                            const Eigen::Vector3d& translation);

/// A well-mixed seed for one noise stream (sensor, frame) derived from the simulation seed.
uint64_t streamSeed(uint64_t seed, uint64_t stream, uint64_t index);

/// The seed the sensor noise streams derive from: noise_seed, or the layout seed when it is 0
/// (so a simulation without a noise seed is what it always was).
uint64_t noiseSeed(const MapSimulationOptions& options);

SimulatedMaps simulateMaps(const MapSimulationOptions& options);

}  // namespace simulation
}  // namespace pda_registration
