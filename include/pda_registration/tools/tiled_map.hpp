#pragma once
// A large map for the cropping tests and the scale measurement (pda_latency_probe --tile): copies
// of one real cloud laid out on a grid in the xy plane, the middle copy in place (so the cloud's
// ground truth holds there).

#include "pda_registration/core/point_list.hpp"

namespace pda_registration {

struct TiledMap {
  PointList points;
  double spacing = 0.0;  ///< [length] between neighbouring copies
};

/// nx x ny copies (odd counts keep one copy in place) `spacing` apart along x and y.
TiledMap tileCloud(const PointList& tile, int nx, int ny, double spacing);

/// Three times the tile's larger horizontal extent: far enough apart that a source's reach
/// around one copy (see core/target_map.hpp) holds no other copy.
double separatedTileSpacing(const PointList& tile);

}  // namespace pda_registration
