#include "pda_registration/simulation/scene.hpp"

#include <algorithm>
#include <cmath>

namespace pda_registration {
namespace simulation {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();
// Hits closer than this are the surface the ray starts on, not a new one.
constexpr double kMinimumHit = 1e-9;

// The parameter interval [enter, exit] in which the ray is inside the solid; empty when enter >
// exit.
struct Interval {
  double enter = -kInfinity;
  double exit = kInfinity;
  bool empty() const { return enter > exit; }
  void clip(double low, double high) {
    enter = std::max(enter, low);
    exit = std::min(exit, high);
  }
};

// The slab along one axis: the whole line when the ray runs parallel inside it.
void clipToSlab(double origin, double direction, double low, double high, Interval* interval) {
  if (std::abs(direction) < 1e-15) {
    if (origin < low || origin > high) interval->clip(kInfinity, -kInfinity);
    return;
  }
  const double a = (low - origin) / direction;
  const double b = (high - origin) / direction;
  interval->clip(std::min(a, b), std::max(a, b));
}

Interval boxInterval(const Box& box, const Eigen::Vector3d& origin,
                     const Eigen::Vector3d& direction) {
  Interval interval;
  for (int axis = 0; axis < 3 && !interval.empty(); ++axis) {
    clipToSlab(origin[axis], direction[axis], box.min[axis], box.max[axis], &interval);
  }
  return interval;
}

Interval cylinderInterval(const VerticalCylinder& cylinder, const Eigen::Vector3d& origin,
                          const Eigen::Vector3d& direction) {
  Interval interval;
  clipToSlab(origin.z(), direction.z(), cylinder.z_min, cylinder.z_max, &interval);
  if (interval.empty()) return interval;
  const Eigen::Vector2d offset = origin.head<2>() - cylinder.centre;
  const Eigen::Vector2d planar = direction.head<2>();
  const double a = planar.squaredNorm();
  const double c = offset.squaredNorm() - cylinder.radius * cylinder.radius;
  if (a < 1e-30) {  // vertical ray: inside the disc for its whole length, or never
    if (c > 0.0) interval.clip(kInfinity, -kInfinity);
    return interval;
  }
  const double half_b = offset.dot(planar);
  const double discriminant = half_b * half_b - a * c;
  if (discriminant < 0.0) {
    interval.clip(kInfinity, -kInfinity);
    return interval;
  }
  const double root = std::sqrt(discriminant);
  interval.clip((-half_b - root) / a, (-half_b + root) / a);
  return interval;
}

// First surface crossing of a solid's interval in front of the origin.
double firstHit(const Interval& interval) {
  if (interval.empty()) return kInfinity;
  if (interval.enter > kMinimumHit) return interval.enter;
  if (interval.exit > kMinimumHit) return interval.exit;
  return kInfinity;
}

double distanceToBox(const Box& box, const Eigen::Vector3d& point) {
  const Eigen::Vector3d outside =
      (box.min - point).cwiseMax(point - box.max).cwiseMax(Eigen::Vector3d::Zero());
  return outside.norm();
}

double distanceToCylinder(const VerticalCylinder& cylinder, const Eigen::Vector3d& point) {
  const double radial = std::max(0.0, (point.head<2>() - cylinder.centre).norm() - cylinder.radius);
  const double vertical = std::max({0.0, cylinder.z_min - point.z(), point.z() - cylinder.z_max});
  return std::hypot(radial, vertical);
}

}  // namespace

void Scene::addBox(const Eigen::Vector3d& corner_a, const Eigen::Vector3d& corner_b) {
  boxes_.push_back(Box{corner_a.cwiseMin(corner_b), corner_a.cwiseMax(corner_b)});
}

void Scene::addCylinder(const Eigen::Vector2d& centre, double radius, double z_min, double z_max) {
  cylinders_.push_back(
      VerticalCylinder{centre, std::abs(radius), std::min(z_min, z_max), std::max(z_min, z_max)});
}

double Scene::castRay(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction,
                      double max_range) const {
  double nearest = kInfinity;
  for (const Box& box : boxes_) {
    nearest = std::min(nearest, firstHit(boxInterval(box, origin, direction)));
  }
  for (const VerticalCylinder& cylinder : cylinders_) {
    nearest = std::min(nearest, firstHit(cylinderInterval(cylinder, origin, direction)));
  }
  return nearest <= max_range ? nearest : kInfinity;
}

Scene Scene::within(const Eigen::Vector3d& centre, double radius) const {
  Scene nearby;
  for (const Box& box : boxes_) {
    if (distanceToBox(box, centre) <= radius) nearby.boxes_.push_back(box);
  }
  for (const VerticalCylinder& cylinder : cylinders_) {
    if (distanceToCylinder(cylinder, centre) <= radius) nearby.cylinders_.push_back(cylinder);
  }
  return nearby;
}

bool Scene::isInsideSolid(const Eigen::Vector3d& point) const {
  for (const Box& box : boxes_) {
    if (distanceToBox(box, point) == 0.0) return true;
  }
  for (const VerticalCylinder& cylinder : cylinders_) {
    if (distanceToCylinder(cylinder, point) == 0.0) return true;
  }
  return false;
}

}  // namespace simulation
}  // namespace pda_registration
