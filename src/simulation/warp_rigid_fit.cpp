#include "pda_registration/simulation/warp_rigid_fit.hpp"

#include <Eigen/Geometry>  // Eigen::umeyama
#include <algorithm>
#include <cmath>

#include "pda_registration/core/target_index.hpp"

namespace pda_registration {
namespace simulation {
namespace {

// Mean and RMS of |T y - W(y)|.
void residuals(const Eigen::Isometry3d& T, const PointList& points, const PointList& warped,
               double* mean, double* rms) {
  double sum = 0.0, sum_squares = 0.0;
  for (size_t i = 0; i < points.size(); ++i) {
    const double distance = (T * points[i] - warped[i]).norm();
    sum += distance;
    sum_squares += distance * distance;
  }
  const double count = static_cast<double>(std::max<size_t>(points.size(), 1));
  *mean = sum / count;
  *rms = std::sqrt(sum_squares / count);
}

}  // namespace

PointList pointsInOverlap(const PointList& points, const PointList& reference, double radius) {
  PointList inside;
  if (reference.empty()) return inside;
  const TargetIndex index(reference);
  size_t nearest = 0;
  double squared_distance = 0.0;
  for (const Point& p : points) {
    if (p.allFinite() && index.nearestWithinRadius(p, 1, radius, &nearest, &squared_distance) > 0)
      inside.push_back(p);
  }
  return inside;
}

WarpRigidFit fitRigidToWarp(const DriftDistortion& warp, const PointList& points) {
  WarpRigidFit fit;
  fit.overlap_points = points.size();
  PointList warped;
  warped.reserve(points.size());
  for (const Point& p : points) warped.push_back(warp.apply(p));
  if (points.size() >= 3) {
    Eigen::Matrix3Xd from(3, points.size()), to(3, points.size());
    for (size_t i = 0; i < points.size(); ++i) {
      from.col(static_cast<Eigen::Index>(i)) = points[i];
      to.col(static_cast<Eigen::Index>(i)) = warped[i];
    }
    // Eigen's closed form, independent of the registration code the ground truth measures.
    fit.T_fit.matrix() = Eigen::umeyama(from, to, false);
  }
  residuals(Eigen::Isometry3d::Identity(), points, warped, &fit.mean_residual_fixed,
            &fit.rms_residual_fixed);
  residuals(fit.T_fit, points, warped, &fit.mean_residual_fit, &fit.rms_residual_fit);
  return fit;
}

WarpRigidFit fitRigidToWarpOverOverlap(const DriftDistortion& warp,
                                       const PointList& sparse_in_scene,
                                       const PointList& undistorted_dense) {
  return fitRigidToWarp(
      warp, pointsInOverlap(sparse_in_scene, undistorted_dense, kWarpOverlapRadius));
}

}  // namespace simulation
}  // namespace pda_registration
