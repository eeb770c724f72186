#include "pda_registration/core/degeneracy.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

namespace pda_registration {

double constraintEigenvalueRatio(const PointList& moved, const PointList& normals) {
  Point centroid = Point::Zero();
  size_t count = 0;
  for (size_t i = 0; i < moved.size(); ++i) {
    if (normals[i].squaredNorm() == 0.0) continue;
    centroid += moved[i];
    ++count;
  }
  if (count < 6) return -1.0;
  centroid /= static_cast<double>(count);
  double mean_squared_radius = 0.0;
  for (size_t i = 0; i < moved.size(); ++i) {
    if (normals[i].squaredNorm() > 0.0) mean_squared_radius += (moved[i] - centroid).squaredNorm();
  }
  const double length = std::sqrt(mean_squared_radius / static_cast<double>(count));
  if (!(length > 0.0)) return 0.0;

  Eigen::Matrix<double, 6, 6> constraints = Eigen::Matrix<double, 6, 6>::Zero();
  for (size_t i = 0; i < moved.size(); ++i) {
    if (normals[i].squaredNorm() == 0.0) continue;
    Eigen::Matrix<double, 6, 1> row;
    row << normals[i], (moved[i] - centroid).cross(normals[i]) / length;
    constraints.noalias() += row * row.transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 6, 6>> eigen(constraints);
  const double largest = eigen.eigenvalues()(5);
  return largest > 0.0 ? std::max(0.0, eigen.eigenvalues()(0)) / largest : 0.0;
}

}  // namespace pda_registration
