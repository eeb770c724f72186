#include "pda_registration/core/gauss_newton_solver.hpp"

#include <Eigen/Cholesky>

#include "pda_registration/core/pose_jacobian.hpp"

namespace pda_registration {
namespace {

Eigen::Matrix3d skew(const Eigen::Vector3d& v) {
  Eigen::Matrix3d m;
  m << 0.0, -v.z(), v.y(),  //
      v.z(), 0.0, -v.x(),   //
      -v.y(), v.x(), 0.0;
  return m;
}

// The normal equations H = sum J^T Omega J, g = sum J^T Omega e of the M-step, gathered in the
// terms the model's shape allows. With J = [I | -[r]x] (pose_jacobian.hpp, r = R x) and
// Omega = a I + b n n^T (noise_model.hpp: a = W / kappa, b = W (1 - 1 / kappa), b = 0 without a
// normal):
//   sum a J^T J     = [[A I, -[s]x], [[s]x, tr(Q) I - Q]]  with A = sum a, s = sum a r,
//                                                          Q = sum a r r^T,
//   sum b J^T n n^T J = sum b u u^T                         with u = J^T n = [n; r x n],
//   J^T Omega e     = a [e; r x e] + b (n . e) u.
// About half the arithmetic of forming J^T Omega J per point, in the loop EM runs most often.
class NormalEquations {
 public:
  void add(const Eigen::Vector3d& rotated, const Eigen::Vector3d& error,
           const Eigen::Vector3d& normal, double weight, double inverse_kappa) {
    const double a = weight * inverse_kappa;
    a_sum_ += a;
    a_r_ += a * rotated;
    const Eigen::Vector3d a_r = a * rotated;
    for (int c = 0; c < 3; ++c) {
      for (int r = 0; r <= c; ++r) a_rr_(r, c) += a_r(r) * rotated(c);
    }
    gradient_.head<3>() += a * error;
    gradient_.tail<3>() += a * rotated.cross(error);
    if (!(normal.squaredNorm() > 0.0)) return;
    const double b = weight * (1.0 - inverse_kappa);
    Vector6d u;
    u << normal, rotated.cross(normal);
    const Vector6d b_u = b * u;
    for (int c = 0; c < 6; ++c) {
      for (int r = 0; r <= c; ++r) surface_(r, c) += b_u(r) * u(c);
    }
    gradient_ += (b * normal.dot(error)) * u;
  }

  Matrix6d hessian() const {
    // Only the upper triangles of the symmetric sums are gathered (their outer products are the
    // loop's largest cost); the lower ones are their mirror.
    Matrix6d h = surface_.selfadjointView<Eigen::Upper>();
    const Eigen::Matrix3d a_rr = a_rr_.selfadjointView<Eigen::Upper>();
    h.topLeftCorner<3, 3>().diagonal().array() += a_sum_;
    const Eigen::Matrix3d s = skew(a_r_);
    h.topRightCorner<3, 3>() -= s;
    h.bottomLeftCorner<3, 3>() += s;
    h.bottomRightCorner<3, 3>() += a_rr.trace() * Eigen::Matrix3d::Identity() - a_rr;
    return h;
  }
  const Vector6d& gradient() const { return gradient_; }

 private:
  double a_sum_ = 0.0;
  Eigen::Vector3d a_r_ = Eigen::Vector3d::Zero();
  Eigen::Matrix3d a_rr_ = Eigen::Matrix3d::Zero();
  Matrix6d surface_ = Matrix6d::Zero();
  Vector6d gradient_ = Vector6d::Zero();
};

}  // namespace

bool solveGaussNewton(const WeightedCorrespondences& correspondences, int max_iterations,
                      double translation_epsilon, double rotation_epsilon,
                      Eigen::Isometry3d* T_target_source) {
  if (correspondences.size() < 3) return false;
  Eigen::Isometry3d T = *T_target_source;
  for (int iteration = 0; iteration < max_iterations; ++iteration) {
    NormalEquations equations;
    for (size_t i = 0; i < correspondences.size(); ++i) {
      const Eigen::Vector3d rotated = T.linear() * correspondences.source[i];
      const Eigen::Vector3d error = rotated + T.translation() - correspondences.target_mean[i];
      equations.add(rotated, error, correspondences.normal[i], correspondences.weight[i],
                    correspondences.inverse_kappa[i]);
    }
    const Eigen::LDLT<Matrix6d> factorization(equations.hessian());
    if (factorization.info() != Eigen::Success || !factorization.isPositive()) return false;
    const Vector6d delta = -factorization.solve(equations.gradient());
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
