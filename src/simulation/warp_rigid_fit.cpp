#include "pda_registration/simulation/warp_rigid_fit.hpp"

#include <Eigen/Geometry>  // Eigen::umeyama

#include "pda_registration/core/target_index.hpp"

namespace pda_registration {
namespace simulation {
namespace {

double meanResidual(const Eigen::Isometry3d& T, const PointList& points, const PointList& warped) {
  double sum = 0.0;
  for (size_t i = 0; i < points.size(); ++i) sum += (T * points[i] - warped[i]).norm();
  return points.empty() ? 0.0 : sum / static_cast<double>(points.size());
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
  fit.mean_residual_fixed = meanResidual(Eigen::Isometry3d::Identity(), points, warped);
  fit.mean_residual_fit = meanResidual(fit.T_fit, points, warped);
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
