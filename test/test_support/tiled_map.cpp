#include "test_support/tiled_map.hpp"

namespace pda_registration {
namespace testing_support {

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

}  // namespace testing_support
}  // namespace pda_registration
