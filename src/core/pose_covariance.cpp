#include "pda_registration/core/pose_covariance.hpp"

#include <Eigen/Cholesky>

namespace pda_registration {

bool computePoseCovariance(const WeightedCorrespondences& correspondences,
                           const Eigen::Isometry3d& T_target_source, double sigma_squared,
                           Eigen::Matrix<double, 6, 6>* covariance) {
  covariance->setZero();
  if (correspondences.size() < 3 || !(sigma_squared > 0.0)) return false;
  Eigen::Matrix<double, 6, 6> hessian = Eigen::Matrix<double, 6, 6>::Zero();
  for (size_t i = 0; i < correspondences.size(); ++i) {
    // p' = exp(w) R x + t + dt  =>  dp'/d(dt) = I,  dp'/dw = -[R x]_x
    const Point rotated = T_target_source.linear() * correspondences.source[i];
    Eigen::Matrix<double, 3, 6> jacobian;
    jacobian.leftCols<3>().setIdentity();
    jacobian.rightCols<3>() << 0.0, rotated.z(), -rotated.y(),  //
        -rotated.z(), 0.0, rotated.x(),                         //
        rotated.y(), -rotated.x(), 0.0;
    hessian.noalias() += correspondences.weight[i] * jacobian.transpose() * jacobian;
  }
  const Eigen::LDLT<Eigen::Matrix<double, 6, 6>> factorization(hessian);
  if (factorization.info() != Eigen::Success || !factorization.isPositive() ||
      factorization.vectorD().minCoeff() <= 0.0) {
    return false;
  }
  *covariance = sigma_squared * factorization.solve(Eigen::Matrix<double, 6, 6>::Identity());
  *covariance = 0.5 * (*covariance + covariance->transpose()).eval();  // exact symmetry
  return covariance->allFinite();
}

}  // namespace pda_registration
