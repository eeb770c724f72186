#include "pda_registration/core/surface_normals.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <atomic>
#include <cmath>

namespace pda_registration {
namespace {

// Planar voxels only: a clear smallest axis, and points that spread over the voxel in both
// in-plane directions (the second axis at least a tenth of the first in variance, ~1/3 in extent).
// A lidar scan line thickened by range noise is a thin strip: its "normal" is the normal of the
// laser's cone, across which two scans of the same sensor at the same pose agree exactly, so
// taking it for the surface lets sigma collapse onto the sensor's own geometry. It is rejected
// here and the coarser levels, where several scan lines meet, find the real surface.
bool planarNormal(double count, const Eigen::Vector3d& sum, const Eigen::Matrix3d& outer,
                  Eigen::Vector3f* normal) {
  if (count < 5.0) return false;
  const Eigen::Vector3d mean = sum / count;
  const Eigen::Matrix3d covariance = outer / count - mean * mean.transpose();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen;
  eigen.computeDirect(covariance);
  const Eigen::Vector3d& e = eigen.eigenvalues();  // ascending
  if (!(e(2) > 0.0) || e(0) > 0.1 * e(1) || e(1) < SurfaceNormalMap::kTwoDimensionalSpread * e(2))
    return false;
  *normal = eigen.eigenvectors().col(0).normalized().cast<float>();
  return true;
}

}  // namespace

SurfaceNormalMap::SurfaceNormalMap(const PointList& points, double finest_voxel_size) {
  if (!(finest_voxel_size > 0.0) || !std::isfinite(finest_voxel_size)) return;
  double size = finest_voxel_size;
  for (int level = 0; level < kLevels; ++level, size *= 2.0) {
    levels_.emplace_back();
    levels_.back().voxel_size = size;
  }
  add(points, 0);
}

void SurfaceNormalMap::add(const PointList& points, size_t from) {
  if (levels_.empty() || from >= points.size()) return;
  Level& finest = levels_[0];
  const double size = finest.voxel_size, inverse_size = 1.0 / size;
  std::vector<uint64_t> touched;
  touched.reserve(points.size() - from);
  for (size_t i = from; i < points.size(); ++i) {
    const Point& p = points[i];
    const Cell c = voxelCellOf(p, inverse_size);
    // Far-apart cells that wrap onto one key (voxel_cell.hpp) share an entry (the first one's).
    const uint64_t key = voxelCellKey(c);
    Moments& m = finest.moments[key];
    if (m.count == 0.0) m.cell = c;
    const Eigen::Vector3d local = p - Eigen::Vector3d(c.x, c.y, c.z) * size;
    m.count += 1.0;
    m.sum += local;
    m.outer += local * local.transpose();
    if (touched.empty() || touched.back() != key) touched.push_back(key);
  }
  std::sort(touched.begin(), touched.end());
  touched.erase(std::unique(touched.begin(), touched.end()), touched.end());
  refit(0, std::move(touched));
  rebuildLookup();
}

namespace {
// Fibonacci hashing: the top bits of key * 2^64 / golden ratio.
size_t slotOf(uint64_t key, int shift) {
  return static_cast<size_t>((key * 0x9E3779B97F4A7C15ull) >> shift);
}
}  // namespace

void SurfaceNormalMap::rebuildLookup() {
  static std::atomic<uint64_t> next_version{1};
  version_ = next_version++;
  lookup_.resize(levels_.size());
  for (size_t l = 0; l < levels_.size(); ++l) {
    const auto& normals = levels_[l].normals;
    FlatLevel& flat = lookup_[l];
    int bits = 4;  // at most half full
    while ((size_t{1} << bits) < 2 * normals.size()) ++bits;
    flat.shift = 64 - bits;
    flat.keys.assign(size_t{1} << bits, 0);
    flat.normals.resize(size_t{1} << bits);
    const size_t mask = (size_t{1} << bits) - 1;
    for (const auto& entry : normals) {
      size_t slot = slotOf(entry.first, flat.shift);
      while (flat.keys[slot] != 0) slot = (slot + 1) & mask;
      flat.keys[slot] = entry.first + 1;
      flat.normals[slot] = entry.second;
    }
  }
}

void SurfaceNormalMap::refit(int level, std::vector<uint64_t> keys) {
  for (; level < kLevels; ++level) {
    Level& here = levels_[level];
    for (const uint64_t key : keys) {
      const Moments& m = here.moments.at(key);
      Eigen::Vector3f normal;
      if (planarNormal(m.count, m.sum, m.outer, &normal))
        here.normals[key] = normal;
      else
        here.normals.erase(key);
    }
    if (level + 1 == kLevels) break;
    // The parents of what changed: each re-merged from its eight children in a fixed order, so a
    // parent's moments do not depend on the order its children were created in.
    Level& up = levels_[level + 1];
    // Each parent once (up to eight children name it): sorted by key, stably, so that of two
    // parents whose keys wrap onto one the first named is still the first merged.
    std::vector<std::pair<uint64_t, Cell>> parents;
    parents.reserve(keys.size());
    for (const uint64_t key : keys) {
      const Cell parent = parentCell(here.moments.at(key).cell);
      parents.emplace_back(voxelCellKey(parent), parent);
    }
    std::stable_sort(parents.begin(), parents.end(),
                     [](const auto& a, const auto& b) { return a.first < b.first; });
    parents.erase(std::unique(parents.begin(), parents.end(),
                              [](const auto& a, const auto& b) {
                                return a.first == b.first && a.second == b.second;
                              }),
                  parents.end());
    std::vector<uint64_t> parent_keys;
    parent_keys.reserve(parents.size());
    for (const auto& [parent_key, parent] : parents) {
      Moments merged;
      merged.cell = parent;
      for (int child = 0; child < 8; ++child) {
        Cell c;
        c.x = 2 * parent.x + (child & 1);
        c.y = 2 * parent.y + ((child >> 1) & 1);
        c.z = 2 * parent.z + ((child >> 2) & 1);
        const auto it = here.moments.find(voxelCellKey(c));
        if (it == here.moments.end() || !(it->second.cell == c)) continue;
        const Moments& m = it->second;
        const Eigen::Vector3d shift =
            Eigen::Vector3d(c.x - 2 * parent.x, c.y - 2 * parent.y, c.z - 2 * parent.z) *
            here.voxel_size;
        merged.count += m.count;
        merged.sum += m.sum + m.count * shift;
        merged.outer += m.outer + m.sum * shift.transpose() + shift * m.sum.transpose() +
                        m.count * shift * shift.transpose();
      }
      // A wrapped key already holding another parent keeps the first one (as keys did before).
      const auto existing = up.moments.find(parent_key);
      if (existing != up.moments.end() && !(existing->second.cell == parent)) continue;
      up.moments[parent_key] = merged;
      parent_keys.push_back(parent_key);
    }
    std::sort(parent_keys.begin(), parent_keys.end());
    parent_keys.erase(std::unique(parent_keys.begin(), parent_keys.end()), parent_keys.end());
    keys.swap(parent_keys);
  }
}

size_t SurfaceNormalMap::voxelsWithNormal() const {
  size_t count = 0;
  for (const Level& level : levels_) count += level.normals.size();
  return count;
}

Eigen::Vector3d SurfaceNormalMap::normalAt(const Point& p, Memo* memo) const {
  if (lookup_.empty()) return Eigen::Vector3d::Zero();
  // The cell of p on each level, as voxelCellOf(p, 1 / level size) gives it: the levels' sizes
  // double exactly, so p / size halves exactly, and a cast with a correction is floor() without
  // the libm call (18 of them a lookup were a third of its time).
  const auto cellFloor = [](double v) {
    const auto i = static_cast<int64_t>(v);
    return i - (v < static_cast<double>(i) ? 1 : 0);
  };
  Point scaled = p * (1.0 / levels_[0].voxel_size);
  const Cell finest{cellFloor(scaled.x()), cellFloor(scaled.y()), cellFloor(scaled.z())};
  if (memo && memo->version == version_ && memo->cell == finest) return memo->normal;
  // The normal of p's voxel on level l, zero where it is not planar.
  const auto levelNormal = [this](size_t l, const Cell& cell) -> Eigen::Vector3d {
    const FlatLevel& flat = lookup_[l];
    const uint64_t key = voxelCellKey(cell);
    const size_t mask = flat.keys.size() - 1;
    for (size_t slot = slotOf(key, flat.shift); flat.keys[slot] != 0; slot = (slot + 1) & mask) {
      if (flat.keys[slot] == key + 1) return flat.normals[slot].cast<double>();
    }
    return Eigen::Vector3d::Zero();
  };
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
  Cell cell = finest;
  for (size_t l = 0; l < lookup_.size(); ++l) {
    if (l > 0) {
      scaled *= 0.5;
      cell = {cellFloor(scaled.x()), cellFloor(scaled.y()), cellFloor(scaled.z())};
    }
    normal = levelNormal(l, cell);
    if (normal.squaredNorm() == 0.0) continue;
    // Its parent, planar and steeply tilted from it, holds the surface (see the header).
    if (l + 1 < lookup_.size()) {
      scaled *= 0.5;
      const Cell parent{cellFloor(scaled.x()), cellFloor(scaled.y()), cellFloor(scaled.z())};
      const Eigen::Vector3d coarser = levelNormal(l + 1, parent);
      if (coarser.squaredNorm() > 0.0 && std::abs(coarser.dot(normal)) < kParentAgreement) {
        normal = coarser;
      }
    }
    break;
  }
  if (memo) *memo = {version_, finest, normal};
  return normal;
}

}  // namespace pda_registration
