#pragma once
// The residual covariance of a source point: Sigma_j = sigma^2 M_j with the unit-free shape
//   M_j = n n^T + kappa_j (I - n n^T)   when the target surface around it has a normal n,
//   M_j = kappa_j I                     otherwise.
// kappa_j >= 1 says how much less a residual along the target surface counts than one across it:
// a sparse point may have hit the surface anywhere between the dense map's samples. Where kappa_j
// comes from (a constant, or the target's local sampling spacing) is noise_shapes.hpp's concern;
// kappa_j = 1 everywhere is the paper's Sigma = sigma^2 I. All functions take 1 / kappa_j, with n
// either zero or unit length.

#include <Eigen/Core>
#include <cmath>

namespace pda_registration {

/// |r|^2_M from |r|^2 and the normal's component n . r (0 without a normal).
inline double shapedSquaredNormFromParts(double squared, double normal_component,
                                         double inverse_kappa) {
  return inverse_kappa * squared + (1.0 - inverse_kappa) * normal_component * normal_component;
}

/// r^T M^-1 r.
inline double shapedSquaredNorm(const Eigen::Vector3d& r, const Eigen::Vector3d& normal,
                                double inverse_kappa) {
  const double squared = r.squaredNorm();
  if (!(normal.squaredNorm() > 0.0)) return inverse_kappa * squared;
  return shapedSquaredNormFromParts(squared, normal.dot(r), inverse_kappa);
}

/// M^-1 as a matrix.
inline Eigen::Matrix3d shapeInverse(const Eigen::Vector3d& normal, double inverse_kappa) {
  if (!(normal.squaredNorm() > 0.0)) return inverse_kappa * Eigen::Matrix3d::Identity();
  return inverse_kappa * Eigen::Matrix3d::Identity() +
         (1.0 - inverse_kappa) * normal * normal.transpose();
}

/// M^-1/2 as a matrix (its square is shapeInverse): whitens a residual for least squares.
inline Eigen::Matrix3d shapeInverseSqrt(const Eigen::Vector3d& normal, double inverse_kappa) {
  const double s = std::sqrt(inverse_kappa);
  if (!(normal.squaredNorm() > 0.0)) return s * Eigen::Matrix3d::Identity();
  return s * Eigen::Matrix3d::Identity() + (1.0 - s) * normal * normal.transpose();
}

/// The squared residual split into its part across the surface (along n) and along it; with no
/// normal the whole residual counts as "along" (it is scaled by 1 / kappa alone).
inline void splitSquaredResidual(const Eigen::Vector3d& r, const Eigen::Vector3d& normal,
                                 double* across, double* along) {
  const double squared = r.squaredNorm();
  if (!(normal.squaredNorm() > 0.0)) {
    *across = 0.0;
    *along = squared;
    return;
  }
  const double n = normal.dot(r);
  *across = n * n;
  *along = std::max(0.0, squared - n * n);
}

}  // namespace pda_registration
