#pragma once
// Detects geometry that cannot pin down all six degrees of freedom (a single plane, a corridor,
// a line). Point-to-point objectives hide this (their Hessian is always full rank), so the test
// uses the source points' target surface normals (em_run.hpp): the point-to-plane constraint
// matrix sum_j a_j a_j^T, a_j = [n_j; (q_j - c) x n_j / L], with q_j the moved source points, c
// their centroid and L their RMS radius (so rotations and translations compare in length units).
// Its smallest/largest eigenvalue ratio is ~0 along unconstrained directions.

#include "pda_registration/core/point_list.hpp"

namespace pda_registration {

/// `moved` and `normals` are parallel; zero normals are skipped. Returns the ratio in [0, 1], or
/// -1 when fewer than 6 normals are known (degeneracy cannot be judged).
double constraintEigenvalueRatio(const PointList& moved, const PointList& normals);

}  // namespace pda_registration
