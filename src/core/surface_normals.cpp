#include "pda_registration/core/surface_normals.hpp"

#include <Eigen/Eigenvalues>
#include <cmath>

namespace pda_registration {
namespace {

struct Cell {
  int64_t x, y, z;
};

Cell cellOf(const Point& p, double inverse_size) {
  return {static_cast<int64_t>(std::floor(p.x() * inverse_size)),
          static_cast<int64_t>(std::floor(p.y() * inverse_size)),
          static_cast<int64_t>(std::floor(p.z() * inverse_size))};
}

// 21 bits per axis; far-apart cells that wrap onto one key only blur a normal.
uint64_t keyOf(const Cell& c) {
  const auto bits = [](int64_t v) { return static_cast<uint64_t>(v) & 0x1FFFFF; };
  return (bits(c.x) << 42) | (bits(c.y) << 21) | bits(c.z);
}

int64_t floorHalf(int64_t v) { return v >= 0 ? v / 2 : -((-v + 1) / 2); }

// First and second moments of a voxel's points, relative to the voxel's own corner so that
// large coordinates do not cancel catastrophically in the covariance.
struct Moments {
  Cell cell{0, 0, 0};
  double count = 0.0;
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  Eigen::Matrix3d outer = Eigen::Matrix3d::Zero();

  // Adds moments taken relative to a corner that lies `shift` from this voxel's corner.
  void add(const Moments& other, const Eigen::Vector3d& shift) {
    count += other.count;
    sum += other.sum + other.count * shift;
    outer += other.outer + other.sum * shift.transpose() + shift * other.sum.transpose() +
             other.count * shift * shift.transpose();
  }
};

using MomentGrid = std::unordered_map<uint64_t, Moments>;

// Planar voxels only: a clear smallest axis and two comparable in-plane axes (a single scan
// line has one dominant axis and is rejected).
bool planarNormal(const Moments& m, Eigen::Vector3f* normal) {
  if (m.count < 5.0) return false;
  const Eigen::Vector3d mean = m.sum / m.count;
  const Eigen::Matrix3d covariance = m.outer / m.count - mean * mean.transpose();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen;
  eigen.computeDirect(covariance);
  const Eigen::Vector3d& e = eigen.eigenvalues();  // ascending
  if (!(e(2) > 0.0) || e(0) > 0.1 * e(1) || e(1) < 0.01 * e(2)) return false;
  *normal = eigen.eigenvectors().col(0).normalized().cast<float>();
  return true;
}

}  // namespace

SurfaceNormalMap::SurfaceNormalMap(const PointList& points, double finest_voxel_size) {
  if (!(finest_voxel_size > 0.0) || !std::isfinite(finest_voxel_size)) return;
  // Finest level from the points; each coarser level (twice the size) by merging 8 children.
  MomentGrid grid;
  const double inverse_size = 1.0 / finest_voxel_size;
  for (const Point& p : points) {
    const Cell c = cellOf(p, inverse_size);
    Moments& m = grid[keyOf(c)];
    if (m.count == 0.0) m.cell = c;
    const Eigen::Vector3d local = p - Eigen::Vector3d(c.x, c.y, c.z) * finest_voxel_size;
    m.count += 1.0;
    m.sum += local;
    m.outer += local * local.transpose();
  }
  double size = finest_voxel_size;
  for (int level = 0; level < kLevels; ++level) {
    Level out;
    out.voxel_size = size;
    out.normals.reserve(grid.size());
    for (const auto& entry : grid) {
      Eigen::Vector3f normal;
      if (planarNormal(entry.second, &normal)) out.normals.emplace(entry.first, normal);
    }
    levels_.push_back(std::move(out));
    if (level + 1 == kLevels) break;

    MomentGrid parents;
    const double parent_size = 2.0 * size;
    for (const auto& entry : grid) {
      const Cell& c = entry.second.cell;
      const Cell parent{floorHalf(c.x), floorHalf(c.y), floorHalf(c.z)};
      Moments& m = parents[keyOf(parent)];
      if (m.count == 0.0) m.cell = parent;
      const Eigen::Vector3d shift = Eigen::Vector3d(c.x, c.y, c.z) * size -
                                    Eigen::Vector3d(parent.x, parent.y, parent.z) * parent_size;
      m.add(entry.second, shift);
    }
    grid.swap(parents);
    size = parent_size;
  }
}

size_t SurfaceNormalMap::voxelsWithNormal() const {
  size_t count = 0;
  for (const Level& level : levels_) count += level.normals.size();
  return count;
}

Eigen::Vector3d SurfaceNormalMap::normalAt(const Point& p) const {
  for (const Level& level : levels_) {
    const auto it = level.normals.find(keyOf(cellOf(p, 1.0 / level.voxel_size)));
    if (it != level.normals.end()) return it->second.cast<double>();
  }
  return Eigen::Vector3d::Zero();
}

}  // namespace pda_registration
