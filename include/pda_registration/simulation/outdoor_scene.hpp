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

/// One parking place of the car park's two rows, as drawn (cars stand across the rows).
struct ParkingSlot {
  double x = 0.0;  ///< [m] where a car parked here starts along the road
  int side = 1;    ///< +1 / -1: the row on the +y / -y side of the road
  bool occupied = false;
};

struct OutdoorScene {
  Scene scene;
  /// Free positions on the road (z = 0) where the simulated vehicles stop, along +x.
  std::vector<Eigen::Vector2d> road_stops;
  /// Every parking place in the order drawn, free or taken; the taken ones are scene's boxes
  /// from first_car_box on, in this order (nothing but cars follows them among the boxes).
  std::vector<ParkingSlot> slots;
  size_t first_car_box = 0;
};

OutdoorScene makeOutdoorScene(uint64_t seed);

/// The same car park on another day: every parking place is drawn again with probability
/// `share` (a car left, another came, or one parked a little differently; taken as often as on
/// the first day), the rest of the scene unchanged. What a map made weeks earlier and today's
/// scan disagree on: surfaces only one of them saw. `changed`, when given, counts the places
/// drawn again. share 0 gives the scene itself.
Scene carParkAnotherDay(const OutdoorScene& outdoor, double share, uint64_t seed,
                        size_t* changed = nullptr);

}  // namespace simulation
}  // namespace pda_registration
