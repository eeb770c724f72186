#pragma once
// Detects geometry that cannot pin down all six degrees of freedom (a single plane, a corridor,
// a line). Point-to-point objectives hide this (their Hessian is always full rank), so the test
// uses surface normals estimated from each source point's candidate set: the point-to-plane
// constraint matrix sum_j a_j a_j^T, a_j = [n_j; (q_j - c) x n_j / L], with q_j the moved source
// points, c their centroid and L their RMS radius (so rotations and translations compare in
// length units). Its smallest/largest eigenvalue ratio is ~0 along unconstrained directions.

#include <Eigen/Geometry>

#include "pda_registration/core/candidate_sets.hpp"
#include "pda_registration/core/point_list.hpp"

namespace pda_registration {

/// Returns the min/max eigenvalue ratio in [0, 1]; 0 when fewer than 6 usable normals exist.
double constraintEigenvalueRatio(const PointList& target, const PointList& source,
                                 const CandidateSets& candidates,
                                 const Eigen::Isometry3d& T_target_source);

}  // namespace pda_registration
