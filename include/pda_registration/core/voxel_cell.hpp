#pragma once
// Integer voxel cells of a regular grid, their parents on the grid twice as coarse, and a 64-bit
// hash key: shared by the voxel filter, the surface-normal map and the covariance's block grid.

#include <cmath>
#include <cstdint>

#include "pda_registration/core/point_list.hpp"

namespace pda_registration {

struct VoxelCell {
  int64_t x = 0, y = 0, z = 0;
  bool operator==(const VoxelCell& o) const { return x == o.x && y == o.y && z == o.z; }
};

/// The cell holding p on a grid of voxels 1 / inverse_size wide (floor of p * inverse_size).
inline VoxelCell voxelCellOf(const Point& p, double inverse_size) {
  return {static_cast<int64_t>(std::floor(p.x() * inverse_size)),
          static_cast<int64_t>(std::floor(p.y() * inverse_size)),
          static_cast<int64_t>(std::floor(p.z() * inverse_size))};
}

/// The cell containing c on the grid twice as coarse (floor division by 2).
inline VoxelCell parentCell(const VoxelCell& c) {
  const auto half = [](int64_t v) { return v >= 0 ? v / 2 : -((-v + 1) / 2); };
  return {half(c.x), half(c.y), half(c.z)};
}

/// Packs three 21-bit coordinates into one key. Cells more than 2^21 apart wrap onto one key
/// (a 1 cm grid spans 20 km): a user that cannot tolerate that keeps the cell beside the key.
inline uint64_t voxelCellKey(const VoxelCell& c) {
  const auto bits = [](int64_t v) { return static_cast<uint64_t>(v) & 0x1FFFFF; };
  return (bits(c.x) << 42) | (bits(c.y) << 21) | bits(c.z);
}

}  // namespace pda_registration
