#include "pda_registration/simulation/office_scene.hpp"

#include <algorithm>
#include <cmath>
#include <random>
#include <utility>
#include <vector>

namespace pda_registration {
namespace simulation {
namespace {

using Eigen::Vector2d;
using Eigen::Vector3d;

constexpr double kWallThickness = 0.2;
constexpr double kPartitionThickness = 0.15;
constexpr double kDoorWidth = 1.0;
constexpr double kDoorHeight = 2.1;
constexpr double kCabinetDepth = 0.45;

class Random {
 public:
  explicit Random(uint64_t seed) : generator_(seed) {}
  double uniform(double low, double high) {
    return std::uniform_real_distribution<double>(low, high)(generator_);
  }
  bool chance(double probability) { return uniform(0.0, 1.0) < probability; }
  template <typename T>
  const T& pick(const std::vector<T>& items) {
    return items[std::uniform_int_distribution<size_t>(0, items.size() - 1)(generator_)];
  }

 private:
  std::mt19937_64 generator_;
};

using Span = std::pair<double, double>;  // an interval along a wall [m]

bool overlapsAny(const Span& span, const std::vector<Span>& taken) {
  return std::any_of(taken.begin(), taken.end(), [&span](const Span& t) {
    return span.first < t.second && t.first < span.second;
  });
}

// A straight stretch of wall face, seen from the room: objects are placed by their distance
// along the wall and their depth away from it, so one routine furnishes every wall.
struct WallRun {
  Vector2d start;   // a corner of the face
  Vector2d along;   // unit, axis-aligned
  Vector2d inward;  // unit, axis-aligned, into the room
  double length = 0.0;

