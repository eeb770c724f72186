#pragma once
// A procedural office: a room with cabinets along its walls, an island of desks, chairs, monitors
// and pillars in the middle, ceiling lights, and a corridor behind a partition with two doors.
// Every size and placement is drawn from the seed, so one seed always gives the same scene.
//
// The office floor is [0, length] x [0, width] at z = 0; the corridor runs along y > width.
// A band around the walkway loop (walkway_inset from the office walls, +- walkway_clearance)
// is kept free of furniture so the simulated sensors can move along it.

#include <Eigen/Geometry>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "pda_registration/simulation/scene.hpp"

namespace pda_registration {
namespace simulation {

/// Where a desk's chair stands, or would: the desk's middle along the island, the island's centre
/// line and the desk's side of it; and, when the scene holds a chair there, its three primitives
/// (seat and back boxes, post cylinder) by index into the scene's boxes and cylinders.
struct ChairPlace {
  double middle = 0.0, centre_y = 0.0, side = 1.0;
  int seat_box = -1, back_box = -1, post_cylinder = -1;  ///< -1: no chair on the first day
};

struct OfficeScene {
  Scene scene;
  std::vector<ChairPlace> chairs;  ///< one per desk, in the order drawn
  Eigen::AlignedBox2d office;      ///< free floor of the office, inside its walls [m]
  Eigen::AlignedBox2d corridor;    ///< free floor of the corridor [m]
  double ceiling_height = 0.0;     ///< [m]
  double walkway_inset = 1.4;      ///< [m] distance of the sensor loop from the office walls
  double walkway_clearance = 0.6;  ///< [m] free half-width of the band around the loop
};

OfficeScene makeOfficeScene(uint64_t seed);

/// The same office on another day: every desk's chair drawn again with probability `share` (gone,
/// or pushed in or pulled out and moved along the desk: up to 0.4 m aside, 0.6-1.3 m from the
/// desk's edge; there as often as on the first day), the rest of the scene unchanged. `changed`,
/// when given, counts the chairs drawn again; share 0 gives the scene itself.
Scene officeAnotherDay(const OfficeScene& office, double share, uint64_t seed,
                       size_t* changed = nullptr);

}  // namespace simulation
}  // namespace pda_registration
