#pragma once
// The ground truth of a sparse map against a non-rigidly warped dense map. A rigid registration
// cannot follow the warp W: the best it can do is the rigid transform that best fits W where the
// two maps overlap. The warp's fixed point (the rigid transform before warping) is not that
// transform, and measuring against it blames the registration for the warp. So the simulation's
// ground truth for a warped dense map is T_fit * T_unwarped, where
//   T_fit = argmin over rigid T of  sum_y |T y - W(y)|^2
// over the sparse map's points y in the scene frame (= the undistorted dense frame) that lie in
// the overlap. W is known in simulation, so this is exact; zero warp gives T_fit = identity.
//
// The overlap: sparse points with an undistorted dense point within kWarpOverlapRadius. Those are
// on surfaces both sensors saw, and they are what a registration can associate; lidar returns
// off the dense map's coverage (ceilings, walls beyond the Kinect's 4.5 m) constrain nothing.
// 0.1 m is the dense map's 3 cm voxel diagonal (5 cm) plus a few sigma of both sensors' noise
// (VLP-16: 3 cm along the beam), and far below the gaps between surfaces in the office.

#include <Eigen/Geometry>
#include <cstddef>

#include "pda_registration/core/point_list.hpp"
#include "pda_registration/simulation/drift_distortion.hpp"

namespace pda_registration {
namespace simulation {

constexpr double kWarpOverlapRadius = 0.1;  ///< [m]

struct WarpRigidFit {
  Eigen::Isometry3d T_fit = Eigen::Isometry3d::Identity();  ///< scene -> warped dense frame
  size_t overlap_points = 0;  ///< points the fit is over
  // Residuals |T y - W(y)| over those points at the fixed point (T = identity) and at T_fit. The
  // fit minimises the RMS; the mean (eq. 22's kind of average) usually drops too, but need not:
  // over a uniform box centred on the warp it rises (3.9 -> 4.3 cm at amount 0.01).
  double rms_residual_fixed = 0.0;   ///< [m]
  double rms_residual_fit = 0.0;     ///< [m]
  double mean_residual_fixed = 0.0;  ///< [m]
  double mean_residual_fit = 0.0;    ///< [m]
};

/// The points of `points` with a point of `reference` strictly within `radius`.
PointList pointsInOverlap(const PointList& points, const PointList& reference, double radius);

/// The rigid T minimising sum |T y - W(y)|^2 over `points` (Umeyama without scale). With fewer
/// than 3 points the fit is undetermined: T_fit stays the identity (the fixed point).
WarpRigidFit fitRigidToWarp(const DriftDistortion& warp, const PointList& points);

/// fitRigidToWarp over the points of `sparse_in_scene` within kWarpOverlapRadius of
/// `undistorted_dense` (both in the scene frame).
WarpRigidFit fitRigidToWarpOverOverlap(const DriftDistortion& warp,
                                       const PointList& sparse_in_scene,
                                       const PointList& undistorted_dense);

}  // namespace simulation
}  // namespace pda_registration
