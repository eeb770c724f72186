#include "pda_registration/core/gauss_newton_solver.hpp"

#include <Eigen/Cholesky>

#include "pda_registration/core/noise_model.hpp"
#include "pda_registration/core/pose_jacobian.hpp"

namespace pda_registration {

bool solveGaussNewton(const WeightedCorrespondences& correspondences, int max_iterations,
                      double translation_epsilon, double rotation_epsilon,
                      Eigen::Isometry3d* T_target_source) {
  if (correspondences.size() < 3) return false;
  Eigen::Isometry3d T = *T_target_source;
  for (int iteration = 0; iteration < max_iterations; ++iteration) {
    Matrix6d hessian = Matrix6d::Zero();
    Vector6d gradient = Vector6d::Zero();
    for (size_t i = 0; i < correspondences.size(); ++i) {
      const Eigen::Vector3d rotated = T.linear() * correspondences.source[i];
      const Eigen::Vector3d error = rotated + T.translation() - correspondences.target_mean[i];
      const Eigen::Matrix3d information =
          correspondences.weight[i] *
          shapeInverse(correspondences.normal[i], correspondences.inverse_kappa[i]);
      const PoseJacobian jacobian = poseJacobian(rotated);
      const Eigen::Matrix<double, 6, 3> jt_information = jacobian.transpose() * information;
      hessian.noalias() += jt_information * jacobian;
      gradient.noalias() += jt_information * error;
    }
    const Eigen::LDLT<Matrix6d> factorization(hessian);
    if (factorization.info() != Eigen::Success || !factorization.isPositive()) return false;
    const Vector6d delta = -factorization.solve(gradient);
    if (!delta.allFinite()) return false;
    T = applyIncrement(T, delta);
    if (delta.head<3>().norm() <= translation_epsilon &&
        delta.tail<3>().norm() <= rotation_epsilon) {
      break;
    }
  }
  *T_target_source = T;
  return true;
}

}  // namespace pda_registration
