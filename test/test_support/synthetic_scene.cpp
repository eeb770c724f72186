#include "test_support/synthetic_scene.hpp"

#include <random>

namespace pda_registration {
namespace testing_support {
namespace {

// An axis-aligned box face or a free-standing box: the room is a union of rectangles.
struct Rectangle {
  Point origin, u, v;  // corner and two edge vectors
};

std::vector<Rectangle> roomSurfaces() {
  std::vector<Rectangle> s;
  const double w = 6.0, d = 4.0, h = 2.5;
  s.push_back({{0, 0, 0}, {w, 0, 0}, {0, d, 0}});  // floor
  s.push_back({{0, 0, 0}, {w, 0, 0}, {0, 0, h}});  // walls
  s.push_back({{0, d, 0}, {w, 0, 0}, {0, 0, h}});
  s.push_back({{0, 0, 0}, {0, d, 0}, {0, 0, h}});
  s.push_back({{w, 0, 0}, {0, d, 0}, {0, 0, h}});
  // A desk-like box and a pillar break the room's symmetries.
  const auto box = [&s](Point o, double a, double b, double c) {
    s.push_back({o, {a, 0, 0}, {0, b, 0}});
    s.push_back({o + Point(0, 0, c), {a, 0, 0}, {0, b, 0}});
    s.push_back({o, {a, 0, 0}, {0, 0, c}});
    s.push_back({o + Point(0, b, 0), {a, 0, 0}, {0, 0, c}});
    s.push_back({o, {0, b, 0}, {0, 0, c}});
    s.push_back({o + Point(a, 0, 0), {0, b, 0}, {0, 0, c}});
  };
  box({1.0, 0.5, 0.0}, 1.6, 0.8, 0.75);
  box({4.2, 2.6, 0.0}, 0.4, 0.4, 2.5);
  box({2.5, 3.0, 0.0}, 0.9, 0.6, 1.2);
  return s;
}

}  // namespace

Eigen::Isometry3d syntheticGroundTruth(double scale) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = (Eigen::AngleAxisd(0.10, Eigen::Vector3d::UnitZ()) *
                Eigen::AngleAxisd(0.05, Eigen::Vector3d::UnitY()) *
                Eigen::AngleAxisd(-0.04, Eigen::Vector3d::UnitX()))
                   .toRotationMatrix();
  T.translation() = scale * Eigen::Vector3d(0.20, -0.15, 0.10);
  return T;
}

SyntheticCase makeSyntheticRoom(const SyntheticOptions& o) {
  std::mt19937_64 generator(o.seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::normal_distribution<double> noise(0.0, o.source_noise);
  const std::vector<Rectangle> surfaces = roomSurfaces();

  SyntheticCase c;
  c.T_target_source = syntheticGroundTruth(o.scale);
  for (const Rectangle& r : surfaces) {
    const int nu = std::max(1, static_cast<int>(r.u.norm() / o.target_spacing));
    const int nv = std::max(1, static_cast<int>(r.v.norm() / o.target_spacing));
    for (int i = 0; i <= nu; ++i) {
      for (int j = 0; j <= nv; ++j) {
        c.target.push_back(o.scale * (r.origin + r.u * (double(i) / nu) + r.v * (double(j) / nv)));
      }
    }
  }
  // Sample surfaces in proportion to their area.
  std::vector<double> areas;
  double total_area = 0.0;
  for (const Rectangle& r : surfaces) {
    areas.push_back(r.u.cross(r.v).norm());
    total_area += areas.back();
  }
  const Eigen::Isometry3d T_source_target = c.T_target_source.inverse();
  for (int n = 0; n < o.source_points; ++n) {
    double pick = unit(generator) * total_area;
    size_t s = 0;
    while (s + 1 < surfaces.size() && pick > areas[s]) pick -= areas[s++];
    const Rectangle& r = surfaces[s];
    const Point on_surface = r.origin + unit(generator) * r.u + unit(generator) * r.v;
    const Point noisy =
        o.scale * (on_surface + Point(noise(generator), noise(generator), noise(generator)));
    c.source.push_back(T_source_target * noisy);
  }
  const int outliers = static_cast<int>(o.outlier_fraction * o.source_points);
  for (int n = 0; n < outliers; ++n) {
    const Point in_room(unit(generator) * 6.0, unit(generator) * 4.0, unit(generator) * 2.5);
    c.source.push_back(T_source_target * (o.scale * in_room));
  }
  return c;
}

PointList makePlane(double size, double spacing) {
  PointList plane;
  for (double x = 0.0; x <= size; x += spacing) {
    for (double y = 0.0; y <= size; y += spacing) plane.emplace_back(x, y, 0.0);
  }
  return plane;
}

}  // namespace testing_support
}  // namespace pda_registration
