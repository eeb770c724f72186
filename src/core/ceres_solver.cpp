#include "pda_registration/core/ceres_solver.hpp"

#include <ceres/ceres.h>

#include <algorithm>
#include <cmath>

namespace pda_registration {
namespace {

// sqrt(W) * (R x + t - y_bar): one weighted point-to-point residual.
struct WeightedPointResidual {
  WeightedPointResidual(const Point& source, const Point& target, double weight)
      : source_(source), target_(target), scale_(std::sqrt(weight)) {}

  template <typename Scalar>
  bool operator()(const Scalar* quaternion, const Scalar* translation, Scalar* residual) const {
    const Eigen::Map<const Eigen::Quaternion<Scalar>> q(quaternion);
    const Eigen::Map<const Eigen::Matrix<Scalar, 3, 1>> t(translation);
    const Eigen::Matrix<Scalar, 3, 1> moved = q * source_.cast<Scalar>() + t;
    for (int i = 0; i < 3; ++i) residual[i] = Scalar(scale_) * (moved[i] - Scalar(target_[i]));
    return true;
  }

  Point source_, target_;
  double scale_;
};

}  // namespace

bool solveWithCeres(const WeightedCorrespondences& correspondences, int max_iterations,
                    int threads, Eigen::Isometry3d* T_target_source) {
  if (correspondences.size() < 3) return false;
  Eigen::Quaterniond rotation(T_target_source->rotation());
  Eigen::Vector3d translation = T_target_source->translation();

  ceres::Problem problem;
  for (size_t i = 0; i < correspondences.size(); ++i) {
    problem.AddResidualBlock(
        new ceres::AutoDiffCostFunction<WeightedPointResidual, 3, 4, 3>(new WeightedPointResidual(
            correspondences.source[i], correspondences.target_mean[i], correspondences.weight[i])),
        nullptr, rotation.coeffs().data(), translation.data());
  }
  problem.SetManifold(rotation.coeffs().data(), new ceres::EigenQuaternionManifold);

  ceres::Solver::Options options;
  options.linear_solver_type = ceres::DENSE_QR;
  options.max_num_iterations = std::max(max_iterations, 1);
  options.num_threads = std::max(threads, 1);
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
