#include "pda_registration/core/degeneracy.hpp"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <vector>

namespace pda_registration {

double constraintEigenvalueRatio(const PointList& target, const PointList& source,
                                 const CandidateSets& candidates,
                                 const Eigen::Isometry3d& T_target_source) {
  PointList moved, normals;
  for (size_t j = 0; j < candidates.sourceCount(); ++j) {
    const size_t count = candidates.candidateCount(j);
    if (count < 3) continue;
    Point mean = Point::Zero();
    for (size_t c = candidates.offsets[j]; c < candidates.offsets[j + 1]; ++c) {
      mean += target[candidates.target_indices[c]];
    }
    mean /= static_cast<double>(count);
    Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
    for (size_t c = candidates.offsets[j]; c < candidates.offsets[j + 1]; ++c) {
      const Point d = target[candidates.target_indices[c]] - mean;
      scatter += d * d.transpose();
    }
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen;
    eigen.computeDirect(scatter);
    // Skip patches without a clear normal (collinear candidates or a blob).
    if (!(eigen.eigenvalues()(1) > 0.0) || eigen.eigenvalues()(0) > 0.3 * eigen.eigenvalues()(1)) {
      continue;
    }
    moved.push_back(T_target_source * source[j]);
    normals.push_back(eigen.eigenvectors().col(0));
  }
  if (moved.size() < 6) return 0.0;

  Point centroid = Point::Zero();
  for (const Point& q : moved) centroid += q;
  centroid /= static_cast<double>(moved.size());
  double mean_squared_radius = 0.0;
  for (const Point& q : moved) mean_squared_radius += (q - centroid).squaredNorm();
  const double length = std::sqrt(mean_squared_radius / static_cast<double>(moved.size()));
  if (!(length > 0.0)) return 0.0;

  Eigen::Matrix<double, 6, 6> constraints = Eigen::Matrix<double, 6, 6>::Zero();
  for (size_t i = 0; i < moved.size(); ++i) {
    Eigen::Matrix<double, 6, 1> row;
    row << normals[i], (moved[i] - centroid).cross(normals[i]) / length;
    constraints.noalias() += row * row.transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 6, 6>> eigen(constraints);
  const double largest = eigen.eigenvalues()(5);
  return largest > 0.0 ? std::max(0.0, eigen.eigenvalues()(0)) / largest : 0.0;
}

}  // namespace pda_registration
