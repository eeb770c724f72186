#pragma once
// The scale at which the target stops looking like scan lines. A single lidar revolution samples
// the world densely along each ring and sparsely across the rings (a VLP-16 at 10 m: 4 cm along,
// 35 cm to 2 m across); a voxel that holds two rings is always "planar", whether the rings lie on
// one surface or on two (the ground and a kerb, a wall and a car). The normal map's finest voxel
// (surface_normals.hpp) is raised to this scale, so that its finest level sees surfaces, not pairs
// of rings. On maps sampled in two directions (RGB-D, stacked or multi-beam lidar scans) the scale
// is a few sample spacings and the configured voxel stays.

#include <cstddef>

#include "pda_registration/core/target_index.hpp"

namespace pda_registration {

/// For up to `samples` points spread over the index, the nearest neighbours are taken one at a
/// time (from the 8th up to the 64th) until they spread in two directions (second principal
/// variance >= 0.1 of the first: the normal map's own test); the point's scale is the distance of
/// the neighbour that did it (of the 64th when none did). Returns the median [length]; 0 for an
/// index of fewer than 8 points. The 16 nearest are asked for first, the 64 nearest only where
/// those are not two-dimensional: about 1 ms on a 3858-point target thinned to 0.25 m.
double scanLineScale(const TargetIndex& index, size_t samples = 1000);

}  // namespace pda_registration
