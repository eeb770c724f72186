#pragma once
// A static scene made of solid axis-aligned boxes and vertical cylinders, and the ray cast every
// simulated sensor uses. Units are metres, z is up (REP-103).

#include <Eigen/Core>
#include <limits>
#include <vector>

namespace pda_registration {
namespace simulation {

struct Box {
  Eigen::Vector3d min = Eigen::Vector3d::Zero();
  Eigen::Vector3d max = Eigen::Vector3d::Zero();
};

struct VerticalCylinder {
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();
  double radius = 0.0;
  double z_min = 0.0;
  double z_max = 0.0;
};

class Scene {
 public:
  /// A box between two opposite corners (in any order). Thin boxes model walls and panels.
  void addBox(const Eigen::Vector3d& corner_a, const Eigen::Vector3d& corner_b);
  void addCylinder(const Eigen::Vector2d& centre, double radius, double z_min, double z_max);

  const std::vector<Box>& boxes() const { return boxes_; }
  const std::vector<VerticalCylinder>& cylinders() const { return cylinders_; }
  size_t primitiveCount() const { return boxes_.size() + cylinders_.size(); }

  /// Distance along the unit `direction` from `origin` to the first surface, in (0, max_range];
  /// +infinity when the ray hits nothing that close. A ray starting inside a solid hits its
  /// inner face.
  double castRay(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction,
                 double max_range = std::numeric_limits<double>::infinity()) const;

  /// The primitives that come within `radius` of `centre`: casting rays no longer than `radius`
  /// from `centre` gives the same hits as in the whole scene, with fewer primitives to test.
  Scene within(const Eigen::Vector3d& centre, double radius) const;

  /// True when the point is inside (or on) a solid primitive.
  bool isInsideSolid(const Eigen::Vector3d& point) const;

 private:
  std::vector<Box> boxes_;
  std::vector<VerticalCylinder> cylinders_;
};

}  // namespace simulation
}  // namespace pda_registration
