#pragma once
// Covariance of the estimate, in the convention of geometry_msgs/PoseWithCovariance: a left
// perturbation (dx, dy, dz, droll, dpitch, dyaw) of T in the target frame (pose_jacobian.hpp).
//
// It is the upper bound of two terms:
//  - model: sigma^2 times the inverse of the observed information of the EM objective (Louis
//    1982): sum_j W_j J_j^T M_j^-1 J_j (M_j the point's noise shape) less the posterior spread of
//    each point's candidates' pulls, which the unknown association and t-weight leave open. The
//    complete-data matrix alone treats every association as known: on a same-sensor lattice, whose
//    samples are as far apart as the noise, it was 3x too confident. It is right only if every
//    residual were independent noise.
//  - structure: a spatial HAC sandwich H^-1 S(L) H^-1 (heteroskedasticity and autocorrelation
//    consistent, as in spatial econometrics), S(L) = sum g_i g_j^T over the pairs of points
//    closer than about L, g_i the gradient of point i's term of the objective. Neighbouring
//    residuals share the model's errors (sampling, surface fit, non-rigid distortion), so they
//    are not independent constraints; S(L) grows with L as far as the scores stay correlated.
//    L is not a constant: the term is the level of a doubling ladder of L, from the overlap's
//    diagonal / 128 to its size, that reaches furthest, summed per grid cell (27 neighbouring
//    cells). Not the upper bound over the levels: each level estimates the same covariance with
//    its own noise, and their bound adds that noise up direction by direction.
//    H^-1 here is the model term's inverse information, as in an M-estimator's sandwich. What
//    the map's parts disagree on as wholes (a warp over the whole map, a map that covers part of
//    the scan) comes from a delete-one-octant jackknife, and the structure term is the upper
//    bound of the two.
//  - cuts: the overlap cut in two halves along each of its long axes (map_scale_spread.hpp). A
//    cut whose halves disagree beyond what every level allows (a chi-square test at 95 % against
//    the model term bounded with all the levels and the jackknife) is taken into the bound: a
//    warp or a bend of the whole map, which no neighbourhood of the correlogram reaches and an
//    eighth left out barely moves. The test's null is the wide one so that the warp polish
//    (warp_polish.hpp), which the test triggers, fires on a warp and not on the levels' scatter.
// The structure term holds the white noise too, so the two are bounded, not summed. The bounds
// are taken with rotations about the overlap's centre, so they do not depend on where the source
// origin lies; the result is expressed about the source origin, as the message wants.
// See docs/benchmark.md (Covariance) for what it is calibrated against (pda_covariance_check).

#include <Eigen/Geometry>

#include "pda_registration/core/association_weights.hpp"

namespace pda_registration {

/// The two terms and the correlogram's widest level, for inspection and tests.
struct PoseCovarianceTerms {
  Eigen::Matrix<double, 6, 6> model = Eigen::Matrix<double, 6, 6>::Zero();
  Eigen::Matrix<double, 6, 6> structure = Eigen::Matrix<double, 6, 6>::Zero();
  size_t cells = 0;        ///< occupied cells of the ladder's largest level (0: no structure term)
  double cell_edge = 0.0;  ///< [length] their edge: about how far the residuals are correlated
  size_t disagreeing_cuts = 0;  ///< halves of the overlap that disagreed beyond the rest (0-3)
};

/// `nu` is the E-step's (+inf: Gaussian). The correspondences' second moments (the E-step's
/// EStepBuffers::second_moments) give the observed information; without them the complete-data
/// one is used. Returns false (and a zero matrix) when the Hessian is singular or there is
/// nothing to use.
bool computePoseCovariance(const WeightedCorrespondences& correspondences,
                           const Eigen::Isometry3d& T_target_source, double sigma_squared,
                           double nu, Eigen::Matrix<double, 6, 6>* covariance,
                           PoseCovarianceTerms* terms = nullptr);

/// The error a covariance expects, as one number per part: sqrt(trace) of its translation block
/// [length] and of its rotation block [rad] (for an unbiased estimate, the root mean square of
/// |t error| and of the rotation angle).
struct ExpectedError {
  double translation = 0.0;
  double rotation = 0.0;
};
ExpectedError expectedError(const Eigen::Matrix<double, 6, 6>& covariance);

/// The covariance of T^-1 given the covariance of T (same convention, expressed for the inverse
/// transform's own parent frame): the first-order propagation through inversion.
Eigen::Matrix<double, 6, 6> invertedPoseCovariance(const Eigen::Isometry3d& T,
                                                   const Eigen::Matrix<double, 6, 6>& covariance);

}  // namespace pda_registration
