#include "pda_registration/simulation/kinect_simulator.hpp"

#include <cmath>
#include <limits>
#include <random>
#include <vector>

namespace pda_registration {
namespace simulation {
namespace {
constexpr double kDegrees = M_PI / 180.0;

// Pixel offsets from the optical axis per unit depth: (left, up) of the pixel centre.
Eigen::Vector2d pixelSlope(const KinectParameters& parameters, int column, int row) {
  const double tan_x = std::tan(0.5 * parameters.horizontal_fov_deg * kDegrees);
  const double tan_y = std::tan(0.5 * parameters.vertical_fov_deg * kDegrees);
  const double u = (column + 0.5) / parameters.width * 2.0 - 1.0;  // -1 left edge, +1 right
  const double v = (row + 0.5) / parameters.height * 2.0 - 1.0;    // -1 top edge, +1 bottom
  return Eigen::Vector2d(-u * tan_x, -v * tan_y);
}
}  // namespace

double kinectDepthNoise(const KinectParameters& parameters, double depth) {
  const double offset = depth - parameters.noise_offset;
  return parameters.noise_constant + parameters.noise_quadratic * offset * offset;
}

Eigen::Vector3d kinectPixelRay(const KinectParameters& parameters, int column, int row) {
  const Eigen::Vector2d slope = pixelSlope(parameters, column, row);
  return Eigen::Vector3d(1.0, slope.x(), slope.y()).normalized();
}

PointList simulateKinectFrame(const Scene& scene, const Eigen::Isometry3d& T_world_camera,
                              const KinectParameters& parameters, uint64_t noise_seed) {
  const int width = parameters.width, height = parameters.height;
  const Eigen::Vector3d origin = T_world_camera.translation();
  const Eigen::Matrix3d rotation = T_world_camera.linear();
  // A corner ray is the longest for a given depth; the margin lets noise pull a slightly
  // farther surface back into range.
  const double longest_ray = (parameters.max_depth + 0.1) / kinectPixelRay(parameters, 0, 0).x();
  const Scene nearby = scene.within(origin, longest_ray);

  // Noise-free depths first (in parallel), then noise in pixel order so the frame does not
  // depend on the thread count.
  std::vector<double> true_depth(static_cast<size_t>(width) * height,
                                 std::numeric_limits<double>::infinity());
#pragma omp parallel for schedule(static)
  for (int row = 0; row < height; ++row) {
    for (int column = 0; column < width; ++column) {
      const Eigen::Vector3d ray = kinectPixelRay(parameters, column, row);
      const double distance = nearby.castRay(origin, rotation * ray, longest_ray);
      true_depth[static_cast<size_t>(row) * width + column] = distance * ray.x();
    }
  }

  std::mt19937_64 generator(noise_seed);
  std::normal_distribution<double> standard_normal(0.0, 1.0);
  PointList points;
  points.reserve(true_depth.size());
  for (int row = 0; row < height; ++row) {
    for (int column = 0; column < width; ++column) {
      const double depth = true_depth[static_cast<size_t>(row) * width + column];
      if (!std::isfinite(depth)) continue;
      const double measured = parameters.noise ? depth + kinectDepthNoise(parameters, depth) *
                                                             standard_normal(generator)
                                               : depth;
      if (measured < parameters.min_depth || measured > parameters.max_depth) continue;
      const Eigen::Vector2d slope = pixelSlope(parameters, column, row);
      points.push_back(T_world_camera * (measured * Eigen::Vector3d(1.0, slope.x(), slope.y())));
    }
  }
  return points;
}

}  // namespace simulation
}  // namespace pda_registration
