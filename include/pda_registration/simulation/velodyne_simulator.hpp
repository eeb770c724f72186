#pragma once
// A simulated Velodyne VLP-16: 16 lasers at elevations -15..+15 degrees every 2 degrees, one
// firing every 0.2 degrees of azimuth (1800 per revolution), ranges 0.4-100 m.
//
// Noise model: Gaussian range noise with standard deviation 0.03 m along each beam (the
// datasheet's +-3 cm accuracy). A beam returns when its noisy range lies within the limits.

#include <Eigen/Geometry>
#include <cstdint>

#include "pda_registration/core/point_list.hpp"
#include "pda_registration/simulation/scene.hpp"

namespace pda_registration {
namespace simulation {

struct VelodyneParameters {
  int rings = 16;
  double lowest_elevation_deg = -15.0;
  double ring_spacing_deg = 2.0;
  double azimuth_step_deg = 0.2;
  double min_range = 0.4;     ///< [m] the velodyne_pointcloud driver's default cut-off
  double max_range = 100.0;   ///< [m]
  double range_noise = 0.03;  ///< [m] standard deviation
  bool noise = true;          ///< false: exact ranges (for tests)
};

/// A 64-beam spinning lidar (Pandar64 / HDL-64 class): 64 rings evenly from -25 to +15 degrees,
/// the VLP-16's 0.2 degree azimuth grid, 2 cm range noise, 120 m.
VelodyneParameters lidar64Parameters();

/// `count` rings of `parameters` (first, first + stride, ...) on the same azimuth grid: a scan of
/// the same sensor cut to fewer rings, whose returns fall on the full sensor's sampling lattice.
VelodyneParameters ringSubset(const VelodyneParameters& parameters, int first, int stride,
                              int count);

/// Firings per revolution (360 / azimuth_step_deg, rounded).
int velodyneColumns(const VelodyneParameters& parameters);

/// Unit beam of `ring` (0 = lowest) at firing `column` in the sensor frame (x forward, y left,
/// z up); column 0 points along x, azimuth grows counter-clockwise.
Eigen::Vector3d velodyneBeam(const VelodyneParameters& parameters, int ring, int column);

/// One revolution from the sensor at T_world_sensor (no motion during the sweep), as points in
/// the world frame, firing by firing. The same noise_seed gives the same revolution.
PointList simulateVelodyneRevolution(const Scene& scene, const Eigen::Isometry3d& T_world_sensor,
                                     const VelodyneParameters& parameters, uint64_t noise_seed);

}  // namespace simulation
}  // namespace pda_registration
