#include "pda_registration/core/closed_form_solver.hpp"

#include <Eigen/SVD>

namespace pda_registration {

bool solveClosedForm(const WeightedCorrespondences& correspondences,
                     Eigen::Isometry3d* T_target_source) {
  if (correspondences.size() < 3) return false;
  double total_weight = 0.0;
  Point source_centroid = Point::Zero();
  Point target_centroid = Point::Zero();
  for (size_t i = 0; i < correspondences.size(); ++i) {
    total_weight += correspondences.weight[i];
    source_centroid += correspondences.weight[i] * correspondences.source[i];
    target_centroid += correspondences.weight[i] * correspondences.target_mean[i];
  }
  if (!(total_weight > 0.0)) return false;
  source_centroid /= total_weight;
  target_centroid /= total_weight;

  Eigen::Matrix3d cross_covariance = Eigen::Matrix3d::Zero();
  for (size_t i = 0; i < correspondences.size(); ++i) {
    cross_covariance += correspondences.weight[i] *
                        (correspondences.target_mean[i] - target_centroid) *
                        (correspondences.source[i] - source_centroid).transpose();
  }
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(cross_covariance,
                                              Eigen::ComputeFullU | Eigen::ComputeFullV);
  // Flip the weakest axis if needed so the result is a rotation, not a reflection.
  Eigen::Matrix3d sign = Eigen::Matrix3d::Identity();
  if ((svd.matrixU() * svd.matrixV().transpose()).determinant() < 0.0) sign(2, 2) = -1.0;
  const Eigen::Matrix3d rotation = svd.matrixU() * sign * svd.matrixV().transpose();

  Eigen::Isometry3d solution = Eigen::Isometry3d::Identity();
  solution.linear() = rotation;
  solution.translation() = target_centroid - rotation * source_centroid;
  *T_target_source = solution;
  return true;
}

}  // namespace pda_registration
