#include "pda_registration/core/nearest_rotation.hpp"

#include <Eigen/LU>
#include <Eigen/SVD>

namespace pda_registration {

bool nearestRotation(const Eigen::Matrix3d& r, Eigen::Matrix3d* rotation) {
  const bool orthonormal = (r.transpose() * r - Eigen::Matrix3d::Identity()).norm() <= 1e-3;
  if (!orthonormal || !(r.determinant() > 0.0)) return false;
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(r, Eigen::ComputeFullU | Eigen::ComputeFullV);
  *rotation = svd.matrixU() * svd.matrixV().transpose();
  return true;
}

}  // namespace pda_registration
