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
                         shapeInverse(correspondences.normal[i], correspondences.inverse_kappa[i]) *
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

Eigen::Matrix<double, 6, 6> invertedPoseCovariance(const Eigen::Isometry3d& T,
                                                   const Eigen::Matrix<double, 6, 6>& covariance) {
  // T^-1 = (R^T, -R^T t). With R <- exp(w) R, t <- t + v on T, the inverse moves by
  // w' = -R^T w and v' = -R^T v - R^T [t]x w (first order).
  const Eigen::Matrix3d Rt = T.linear().transpose();
  const Eigen::Vector3d t = T.translation();
  Eigen::Matrix3d t_cross;
  t_cross << 0.0, -t.z(), t.y(), t.z(), 0.0, -t.x(), -t.y(), t.x(), 0.0;
  Matrix6d jacobian = Matrix6d::Zero();
  jacobian.topLeftCorner<3, 3>() = -Rt;
  jacobian.topRightCorner<3, 3>() = -Rt * t_cross;
  jacobian.bottomRightCorner<3, 3>() = -Rt;
  return jacobian * covariance * jacobian.transpose();
}

}  // namespace pda_registration
