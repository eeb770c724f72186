#pragma once
// A procedural office: a room with cabinets along its walls, an island of desks, chairs, monitors
// and pillars in the middle, ceiling lights, and a corridor behind a partition with two doors.
// Every size and placement is drawn from the seed, so one seed always gives the same scene.
//
// The office floor is [0, length] x [0, width] at z = 0; the corridor runs along y > width.
// A band around the walkway loop (walkway_inset from the office walls, +- walkway_clearance)
// is kept free of furniture so the simulated sensors can move along it.

#include <Eigen/Geometry>
#include <cstdint>

#include "pda_registration/simulation/scene.hpp"

namespace pda_registration {
namespace simulation {

struct OfficeScene {
  Scene scene;
  Eigen::AlignedBox2d office;      ///< free floor of the office, inside its walls [m]
  Eigen::AlignedBox2d corridor;    ///< free floor of the corridor [m]
  double ceiling_height = 0.0;     ///< [m]
  double walkway_inset = 1.4;      ///< [m] distance of the sensor loop from the office walls
  double walkway_clearance = 0.6;  ///< [m] free half-width of the band around the loop
};

OfficeScene makeOfficeScene(uint64_t seed);

}  // namespace simulation
}  // namespace pda_registration
