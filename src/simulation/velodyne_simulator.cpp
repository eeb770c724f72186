#include "pda_registration/simulation/velodyne_simulator.hpp"

#include <cmath>
#include <limits>
#include <random>
#include <vector>

namespace pda_registration {
namespace simulation {
namespace {
constexpr double kDegrees = M_PI / 180.0;
// How far beyond max_range a surface may lie and still be pulled into range by the noise.
constexpr double kNoiseMarginSigmas = 6.0;
}  // namespace

VelodyneParameters lidar64Parameters() {
  VelodyneParameters parameters;
  parameters.rings = 64;
  parameters.lowest_elevation_deg = -25.0;
  parameters.ring_spacing_deg = 40.0 / 63.0;
  parameters.max_range = 120.0;
  parameters.range_noise = 0.02;
  return parameters;
}

VelodyneParameters ringSubset(const VelodyneParameters& parameters, int first, int stride,
                              int count) {
  VelodyneParameters subset = parameters;
  subset.rings = count;
  subset.lowest_elevation_deg =
      parameters.lowest_elevation_deg + first * parameters.ring_spacing_deg;
  subset.ring_spacing_deg = stride * parameters.ring_spacing_deg;
  return subset;
}

int velodyneColumns(const VelodyneParameters& parameters) {
  return static_cast<int>(std::lround(360.0 / parameters.azimuth_step_deg));
}

Eigen::Vector3d velodyneBeam(const VelodyneParameters& parameters, int ring, int column) {
  const double elevation =
      (parameters.lowest_elevation_deg + ring * parameters.ring_spacing_deg) * kDegrees;
  const double azimuth = column * parameters.azimuth_step_deg * kDegrees;
  return Eigen::Vector3d(std::cos(elevation) * std::cos(azimuth),
                         std::cos(elevation) * std::sin(azimuth), std::sin(elevation));
}

PointList simulateVelodyneRevolution(const Scene& scene, const Eigen::Isometry3d& T_world_sensor,
                                     const VelodyneParameters& parameters, uint64_t noise_seed) {
  const int columns = velodyneColumns(parameters);
  const int rings = parameters.rings;
  const Eigen::Vector3d origin = T_world_sensor.translation();
  const Eigen::Matrix3d rotation = T_world_sensor.linear();
  const double cast_range =
      parameters.max_range + (parameters.noise ? kNoiseMarginSigmas * parameters.range_noise : 0.0);
  const Scene nearby = scene.within(origin, cast_range);

  // Noise-free ranges in parallel, then noise in firing order (independent of thread count).
  std::vector<double> true_range(static_cast<size_t>(columns) * rings,
                                 std::numeric_limits<double>::infinity());
#pragma omp parallel for schedule(static)
  for (int column = 0; column < columns; ++column) {
    for (int ring = 0; ring < rings; ++ring) {
      true_range[static_cast<size_t>(column) * rings + ring] =
          nearby.castRay(origin, rotation * velodyneBeam(parameters, ring, column), cast_range);
    }
  }

  std::mt19937_64 generator(noise_seed);
  std::normal_distribution<double> noise(0.0, parameters.range_noise);
  PointList points;
  points.reserve(true_range.size());
  for (int column = 0; column < columns; ++column) {
    for (int ring = 0; ring < rings; ++ring) {
      const double range = true_range[static_cast<size_t>(column) * rings + ring];
      if (!std::isfinite(range)) continue;
      const double measured = parameters.noise ? range + noise(generator) : range;
      if (measured < parameters.min_range || measured > parameters.max_range) continue;
      points.push_back(T_world_sensor * (measured * velodyneBeam(parameters, ring, column)));
    }
  }
  return points;
}

}  // namespace simulation
}  // namespace pda_registration
