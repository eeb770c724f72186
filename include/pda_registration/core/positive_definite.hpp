#pragma once
// Small helpers on 6x6 positive (semi)definite matrices: the pose covariance's information
// matrices and covariances.

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

#include "pda_registration/core/pose_jacobian.hpp"

namespace pda_registration {

/// The inverse of a positive definite matrix; false (inverse untouched) if it is not one.
inline bool invertPositiveDefinite(const Matrix6d& matrix, Matrix6d* inverse) {
  const Eigen::LDLT<Matrix6d> factorization(matrix);
  if (factorization.info() != Eigen::Success || !factorization.isPositive() ||
      factorization.vectorD().minCoeff() <= 0.0) {
    return false;
  }
  const Matrix6d solved = factorization.solve(Matrix6d::Identity());
  if (!solved.allFinite()) return false;
  *inverse = solved;
  return true;
}

/// The largest ratio v^T a v / v^T b v over directions v (a symmetric, b positive definite): how
/// far a exceeds b in its worst direction, whatever the units of each direction. 0 if it cannot
/// be computed.
inline double largestExcess(const Matrix6d& a, const Matrix6d& b) {
  const Eigen::GeneralizedSelfAdjointEigenSolver<Matrix6d> solver(a, b);
  if (solver.info() != Eigen::Success) return 0.0;
  return solver.eigenvalues().maxCoeff();
}

}  // namespace pda_registration
