#include "pda_registration/tools/tiled_map.hpp"

#include <algorithm>
#include <limits>

namespace pda_registration {

TiledMap tileCloud(const PointList& tile, int nx, int ny, double spacing) {
  TiledMap map;
  map.spacing = spacing;
  map.points.reserve(tile.size() * static_cast<size_t>(nx) * static_cast<size_t>(ny));
  for (int i = 0; i < nx; ++i) {
    for (int j = 0; j < ny; ++j) {
      const Point offset((i - nx / 2) * spacing, (j - ny / 2) * spacing, 0.0);
      for (const Point& p : tile) map.points.push_back(p + offset);
    }
  }
  return map;
}

double separatedTileSpacing(const PointList& tile) {
  Eigen::Vector2d low = Eigen::Vector2d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector2d high = -low;
  for (const Point& p : tile) {
    if (!p.allFinite()) continue;
    low = low.cwiseMin(p.head<2>());
    high = high.cwiseMax(p.head<2>());
  }
  return tile.empty() ? 1.0 : 3.0 * std::max((high - low).maxCoeff(), 1e-3);
}

}  // namespace pda_registration
