#pragma once
// The per-alignment source budget: a source of more than `max_points` points is thinned to an
// unbiased subsample of `max_points` points (every finite point equally likely, input order kept,
// fixed seed), so alignment time stays bounded however large the sparse map grows while the
// objective stays the whole cloud's in expectation. (A spatially uniform subsample re-weights
// the map towards its sparse parts and cost 2.4 mm on the simulated office.)

#include <cstddef>

#include "pda_registration/core/point_list.hpp"

namespace pda_registration {

/// The subsample when `points` exceeds `max_points` (> 0); otherwise an empty list (use the
/// input as it is: no copy). Non-finite points are skipped.
PointList applySourceBudget(const PointList& points, size_t max_points);

/// The same, for a caller that has counted the finite points already (countFinitePoints): a
/// 2M-point map is not read once more to count them again.
PointList applySourceBudget(const PointList& points, size_t max_points, size_t finite_points);

}  // namespace pda_registration
