#pragma once
// What one alignment returns. Never thrown: a failed alignment is a result with converged = false
// and a reason a person can act on.

#include <Eigen/Geometry>
#include <string>

namespace pda_registration {

struct RegistrationResult {
  /// p_target = T_target_source * p_source. Equal to the initial guess when nothing could be done.
  Eigen::Isometry3d T_target_source = Eigen::Isometry3d::Identity();
  /// Covariance of the estimate, ROS order (x, y, z, roll, pitch, yaw): a left perturbation
  /// exp(delta) * T expressed in the target frame (pose_covariance.hpp: noise plus the residuals'
  /// spatial correlation). Zero when it could not be computed.
  Eigen::Matrix<double, 6, 6> covariance = Eigen::Matrix<double, 6, 6>::Zero();
  /// [length] how far the residuals were found correlated: the cell edge of the structure term's
  /// largest level (0: noise term only)
  double covariance_correlation_length = 0.0;
  double covariance_ms = 0.0;  ///< time spent on it (part of time_ms)
  /// Cuts of the overlap whose halves disagreed beyond the covariance (pose_covariance.hpp, 0-3):
  /// a map warped or bent as a whole.
  size_t disagreeing_halves = 0;
  /// [length] how far along the least certain direction a second pose fits the points that fix
  /// that direction nearly as well (competing_shift.hpp; 0: none): the covariance holds it
  double competing_shift = 0.0;
  double competing_share = 0.0;  ///< that pose's share of the two poses' support (0: none)
  /// The most prominent peak beyond the estimate's, found or not: its rise relative to the
  /// estimate's (a competing pose from 0.5; 0: no peak). How near the flag an answer stands.
  double competing_prominence = 0.0;

  bool converged = false;
  std::string reason;  ///< why not converged (empty when converged)
  /// Stopped by time_limit_ms before it came to rest, or failed with the other direction or a
  /// wider search still to try when the limit cut them (the reason says which).
  bool out_of_time = false;

  int runs = 0;           ///< candidate-set computations (outer loop)
  int em_iterations = 0;  ///< E/M iterations summed over runs
  double sigma = 0.0;     ///< final residual scale [length]
  double nu = 0.0;        ///< Student-t degrees of freedom at the end (estimated or the parameter)

  size_t source_points_used = 0;     ///< finite source points after downsampling
  size_t source_points_dropped = 0;  ///< NaN/Inf source points dropped
  size_t target_points_used = 0;     ///< target points indexed (after any crop)
  size_t target_points_total = 0;    ///< finite target points kept (before any crop)
  bool target_cropped = false;       ///< the index covers only the source's reach
  double target_subset_voxel = 0.0;  ///< [length] grid of the indexed voxel means (0: every point)
  /// [length] finest voxel of the target's normal map: normal_voxel_size, or the target's
  /// scan-line scale where that is larger (scan_line_scale.hpp)
  double normal_voxel_size = 0.0;
  /// The usual direction did not converge and the source is the denser cloud, so the target was
  /// aligned onto it and the answer inverted (alignment_direction.hpp); the statistics (sigma,
  /// inliers, candidates) are of that run.
  bool roles_swapped = false;
  /// The first alignment ended unresolved (sigma as wide as its search); this is the one from the
  /// seed with the radius widened (wider_search.hpp; its overlap and support within that radius).
  bool search_widened = false;
  /// The first alignment failed, or slid away from the seed; this is the one from the seed with
  /// the outlier class, kept near the seed (local_start.hpp).
  bool local_start = false;
  /// The usual answer was questionable (as for a local start); this is the whole alignment once
  /// more from the seed, its first attempt searching as far as its steps reach (near_search.hpp).
  bool near_search = false;
  /// The halves of the overlap disagreed: the result was refined on with Gaussian weights, to the
  /// least-squares fit over the warped overlap (warp_polish.hpp); nu is then infinity.
  bool warp_polished = false;
  double target_index_ms = 0.0;      ///< time this call spent (re)indexing the target (in time_ms)
  size_t target_points_dropped = 0;  ///< NaN/Inf target points dropped
  size_t source_points_with_candidates = 0;  ///< in the last run
  double inlier_fraction = 0.0;  ///< source points whose best residual is under inlier_sigmas*sigma
  /// Source points with a target point within `radius` at the final estimate: where the two
  /// clouds overlap. The rest (parts of the scene only the source saw) neither support nor
  /// contradict the estimate.
  size_t overlap_points = 0;
  /// Inliers among the overlap_points: what the verdict's min_support_fraction is compared with.
  double support_fraction = 0.0;
  double mean_residual = 0.0;     ///< [length] mean distance to the best candidate, inliers only
  double degeneracy_ratio = 0.0;  ///< min/max eigenvalue of the point-to-plane constraint matrix
  double time_ms = 0.0;  ///< wall time of align(), including any (re)indexing of a large target
};

}  // namespace pda_registration
