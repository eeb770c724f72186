#include "pda_registration/core/pose_covariance.hpp"

#include <Eigen/Cholesky>

#include "pda_registration/core/noise_model.hpp"
#include "pda_registration/core/pose_jacobian.hpp"

namespace pda_registration {

bool computePoseCovariance(const WeightedCorrespondences& correspondences,
                           const Eigen::Isometry3d& T_target_source, double sigma_squared,
                           Eigen::Matrix<double, 6, 6>* covariance) {
  covariance->setZero();
  if (correspondences.size() < 3 || !(sigma_squared > 0.0)) return false;
  Matrix6d hessian = Matrix6d::Zero();
  for (size_t i = 0; i < correspondences.size(); ++i) {
    const PoseJacobian jacobian =
        poseJacobian(T_target_source.linear() * correspondences.source[i]);
    hessian.noalias() += correspondences.weight[i] * jacobian.transpose() *
                         shapeInverse(correspondences.normal[i], correspondences.inverse_kappa) *
                         jacobian;
  }
  const Eigen::LDLT<Matrix6d> factorization(hessian);
  if (factorization.info() != Eigen::Success || !factorization.isPositive() ||
      factorization.vectorD().minCoeff() <= 0.0) {
    return false;
  }
  *covariance = sigma_squared * factorization.solve(Matrix6d::Identity());
  *covariance = 0.5 * (*covariance + covariance->transpose()).eval();  // exact symmetry
  return covariance->allFinite();
}

}  // namespace pda_registration
