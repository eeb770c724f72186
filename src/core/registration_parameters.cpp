#include "pda_registration/core/registration_parameters.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace pda_registration {
namespace {
bool finiteNonNegative(double v) { return std::isfinite(v) && v >= 0.0; }
bool finitePositive(double v) { return std::isfinite(v) && v > 0.0; }
}  // namespace

std::string validateParameters(const RegistrationParameters& p) {
  std::ostringstream error;
  if (p.k < 1 || p.k > 1000)
    error << "k must be in [1, 1000] (got " << p.k << ")";
  else if (!finitePositive(p.radius))
    error << "radius must be > 0 and finite (got " << p.radius << ")";
  else if (!finitePositive(p.min_radius))
    error << "min_radius must be > 0 and finite (got " << p.min_radius << ")";
  else if (std::isnan(p.nu) || !(p.nu > 0.0))
    error << "nu must be > 0 or inf (got " << p.nu << ")";
  else if (p.nu_mode == NuMode::kEstimated && !std::isfinite(p.nu))
    error << "nu_mode estimated needs a finite starting nu (got " << p.nu << ")";
  else if (p.sigma_mode == SigmaMode::kFixed && !finitePositive(p.fixed_sigma))
    error << "fixed_sigma must be > 0 and finite (got " << p.fixed_sigma << ")";
  else if (p.max_em_iterations < 1 || p.max_em_iterations > 1000)
    error << "max_em_iterations must be in [1, 1000] (got " << p.max_em_iterations << ")";
  else if (p.max_runs < 1 || p.max_runs > 1000)
    error << "max_runs must be in [1, 1000] (got " << p.max_runs << ")";
  else if (p.coarse_stride < 1 || p.coarse_stride > 1000)
    error << "coarse_stride must be in [1, 1000] (got " << p.coarse_stride << ")";
  else if (!(p.time_limit_ms >= 0.0) || !std::isfinite(p.time_limit_ms))
    error << "time_limit_ms must be finite and >= 0 (got " << p.time_limit_ms << ")";
  else if (!finiteNonNegative(p.translation_epsilon) || !finiteNonNegative(p.rotation_epsilon))
    error << "translation_epsilon and rotation_epsilon must be >= 0 and finite";
  else if (p.solver_max_iterations < 1 || p.solver_max_iterations > 1000)
    error << "solver_max_iterations must be in [1, 1000] (got " << p.solver_max_iterations << ")";
  else if (!(std::isfinite(p.surface_anisotropy) && p.surface_anisotropy >= 1.0))
    error << "surface_anisotropy must be >= 1 and finite (got " << p.surface_anisotropy << ")";
  else if (!finiteNonNegative(p.sampling_scale) || p.sampling_scale > 1e6)
    error << "sampling_scale must be in [0, 1e6] (got " << p.sampling_scale << ")";
  else if (p.solver == MStepSolver::kClosedForm && p.surface_anisotropy != 1.0)
    error << "solver closed_form needs surface_anisotropy = 1 (it cannot weigh surface normals);"
          << " use gauss_newton or ceres";
  else if (!finitePositive(p.normal_voxel_size))
    error << "normal_voxel_size must be > 0 and finite (got " << p.normal_voxel_size << ")";
  else if (!finiteNonNegative(p.source_voxel_size) || !finiteNonNegative(p.target_voxel_size))
    error << "voxel sizes must be >= 0 and finite (0 disables downsampling)";
  else if (p.crop_above_points < 0)
    error << "crop_above_points must be >= 0 (got " << p.crop_above_points << ")";
  else if (!finiteNonNegative(p.crop_max_translation))
    error << "crop_max_translation must be >= 0 and finite (got " << p.crop_max_translation << ")";
  else if (!(p.crop_max_rotation_deg >= 0.0 && p.crop_max_rotation_deg <= 180.0))
    error << "crop_max_rotation_deg must be in [0, 180] (got " << p.crop_max_rotation_deg << ")";
  else if (p.min_correspondences < 3)
    error << "min_correspondences must be >= 3 (got " << p.min_correspondences << ")";
  else if (!finitePositive(p.inlier_sigmas))
    error << "inlier_sigmas must be > 0 (got " << p.inlier_sigmas << ")";
  else if (!(p.min_support_fraction >= 0.0 && p.min_support_fraction <= 1.0))
    error << "min_support_fraction must be in [0, 1] (got " << p.min_support_fraction << ")";
  else if (!(p.degeneracy_threshold >= 0.0 && p.degeneracy_threshold < 1.0))
    error << "degeneracy_threshold must be in [0, 1) (got " << p.degeneracy_threshold << ")";
  else if (p.threads < 1 || p.threads > 256)
    error << "threads must be in [1, 256] (got " << p.threads << ")";
  else if (p.max_source_points < 0 ||
           (p.max_source_points > 0 && p.max_source_points < p.min_correspondences))
    error << "max_source_points must be 0 (no budget) or at least min_correspondences ("
          << p.min_correspondences << ") (got " << p.max_source_points << ")";
  return error.str();
}

const char* toString(MStepSolver solver) {
  switch (solver) {
    case MStepSolver::kGaussNewton:
      return "gauss_newton";
    case MStepSolver::kClosedForm:
      return "closed_form";
    case MStepSolver::kCeres:
      return "ceres";
  }
  return "unknown";
}

const char* toString(SigmaMode mode) { return mode == SigmaMode::kFixed ? "fixed" : "estimated"; }

const char* toString(NuMode mode) {
  static const char* const kNames[] = {"fixed", "estimated", "refine"};  // NuMode's order
  return kNames[static_cast<int>(mode)];
}

NuMode nuModeOfRun(const RegistrationParameters& p, bool refine_stage) {
  if (p.nu_mode != NuMode::kRefine) return p.nu_mode;
  // nu = inf asks for the paper's Gaussian (`gaussian: true`): the default mode keeps it.
  return refine_stage && std::isfinite(p.nu) ? NuMode::kEstimated : NuMode::kFixed;
}

double refineRadius(const RegistrationParameters& p, double sigma_squared) {
  if (!(sigma_squared > 0.0)) return p.radius;
  return std::min(p.radius, std::max(p.min_radius, 6.0 * std::sqrt(sigma_squared)));
}

bool parseSolver(const std::string& text, MStepSolver* solver) {
  if (text == "gauss_newton")
    *solver = MStepSolver::kGaussNewton;
  else if (text == "closed_form")
    *solver = MStepSolver::kClosedForm;
  else if (text == "ceres")
    *solver = MStepSolver::kCeres;
  else
    return false;
  return true;
}

bool parseSigmaMode(const std::string& text, SigmaMode* mode) {
  if (text == "estimated")
    *mode = SigmaMode::kEstimated;
  else if (text == "fixed")
    *mode = SigmaMode::kFixed;
  else
    return false;
  return true;
}

bool parseNuMode(const std::string& text, NuMode* mode) {
  if (text == "fixed")
    *mode = NuMode::kFixed;
  else if (text == "estimated")
    *mode = NuMode::kEstimated;
  else if (text == "refine")
    *mode = NuMode::kRefine;
  else
    return false;
  return true;
}

}  // namespace pda_registration
