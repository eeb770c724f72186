#pragma once
// The residual covariance of a source point: Sigma_j = sigma^2 M_j with the unit-free shape
//   M_j = n n^T + kappa (I - n n^T)   when the target surface around it has a normal n,
//   M_j = I                           otherwise (and always when kappa = 1: the paper's model).
// kappa >= 1 is the surface anisotropy: residuals along the surface count kappa times less than
// residuals across it, because a sparse point may have hit the surface anywhere between the
// dense map's samples. All functions take 1/kappa, with n either zero or unit length.

#include <Eigen/Core>

namespace pda_registration {

/// r^T M^-1 r.
inline double shapedSquaredNorm(const Eigen::Vector3d& r, const Eigen::Vector3d& normal,
                                double inverse_kappa) {
  const double squared = r.squaredNorm();
  const double along = normal.dot(r);  // 0 when there is no normal
  return inverse_kappa * squared +
         (1.0 - inverse_kappa) * (normal.squaredNorm() > 0.0 ? along * along : squared);
}

/// M^-1 as a matrix.
inline Eigen::Matrix3d shapeInverse(const Eigen::Vector3d& normal, double inverse_kappa) {
  if (!(normal.squaredNorm() > 0.0)) return Eigen::Matrix3d::Identity();
  return inverse_kappa * Eigen::Matrix3d::Identity() +
         (1.0 - inverse_kappa) * normal * normal.transpose();
}

/// M^-1/2 as a matrix (its square is shapeInverse): whitens a residual for least squares.
inline Eigen::Matrix3d shapeInverseSqrt(const Eigen::Vector3d& normal, double inverse_kappa) {
  if (!(normal.squaredNorm() > 0.0)) return Eigen::Matrix3d::Identity();
  const double s = std::sqrt(inverse_kappa);
  return s * Eigen::Matrix3d::Identity() + (1.0 - s) * normal * normal.transpose();
}

}  // namespace pda_registration
