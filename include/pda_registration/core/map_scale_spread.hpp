#pragma once
// The pose covariance's map-scale terms (pose_covariance.hpp): what the overlap's parts, taken as
// wholes, disagree on. The correlogram sees the scores of one neighbourhood at a time, and at the
// optimum the parts' pulls cancel in total; these see the parts against each other (a warp over
// the whole map, a dense map that covers only part of the scan). Everything here is linearised
// at the optimum with rotations about the overlap's centre, from per-octant sums.

#include <Eigen/Geometry>
#include <array>
#include <cstddef>
#include <vector>

#include "pda_registration/core/point_list.hpp"
#include "pda_registration/core/pose_jacobian.hpp"

namespace pda_registration {

/// What one octant of the overlap contributes to the Hessian and the gradient.
struct OctantSums {
  Matrix6d hessian = Matrix6d::Zero();
  Vector6d score = Vector6d::Zero();
  size_t points = 0;
};
using OctantPartition = std::array<OctantSums, 8>;

/// The octant of p about `centre`: bit 0 set above it in x, bit 1 in y, bit 2 in z.
int octantOf(const Point& p, const Eigen::Vector3d& centre);

/// A delete-one-octant jackknife of the estimate (for unequal groups). False, and `spread`
/// untouched, with fewer than two octants that hold 2 % of the points.
bool octantJackknife(const OctantPartition& octants, const Matrix6d& hessian, size_t total_points,
                     Matrix6d* spread);

/// The overlap cut in two halves along each of its long axes (those along which it extends at
/// least half as far as along its longest): per cut, the covariance the whole estimate would
/// have if the two halves' disagreement were their independent errors. Cuts with a half under
/// a tenth of the points, or one the half does not constrain, are left out. `hessian_inverse`:
/// the inverse of the octants' Hessians summed (the caller has it already).
std::vector<Matrix6d> halfSplitDisagreements(const OctantPartition& octants,
                                             const Matrix6d& hessian_inverse,
                                             const Eigen::Vector3d& extent);

}  // namespace pda_registration
