#pragma once
// The per-alignment source budget: a source of more than `max_points` points is thinned to a
// spatially uniform subsample of at most `max_points` (one point per cell of a voxel grid sized
// to hit the budget: the first point of each cell, in input order), so alignment time stays
// bounded however large the sparse map grows. Dense regions lose points, sparse ones keep theirs.

#include <cstddef>

#include "pda_registration/core/point_list.hpp"

namespace pda_registration {

/// The subsample when `points` exceeds `max_points` (> 0); otherwise an empty list (use the
/// input as it is: no copy). Non-finite points are skipped.
PointList applySourceBudget(const PointList& points, size_t max_points);

}  // namespace pda_registration
