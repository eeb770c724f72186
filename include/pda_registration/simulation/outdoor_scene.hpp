#pragma once
// A procedural outdoor scene dominated by its ground: a flat car park and road about 200 m
// across, a few buildings at 20-70 m, rows of parked cars, lamp poles and trees. It is the kind
// of scene where most lidar returns lie on the ground plane and only a few structures constrain
// the yaw: the regime in which a registration that rewards sample coincidences can lock onto a
// yaw of whole azimuth steps (see the "lattice" cases in docs/benchmark.md). One seed, one scene.
//
// The ground is z = 0; the sensors stand around the origin, on the road along the x axis.

#include <Eigen/Geometry>
#include <cstdint>
#include <vector>

#include "pda_registration/simulation/scene.hpp"

namespace pda_registration {
namespace simulation {

struct OutdoorScene {
  Scene scene;
  /// Free positions on the road (z = 0) where the simulated vehicles stop, along +x.
  std::vector<Eigen::Vector2d> road_stops;
};

OutdoorScene makeOutdoorScene(uint64_t seed);

}  // namespace simulation
}  // namespace pda_registration
