#pragma once
// Covariance of the estimate: the inverse Hessian of the EM objective at the solution,
// sigma^2 (sum_j W_j J_j^T M_j^-1 J_j)^-1, with M_j the point's noise shape and J_j the Jacobian
// of the moved source point with respect to (dx, dy, dz, droll, dpitch, dyaw) (pose_jacobian.hpp),
// the convention of geometry_msgs/PoseWithCovariance.

#include <Eigen/Geometry>

#include "pda_registration/core/association_weights.hpp"

namespace pda_registration {

/// Returns false (and a zero matrix) when the Hessian is singular or there is nothing to use.
bool computePoseCovariance(const WeightedCorrespondences& correspondences,
                           const Eigen::Isometry3d& T_target_source, double sigma_squared,
                           Eigen::Matrix<double, 6, 6>* covariance);

/// The covariance of T^-1 given the covariance of T (same convention, expressed for the inverse
/// transform's own parent frame): the first-order propagation through inversion.
Eigen::Matrix<double, 6, 6> invertedPoseCovariance(const Eigen::Isometry3d& T,
                                                   const Eigen::Matrix<double, 6, 6>& covariance);

}  // namespace pda_registration
