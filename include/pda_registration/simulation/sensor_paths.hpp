#pragma once
// Where the simulated sensors stand: poses on the office's walkway loop (a rectangle
// walkway_inset inside the office walls, walked counter-clockwise). Poses are T_world_sensor
// in the sensor's body convention (x forward, y left, z up).

#include <Eigen/Geometry>
#include <vector>

#include "pda_registration/simulation/office_scene.hpp"

namespace pda_registration {
namespace simulation {

struct LoopPoint {
  Eigen::Vector2d position = Eigen::Vector2d::Zero();
  double heading = 0.0;  ///< [rad] direction of travel
};

/// The point at `fraction` (wrapped into [0, 1)) of the loop's length.
LoopPoint walkwayPoint(const OfficeScene& office, double fraction);

/// A hand-held RGB-D scan: `frames` poses spread evenly around the loop at 1.3 m, looking in
/// turn to the right (towards the walls), to the left (towards the desks) and ahead, tilted
/// down to see the floor. A part of the loop, from fraction `begin` to `end` (which may pass 1
/// and wrap), makes one fragment of a scan.
std::vector<Eigen::Isometry3d> kinectTrajectory(const OfficeScene& office, int frames,
                                                double begin = 0.0, double end = 1.0);

/// A robot with the lidar 0.8 m above the floor, stopping `poses` times around the loop, level
/// and facing along it.
std::vector<Eigen::Isometry3d> velodynePoses(const OfficeScene& office, int poses);

/// T_world_sensor from a position, yaw and pitch (positive pitch looks down), zero roll.
Eigen::Isometry3d sensorPose(const Eigen::Vector3d& position, double yaw, double pitch);

}  // namespace simulation
}  // namespace pda_registration
