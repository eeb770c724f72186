#pragma once
// A simulated Kinect 2 (time-of-flight RGB-D) depth camera: a 512 x 424 pinhole depth image over
// a 70.6 x 60 degree field of view, valid depth 0.5-4.5 m, back-projected to points.
//
// Noise model: each pixel's depth z (along the optical axis) gets Gaussian noise with
//   sigma(z) = 0.0012 + 0.0019 (z - 0.4)^2  [m]
// (the axial model of Nguyen, Izadi and Lovell, 3DIMPVT 2012), applied along the pixel's ray so
// the point stays on its pixel. A pixel is kept when its noisy depth lies within the range.

#include <Eigen/Geometry>
#include <cstdint>

#include "pda_registration/core/point_list.hpp"
#include "pda_registration/simulation/scene.hpp"

namespace pda_registration {
namespace simulation {

struct KinectParameters {
  int width = 512;   ///< [pixels]
  int height = 424;  ///< [pixels]
  double horizontal_fov_deg = 70.6;
  double vertical_fov_deg = 60.0;
  double min_depth = 0.5;  ///< [m]
  double max_depth = 4.5;  ///< [m]
  // sigma(z) = noise_constant + noise_quadratic * (z - noise_offset)^2
  double noise_constant = 0.0012;   ///< [m]
  double noise_quadratic = 0.0019;  ///< [1/m]
  double noise_offset = 0.4;        ///< [m]
  bool noise = true;                ///< false: exact depths (for tests and ground-truth clouds)
};

/// Standard deviation of the depth noise at depth z [m].
double kinectDepthNoise(const KinectParameters& parameters, double depth);

/// Unit ray of pixel (column, row) in the camera's body frame (x forward = optical axis,
/// y left, z up); column 0 is the left of the image, row 0 the top.
Eigen::Vector3d kinectPixelRay(const KinectParameters& parameters, int column, int row);

/// One depth frame from the camera at T_world_camera (body convention, see sensor_paths.hpp),
/// as points in the world frame, row by row. The same noise_seed gives the same frame.
PointList simulateKinectFrame(const Scene& scene, const Eigen::Isometry3d& T_world_camera,
                              const KinectParameters& parameters, uint64_t noise_seed);

}  // namespace simulation
}  // namespace pda_registration
