#include "pda_registration/core/ceres_solver.hpp"

#include <ceres/ceres.h>

#include <algorithm>
#include <cmath>

#include "pda_registration/core/noise_model.hpp"

namespace pda_registration {
namespace {

// sqrt(W) M^-1/2 (R x + t - y_bar): one whitened, weighted residual.
struct WeightedPointResidual {
  WeightedPointResidual(const Point& source, const Point& target, double weight,
                        const Eigen::Matrix3d& whitening)
      : source_(source), target_(target), whitening_(std::sqrt(weight) * whitening) {}

  template <typename Scalar>
  bool operator()(const Scalar* quaternion, const Scalar* translation, Scalar* residual) const {
    const Eigen::Map<const Eigen::Quaternion<Scalar>> q(quaternion);
    const Eigen::Map<const Eigen::Matrix<Scalar, 3, 1>> t(translation);
    const Eigen::Matrix<Scalar, 3, 1> error =
        q * source_.cast<Scalar>() + t - target_.cast<Scalar>();
    Eigen::Map<Eigen::Matrix<Scalar, 3, 1>> whitened(residual);
    whitened = whitening_.cast<Scalar>() * error;
    return true;
  }

  Point source_, target_;
  Eigen::Matrix3d whitening_;
};

}  // namespace

bool solveWithCeres(const WeightedCorrespondences& correspondences, int max_iterations, int threads,
                    Eigen::Isometry3d* T_target_source) {
  if (correspondences.size() < 3) return false;
  Eigen::Quaterniond rotation(T_target_source->rotation());
  Eigen::Vector3d translation = T_target_source->translation();

  ceres::Problem problem;
  for (size_t i = 0; i < correspondences.size(); ++i) {
    problem.AddResidualBlock(
        new ceres::AutoDiffCostFunction<WeightedPointResidual, 3, 4, 3>(new WeightedPointResidual(
            correspondences.source[i], correspondences.target_mean[i], correspondences.weight[i],
            shapeInverseSqrt(correspondences.normal[i], correspondences.inverse_kappa[i]))),
        nullptr, rotation.coeffs().data(), translation.data());
  }
  problem.SetManifold(rotation.coeffs().data(), new ceres::EigenQuaternionManifold);

  ceres::Solver::Options options;
  options.linear_solver_type = ceres::DENSE_QR;
  options.max_num_iterations = std::max(max_iterations, 1);
  options.num_threads = std::max(threads, 1);
  // Ceres' default tolerances (1e-6 relative cost change) stop visibly short of the minimum
  // that the closed form and Gauss-Newton reach; EM needs the M-step's actual minimiser.
  options.function_tolerance = 1e-12;
  options.gradient_tolerance = 1e-12;
  options.parameter_tolerance = 1e-12;
  options.logging_type = ceres::SILENT;
  options.minimizer_progress_to_stdout = false;
  ceres::Solver::Summary summary;
  ceres::Solve(options, &problem, &summary);
  if (!summary.IsSolutionUsable()) return false;

  Eigen::Isometry3d solution = Eigen::Isometry3d::Identity();
  solution.linear() = rotation.normalized().toRotationMatrix();
  solution.translation() = translation;
  *T_target_source = solution;
  return true;
}

}  // namespace pda_registration
