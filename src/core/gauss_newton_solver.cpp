#include "pda_registration/core/gauss_newton_solver.hpp"

#include <algorithm>
#include <vector>

#include <Eigen/Cholesky>

#include "pda_registration/core/noise_model.hpp"
#include "pda_registration/core/pose_jacobian.hpp"

namespace pda_registration {

bool solveGaussNewton(const WeightedCorrespondences& correspondences, int max_iterations,
                      double translation_epsilon, double rotation_epsilon, int threads,
                      Eigen::Isometry3d* T_target_source, GaussNewtonBuffers* buffers) {
  if (correspondences.size() < 3) return false;
  const long long n = static_cast<long long>(correspondences.size());
  // Each correspondence's terms are computed in parallel into its own slot and summed serially
  // in order: the same sums, bit for bit, for any thread count.
  GaussNewtonBuffers own_buffers;
  if (!buffers) buffers = &own_buffers;
  auto& hessian_terms = buffers->hessian_terms;
  auto& gradient_terms = buffers->gradient_terms;
  hessian_terms.resize(n);
  gradient_terms.resize(n);
  Eigen::Isometry3d T = *T_target_source;
  for (int iteration = 0; iteration < max_iterations; ++iteration) {
#pragma omp parallel for schedule(static) num_threads(std::max(threads, 1))
    for (long long i = 0; i < n; ++i) {
      const Eigen::Vector3d rotated = T.linear() * correspondences.source[i];
      const Eigen::Vector3d error = rotated + T.translation() - correspondences.target_mean[i];
      const Eigen::Matrix3d information =
          correspondences.weight[i] *
          shapeInverse(correspondences.normal[i], correspondences.inverse_kappa[i]);
      const PoseJacobian jacobian = poseJacobian(rotated);
      const Eigen::Matrix<double, 6, 3> jt_information = jacobian.transpose() * information;
      hessian_terms[i].noalias() = jt_information * jacobian;
      gradient_terms[i].noalias() = jt_information * error;
    }
    Matrix6d hessian = Matrix6d::Zero();
    Vector6d gradient = Vector6d::Zero();
    for (long long i = 0; i < n; ++i) {
      hessian += hessian_terms[i];
      gradient += gradient_terms[i];
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
