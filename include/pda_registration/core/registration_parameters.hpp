#pragma once
// Every knob of the PDA registration, with its default and unit. Lengths are in the clouds' unit
// (metres for ROS data); docs/nodelet.md's parameter tables mirror this file.

#include <limits>
#include <string>

namespace pda_registration {

/// How the M-step solves the weighted least-squares problem (paper eq. 17).
enum class MStepSolver {
  kGaussNewton,  ///< Gauss-Newton on SE(3) with 6x6 normal equations: any noise model
  kClosedForm,   ///< weighted Kabsch/Umeyama: exact, isotropic model only (surface_anisotropy 1)
  kCeres,        ///< Ceres Levenberg-Marquardt on SE(3) (quaternion manifold x R^3)
};

/// How the residual scale sigma^2 (Sigma = sigma^2 I) is obtained.
enum class SigmaMode {
  kEstimated,  ///< re-estimated in every EM iteration: results do not depend on the unit
  kFixed,      ///< sigma = fixed_sigma throughout (fixed_sigma = 1 is the paper's Sigma = I)
};

/// How the Student-t's degrees of freedom nu are obtained.
enum class NuMode {
  kFixed,      ///< nu = the parameter throughout
  kEstimated,  ///< ECM update in every EM iteration, starting from the parameter
               ///< (degrees_of_freedom.hpp), within [1, 60]
  kRefine,     ///< the parameter while the runs approach and settle, then the ECM update in
               ///< the refine runs: the basin is chosen with the parameter's tails, the fit's
               ///< own tails are estimated once it is there
};

struct RegistrationParameters {
  // --- Data association (paper Sec. IV) -----------------------------------------------------
  int k = 5;            ///< max candidates per source point (k nearest target points)
  /// [length] candidates must lie within this distance (an alignment left unresolved is tried
  /// once more at twice it: wider_search.hpp)
  double radius = 1.0;
  /// [length] later runs shrink the radius to 6 sigma but not below this (>= radius: fixed)
  double min_radius = 0.25;
  // --- E-step ------------------------------------------------------------------------------
  double nu = 5.0;  ///< Student-t degrees of freedom; +inf gives the Gaussian of eq. 19
  /// Refine (default): `nu` while the runs approach and settle (the basin is chosen with its
  /// tails), estimated by EM in the refine runs, where the fit's own residuals decide how heavy the
  /// tails are (two sparse scans far apart: 9.5 -> 1.9 cm). Estimated throughout loses the basin at
  /// 20 deg (docs/algorithm.md, "The degrees of freedom").
  NuMode nu_mode = NuMode::kRefine;
  SigmaMode sigma_mode = SigmaMode::kEstimated;
  double fixed_sigma = 1.0;  ///< [length] sigma used when sigma_mode == kFixed
  /// kappa of the noise shape (noise_model.hpp): how much less a residual along the target
  /// surface counts than one across it. 1 = the paper's isotropic Sigma = sigma^2 I. With the
  /// sampling model (sampling_scale > 0) it is the least kappa where a normal is known.
  double surface_anisotropy = 1000.0;
  /// The sampling model (noise_shapes.hpp): along the surface a residual is tolerated up to
  /// sqrt(sampling_scale) times the target's local sampling spread. Unit-free. 0 = constant kappa.
  double sampling_scale = 1.0;
  double normal_voxel_size = 0.15; ///< [length] voxel of the target normal map (> 0)
  // --- EM loop inside one run (candidate sets fixed) ----------------------------------------
  int max_em_iterations = 5;
  // --- Multiple runs (candidate sets recomputed from the current estimate) ------------------
  /// Bound on the runs, counted as work over the whole source (an approach run over the subset
  /// counts as its share); 1 = the paper's single-run mode.
  int max_runs = 50;
  /// Early runs align a random 1/coarse_stride of the source (every point equally likely: a
  /// stride in storage order would keep a few rings of a scan stored firing by firing) until a
  /// run moves less than 10 epsilons; the final runs (and convergence) use every point. 1 = off.
  int coarse_stride = 4;
  /// [ms] wall-clock bound on an alignment, the other direction and a wider search included: no run
  /// starts after it, and a result still moving then comes back "out of time", not converged. 0 =
  /// none (the nodelet sets it for warm alignments: a running system's answer is worth little once
  /// the next scan is waiting).
  double time_limit_ms = 0.0;
  /// [length] converged when a step moves less than this (or when the runs' tail is below 1 % of
  /// sigma: run_tail.hpp)
  double translation_epsilon = 1e-4;
  double rotation_epsilon = 1e-4;  ///< [rad] ... and rotates less than this
  // --- M-step --------------------------------------------------------------------------------
  MStepSolver solver = MStepSolver::kGaussNewton;
  int solver_max_iterations = 1;  ///< GN / LM iterations per M-step (not closed form)
  // --- Pre-processing ------------------------------------------------------------------------
  double source_voxel_size = 0.0;  ///< [length] 0 = keep every source point
  double target_voxel_size = 0.0;  ///< [length] 0 = keep every target point
  /// The target's side of the budget: when the source was thinned to max_source_points, index the
  /// target's voxel means on a grid of the thinned source's sample spacing, if the target holds at
  /// least 2 points per occupied voxel. A target much finer than the points aligned (fused RGB-D
  /// fragments of 1-cm samples against a 15000-point budget) costs its index and queries far more
  /// than it gives the candidate sets. A source within the budget gets every target point (a
  /// sparse sensor's own points need the map's detail). false = always every target point.
  bool target_subset = true;
  // --- Large targets ---------------------------------------------------------------------
  /// Targets with more finite points than this are indexed only around the region each source
  /// can reach (its seed-placed bounds plus the corrections below plus radius); 0 = never crop.
  int crop_above_points = 500000;
  double crop_max_translation = 1.0;  ///< [length] largest correction a cropped target allows
  double crop_max_rotation_deg = 20.0;  ///< [deg] largest rotation a cropped target allows
  // --- Acceptance ----------------------------------------------------------------------------
  int min_correspondences = 10;  ///< fewer source points with candidates: not converged
  double inlier_sigmas = 3.0;    ///< a source point is an inlier if its best residual < this*sigma
  /// A result with fewer inliers than this fraction of the overlap (the source points with a
  /// target point within `radius`) is not converged: sigma has collapsed onto a subset (a lattice
  /// alias, only the ground) that the rest contradicts.
  double min_support_fraction = 0.1;
  double degeneracy_threshold = 1e-3;  ///< min/max eigenvalue ratio of the constraint matrix
  // --- Execution -----------------------------------------------------------------------------
  int threads =
      1;  ///< worker threads for candidate search and E-step (results do not depend on it)
  // --- Per-alignment source budget -----------------------------------------------------------
  /// A source of more points (after source_voxel_size) is aligned as this many of them
  /// (core/source_budget.hpp), so alignment time stays bounded as a sparse map grows or when the
  /// source is itself a dense map; 0 = none. The dense source of a swapped alignment
  /// (alignment_direction.hpp) is still the whole cloud as the target.
  int max_source_points = 15000;
  /// How the budget thins: false, an unbiased random subsample; true, spread over the space the
  /// source covers, its densest voxels first (a lidar map whose near objects changed between the
  /// maps; it costs dense RGB-D maps and sparse scan pairs a few millimetres).
  bool spread_source_budget = false;
};

/// Empty string when the parameters are usable, otherwise a one-line explanation.
std::string validateParameters(const RegistrationParameters& parameters);

const char* toString(MStepSolver solver);
const char* toString(SigmaMode mode);
const char* toString(NuMode mode);
/// The mode one run uses: kRefine is kFixed before the refine stage and kEstimated in it; with
/// nu = inf (the paper's Gaussian, asked for) kFixed throughout.
NuMode nuModeOfRun(const RegistrationParameters& p, bool refine_stage);
/// The candidate radius of a refine run: 6 sigma clamped to [min_radius, radius] (radius while
/// sigma is unknown). Far candidates only matter while the estimate is far off; once it is close
/// they are mostly wrong surfaces (parts of the sparse map the dense map never saw), and dropping
/// them keeps them from biasing the fit. 6 sigma keeps virtually every inlier.
double refineRadius(const RegistrationParameters& p, double sigma_squared);
/// Parses "gauss_newton" / "closed_form" / "ceres"; returns false on anything else.
bool parseSolver(const std::string& text, MStepSolver* solver);
/// Parses "estimated" / "fixed"; returns false on anything else.
bool parseSigmaMode(const std::string& text, SigmaMode* mode);
/// Parses "fixed" / "estimated" / "refine"; returns false on anything else.
bool parseNuMode(const std::string& text, NuMode* mode);

}  // namespace pda_registration