  Vector2d at(double distance, double depth) const {
    return start + distance * along + depth * inward;
  }
  void addBox(Scene* scene, const Span& span, double depth_near, double depth_far, double z_low,
              double z_high) const {
    const Vector2d a = at(span.first, depth_near), b = at(span.second, depth_far);
    scene->addBox(Vector3d(a.x(), a.y(), z_low), Vector3d(b.x(), b.y(), z_high));
  }
};

void addShell(Scene* scene, double length, double outer_y, double height) {
  const double t = kWallThickness;
  scene->addBox(Vector3d(-t, -t, -t), Vector3d(length + t, outer_y + t, 0.0));  // floor
  scene->addBox(Vector3d(-t, -t, height),
                Vector3d(length + t, outer_y + t, height + t));                         // ceiling
  scene->addBox(Vector3d(-t, -t, 0.0), Vector3d(0.0, outer_y + t, height));             // west
  scene->addBox(Vector3d(length, -t, 0.0), Vector3d(length + t, outer_y + t, height));  // east
  scene->addBox(Vector3d(0.0, -t, 0.0), Vector3d(length, 0.0, height));                 // south
  scene->addBox(Vector3d(0.0, outer_y, 0.0), Vector3d(length, outer_y + t, height));    // north
}

// The partition between office and corridor: three wall pieces and a lintel over each door.
void addPartition(Scene* scene, double length, double y, double height,
                  const std::vector<double>& door_centres) {
  double piece_start = 0.0;
  for (double centre : door_centres) {
    const double left = centre - 0.5 * kDoorWidth, right = centre + 0.5 * kDoorWidth;
    scene->addBox(Vector3d(piece_start, y, 0.0), Vector3d(left, y + kPartitionThickness, height));
    scene->addBox(Vector3d(left, y, kDoorHeight), Vector3d(right, y + kPartitionThickness, height));
    piece_start = right;
  }
  scene->addBox(Vector3d(piece_start, y, 0.0), Vector3d(length, y + kPartitionThickness, height));
}

// Shallow full-height pilasters break up long flat walls (and constrain sliding along them).
void addPilasters(Scene* scene, Random* random, const WallRun& run, double height,
                  std::vector<Span>* taken) {
  const int count = run.length > 6.0 ? 2 : 1;
  for (int i = 0; i < count; ++i) {
    const double centre = run.length * (i + 1) / (count + 1) + random->uniform(-0.8, 0.8);
    const Span span(centre - 0.2, centre + 0.2);
    if (overlapsAny(span, *taken)) continue;
    run.addBox(scene, span, 0.0, 0.25, 0.0, height);
    taken->push_back(span);
  }
}

// Cabinets and shelves of assorted widths and heights, with gaps, some with a box on top.
void addCabinets(Scene* scene, Random* random, const WallRun& run, std::vector<Span> taken) {
  const std::vector<double> heights = {0.75, 1.1, 1.1, 2.0};
  double position = random->uniform(0.1, 0.8);
  while (true) {
    const double width = random->uniform(0.8, 1.2);
    const Span span(position, position + width);
    if (span.second > run.length - 0.1) break;
    position = span.second + (random->chance(0.4) ? 0.0 : random->uniform(0.3, 1.5));
    if (overlapsAny(span, taken) || random->chance(0.2)) continue;
    const double height = random->pick(heights);
    run.addBox(scene, span, 0.0, kCabinetDepth, 0.0, height);
    if (height < 1.0 && random->chance(0.5)) {  // a box of files on a low cabinet
      const double at = random->uniform(span.first + 0.05, span.second - 0.45);
      run.addBox(scene, Span(at, at + 0.4), 0.05, 0.35, height,
                 height + random->uniform(0.2, 0.35));
    }
  }
}

// Benches, plants and a water cooler along the corridor's outer wall.
void addCorridorFurniture(Scene* scene, Random* random, const WallRun& run) {
  double position = random->uniform(0.5, 1.5);
  while (position < run.length - 1.8) {
    const int kind = static_cast<int>(random->uniform(0.0, 3.0));
    if (kind == 0) {  // bench: seat on two legs
      const Span span(position, position + 1.5);
      run.addBox(scene, span, 0.05, 0.45, 0.42, 0.47);
      run.addBox(scene, Span(span.first + 0.1, span.first + 0.15), 0.05, 0.45, 0.0, 0.42);
      run.addBox(scene, Span(span.second - 0.15, span.second - 0.1), 0.05, 0.45, 0.0, 0.42);
      position = span.second;
    } else if (kind == 1) {  // potted plant
      const Vector2d centre = run.at(position + 0.3, 0.35);
      scene->addCylinder(centre, 0.25, 0.0, random->uniform(0.8, 1.4));
      position += 0.6;
    } else {  // water cooler
      run.addBox(scene, Span(position, position + 0.35), 0.05, 0.4, 0.0, 1.1);
      position += 0.35;
    }
    position += random->uniform(1.0, 3.0);
  }
}

constexpr double kChairChance = 0.8;  // of a desk having its chair

// A chair at `cx` along the island, its seat `reach` metres from the desk's edge on `side` of the
// island's centre line `centre_y`: seat and back boxes, then the post. Returns its place.
ChairPlace addChair(Scene* scene, double middle, double centre_y, double side, double cx,
                    double reach) {
  const auto y = [centre_y, side](double depth) { return centre_y + side * depth; };
  ChairPlace place{middle, centre_y, side};
  place.seat_box = static_cast<int>(scene->boxes().size());
  scene->addBox(Vector3d(cx - 0.25, y(reach), 0.42), Vector3d(cx + 0.25, y(reach + 0.5), 0.48));
  place.back_box = static_cast<int>(scene->boxes().size());
  scene->addBox(Vector3d(cx - 0.23, y(reach + 0.45), 0.48),
                Vector3d(cx + 0.23, y(reach + 0.5), 0.95));
  place.post_cylinder = static_cast<int>(scene->cylinders().size());
  scene->addCylinder(Vector2d(cx, y(reach + 0.25)), 0.04, 0.0, 0.42);
  return place;
}

// Two back-to-back rows of desks with monitors, chairs and bins, a privacy screen between the
// rows, and a pillar at each end of the island.
void addDeskIsland(Scene* scene, Random* random, const Eigen::AlignedBox2d& island, double height,
                   std::vector<ChairPlace>* chairs) {
  const double centre_y = island.center().y();
  const double pillar_radius = random->uniform(0.2, 0.3);
  scene->addCylinder(Vector2d(island.min().x() + 0.35, centre_y), pillar_radius, 0.0, height);
  scene->addCylinder(Vector2d(island.max().x() - 0.35, centre_y), pillar_radius, 0.0, height);

  const double desk_width = random->uniform(1.2, 1.6);
  const double desk_depth = 0.7;
  const double first_x = island.min().x() + 0.8;
  const int desks_per_row = static_cast<int>((island.max().x() - 0.8 - first_x) / desk_width);
  if (desks_per_row < 1) return;
  const double last_x = first_x + desks_per_row * desk_width;
  if (random->chance(0.8)) {
    scene->addBox(Vector3d(first_x, centre_y - 0.015, 0.75),
                  Vector3d(last_x, centre_y + 0.015, random->uniform(1.1, 1.3)));
  }
  for (double side : {-1.0, 1.0}) {
    // y of a point `depth` metres from the screen on this side of the island.
    const auto y = [centre_y, side](double depth) { return centre_y + side * depth; };
    for (int i = 0; i < desks_per_row; ++i) {
      if (random->chance(0.15)) continue;  // an empty slot
      const double x = first_x + i * desk_width;
      const double middle = x + 0.5 * desk_width;
      scene->addBox(Vector3d(x, y(0.0), 0.72), Vector3d(x + desk_width, y(desk_depth), 0.75));
      scene->addBox(Vector3d(x, y(0.0), 0.0), Vector3d(x + 0.03, y(desk_depth), 0.72));
      scene->addBox(Vector3d(x + desk_width - 0.03, y(0.0), 0.0),
                    Vector3d(x + desk_width, y(desk_depth), 0.72));
      if (random->chance(0.7)) {
        const double offset = random->uniform(-0.2, 0.2);
        scene->addBox(Vector3d(middle + offset - 0.27, y(0.15), 0.78),
                      Vector3d(middle + offset + 0.27, y(0.2), 1.12));
      }
      if (random->chance(kChairChance)) {
        const double cx = middle + random->uniform(-0.15, 0.15);
        const double reach = random->uniform(0.7, 0.85);  // how far the chair is pushed in
        chairs->push_back(addChair(scene, middle, centre_y, side, cx, reach));
      } else {
        chairs->push_back(ChairPlace{middle, centre_y, side});
      }
      if (random->chance(0.4)) {
        scene->addCylinder(Vector2d(x + desk_width - 0.25, y(0.45)), 0.15, 0.0, 0.35);
      }
    }
  }
}

void addCeilingLights(Scene* scene, const Eigen::AlignedBox2d& area, double height) {
  for (double x = area.min().x() + 1.2; x + 0.6 < area.max().x(); x += 2.4) {
    for (double y = area.min().y() + 0.9; y + 0.3 < area.max().y(); y += 2.4) {
      scene->addBox(Vector3d(x - 0.6, y - 0.3, height - 0.04), Vector3d(x + 0.6, y + 0.3, height));
    }
  }
}

}  // namespace

OfficeScene makeOfficeScene(uint64_t seed) {
  Random random(seed);
  OfficeScene office;
  const double length = random.uniform(10.0, 14.0);
  const double width = random.uniform(7.0, 9.0);
  const double height = random.uniform(2.6, 3.0);
  const double corridor_width = random.uniform(1.8, 2.4);
  const double corridor_y = width + kPartitionThickness;
  office.office = Eigen::AlignedBox2d(Vector2d(0.0, 0.0), Vector2d(length, width));
  office.corridor =
      Eigen::AlignedBox2d(Vector2d(0.0, corridor_y), Vector2d(length, corridor_y + corridor_width));
  office.ceiling_height = height;
  Scene* scene = &office.scene;

  addShell(scene, length, corridor_y + corridor_width, height);
  const std::vector<double> doors = {random.uniform(1.5, 0.5 * length - 1.0),
                                     random.uniform(0.5 * length + 1.0, length - 1.5)};
  addPartition(scene, length, width, height, doors);

  // The office walls, counter-clockwise, each seen from inside the office.
  const std::vector<WallRun> office_walls = {
      {Vector2d(0.0, 0.0), Vector2d(1.0, 0.0), Vector2d(0.0, 1.0), length},         // south
      {Vector2d(length, 0.0), Vector2d(0.0, 1.0), Vector2d(-1.0, 0.0), width},      // east
      {Vector2d(length, width), Vector2d(-1.0, 0.0), Vector2d(0.0, -1.0), length},  // partition
      {Vector2d(0.0, width), Vector2d(0.0, -1.0), Vector2d(1.0, 0.0), width},       // west
  };
  for (size_t wall = 0; wall < office_walls.size(); ++wall) {
    const WallRun& run = office_walls[wall];
    // Nothing within the wall's first and last 0.5 m, so corners stay clear.
    std::vector<Span> taken = {Span(-1.0, 0.5), Span(run.length - 0.5, run.length + 1.0)};
    if (wall == 2) {  // keep the doorways clear (the partition run goes from x = length to 0)
      for (double door : doors) {
        const double along = length - door;
        taken.emplace_back(along - 0.5 * kDoorWidth - 0.3, along + 0.5 * kDoorWidth + 0.3);
      }
    } else {
      addPilasters(scene, &random, run, height, &taken);
    }
    addCabinets(scene, &random, run, taken);
  }

  const double island_inset = office.walkway_inset + office.walkway_clearance + 0.2;
  const Eigen::AlignedBox2d island(Vector2d(island_inset, island_inset),
                                   Vector2d(length - island_inset, width - island_inset));
  addDeskIsland(scene, &random, island, height, &office.chairs);

  addCorridorFurniture(scene, &random,
                       {Vector2d(0.0, corridor_y + corridor_width), Vector2d(1.0, 0.0),
                        Vector2d(0.0, -1.0), length});
  addCeilingLights(scene, office.office, height);
  addCeilingLights(scene, office.corridor, height);
  return office;
}

Scene officeAnotherDay(const OfficeScene& office, double share, uint64_t seed, size_t* changed) {
  if (changed) *changed = 0;
  if (!(share > 0.0)) return office.scene;
  std::vector<char> chair_box(office.scene.boxes().size(), 0);
  std::vector<char> chair_post(office.scene.cylinders().size(), 0);
  for (const ChairPlace& place : office.chairs) {
    if (place.seat_box < 0) continue;
    chair_box[place.seat_box] = chair_box[place.back_box] = 1;
    chair_post[place.post_cylinder] = 1;
  }
  Scene day;
  for (size_t b = 0; b < office.scene.boxes().size(); ++b) {
    if (!chair_box[b]) day.addBox(office.scene.boxes()[b].min, office.scene.boxes()[b].max);
  }
  for (size_t c = 0; c < office.scene.cylinders().size(); ++c) {
    const VerticalCylinder& post = office.scene.cylinders()[c];
    if (!chair_post[c]) day.addCylinder(post.centre, post.radius, post.z_min, post.z_max);
  }
  Random random(seed * 104723 + 29);
  for (const ChairPlace& place : office.chairs) {
    if (random.uniform(0.0, 1.0) >= share) {
      if (place.seat_box >= 0) {  // the first day's chair, where it stood
        const Box& seat = office.scene.boxes()[place.seat_box];
        const Box& back = office.scene.boxes()[place.back_box];
        const VerticalCylinder& post = office.scene.cylinders()[place.post_cylinder];
        day.addBox(seat.min, seat.max);
        day.addBox(back.min, back.max);
        day.addCylinder(post.centre, post.radius, post.z_min, post.z_max);
      }
      continue;
    }
    if (changed) ++*changed;
    if (random.chance(kChairChance)) {
      addChair(&day, place.middle, place.centre_y, place.side,
               place.middle + random.uniform(-0.4, 0.4), random.uniform(0.6, 1.3));
    }
  }
  return day;
}

}  // namespace simulation
}  // namespace pda_registration
