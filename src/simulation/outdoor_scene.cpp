#include "pda_registration/simulation/outdoor_scene.hpp"

#include <cmath>
#include <random>

namespace pda_registration {
namespace simulation {
namespace {

using Eigen::Vector2d;
using Eigen::Vector3d;

constexpr double kGroundHalfSize = 110.0;  // [m] past the lidars' useful range
constexpr double kRoadHalfWidth = 4.0;     // [m] kept free along the x axis

class Random {
 public:
  explicit Random(uint64_t seed) : generator_(seed) {}
  double uniform(double low, double high) {
    return std::uniform_real_distribution<double>(low, high)(generator_);
  }

 private:
  std::mt19937_64 generator_;
};

bool onRoad(const Vector2d& p, double margin) { return std::abs(p.y()) < kRoadHalfWidth + margin; }

constexpr double kFreeSlotShare = 0.35;  // of the car park's places, left free on a day

// A car across its row at `x`, its side's distance from the road drawn from `random`.
void parkCar(Scene* scene, double x, int side, Random* random) {
  const double y = side * (kRoadHalfWidth + 3.0 + random->uniform(0.0, 0.4));
  scene->addBox(Vector3d(x, y - 2.3, 0.0), Vector3d(x + 1.8, y + 2.3, random->uniform(1.4, 1.7)));
}

}  // namespace

OutdoorScene makeOutdoorScene(uint64_t seed) {
  OutdoorScene out;
  Random random(seed * 7919 + 17);
  Scene& scene = out.scene;
  scene.addBox(Vector3d(-kGroundHalfSize, -kGroundHalfSize, -1.0),
               Vector3d(kGroundHalfSize, kGroundHalfSize, 0.0));

  // A few buildings, one per quadrant-ish sector, 20-70 m away, never on the road.
  for (int b = 0; b < 4; ++b) {
    const double bearing = (b + random.uniform(0.15, 0.85)) * 0.5 * M_PI;
    const double distance = random.uniform(25.0, 65.0);
    const Vector2d centre(distance * std::cos(bearing), distance * std::sin(bearing));
    const Vector2d half(random.uniform(5.0, 15.0), random.uniform(4.0, 10.0));
    if (onRoad(centre, half.y() + 2.0)) continue;
    scene.addBox(Vector3d(centre.x() - half.x(), centre.y() - half.y(), 0.0),
                 Vector3d(centre.x() + half.x(), centre.y() + half.y(), random.uniform(5.0, 14.0)));
  }
  // Parked cars in two rows beside the road (a car park), with gaps.
  out.first_car_box = scene.boxes().size();
  for (int side = -1; side <= 1; side += 2) {
    for (double x = -30.0; x < 30.0; x += random.uniform(2.6, 7.0)) {
      ParkingSlot slot;
      slot.x = x;
      slot.side = side;
      slot.occupied = random.uniform(0.0, 1.0) >= kFreeSlotShare;
      out.slots.push_back(slot);
      if (slot.occupied) parkCar(&scene, x, side, &random);
    }
  }
  // Lamp poles along the road and trees scattered in the open.
  for (int pole = 0; pole < 7; ++pole) {
    const double side = pole % 2 == 0 ? 1.0 : -1.0;
    scene.addCylinder(Vector2d(-45.0 + 15.0 * pole + random.uniform(-1.0, 1.0),
                               side * (kRoadHalfWidth + 0.8)),
                      0.1, 0.0, 7.0);
  }
  for (int t = 0; t < 10; ++t) {
    const Vector2d p(random.uniform(-60.0, 60.0), random.uniform(12.0, 50.0) *
                                                     (random.uniform(0.0, 1.0) < 0.5 ? -1 : 1));
    const double crown = random.uniform(1.2, 2.5);
    scene.addCylinder(p, random.uniform(0.12, 0.25), 0.0, 3.0);
    scene.addCylinder(p, crown, 2.5, 2.5 + random.uniform(2.0, 4.0));
  }
  for (int stop = 0; stop < 5; ++stop) {
    out.road_stops.emplace_back(-20.0 + 10.0 * stop + random.uniform(-1.0, 1.0), 0.0);
  }
  return out;
}

Scene carParkAnotherDay(const OutdoorScene& outdoor, double share, uint64_t seed,
                        size_t* changed) {
  if (changed) *changed = 0;
  if (!(share > 0.0)) return outdoor.scene;
  Random random(seed * 104729 + 71);
  Scene day;
  const std::vector<Box>& boxes = outdoor.scene.boxes();
  for (size_t b = 0; b < outdoor.first_car_box && b < boxes.size(); ++b) {
    day.addBox(boxes[b].min, boxes[b].max);
  }
  for (const VerticalCylinder& c : outdoor.scene.cylinders()) {
    day.addCylinder(c.centre, c.radius, c.z_min, c.z_max);
  }
  size_t car = outdoor.first_car_box;
  for (const ParkingSlot& slot : outdoor.slots) {
    const Box* first_day = slot.occupied && car < boxes.size() ? &boxes[car++] : nullptr;
    if (random.uniform(0.0, 1.0) >= share) {
      if (first_day) day.addBox(first_day->min, first_day->max);
      continue;
    }
    if (changed) ++*changed;
    // Another car (or none), parked up to 0.4 m along the row from where the first day's stood.
    if (random.uniform(0.0, 1.0) >= kFreeSlotShare) {
      parkCar(&day, slot.x + random.uniform(-0.4, 0.4), slot.side, &random);
    }
  }
  return day;
}

}  // namespace simulation
}  // namespace pda_registration
