#include "pda_registration/ros/live_parameters.hpp"

#include <cmath>
#include <limits>

namespace pda_registration {

LiveParameters liveParametersFrom(const PdaRegistrationConfig& c) {
  LiveParameters live;
  RegistrationParameters& p = live.registration;
  p.k = c.k;
  p.radius = c.radius;
  p.min_radius = c.min_radius;
  p.nu = c.gaussian ? std::numeric_limits<double>::infinity() : c.nu;
  parseNuMode(c.nu_mode, &p.nu_mode);  // the .cfg enums only offer valid names
  parseSigmaMode(c.sigma_mode, &p.sigma_mode);
  p.fixed_sigma = c.fixed_sigma;
  p.surface_anisotropy = c.surface_anisotropy;
  p.sampling_scale = c.sampling_scale;
  p.normal_voxel_size = c.normal_voxel_size;
  p.max_runs = c.runs;
  p.max_em_iterations = c.em_iterations;
  p.coarse_stride = c.coarse_stride;
  p.translation_epsilon = c.translation_epsilon;
  p.rotation_epsilon = c.rotation_epsilon;
  parseSolver(c.solver, &p.solver);
  p.solver_max_iterations = c.solver_iterations;
  p.source_voxel_size = c.source_voxel_size;
  p.target_voxel_size = c.target_voxel_size;
  p.min_correspondences = c.min_correspondences;
  p.min_support_fraction = c.min_support_fraction;
  p.threads = c.threads;
  p.max_source_points = c.max_source_points;
  p.spread_source_budget = c.spread_source_budget;
  // The keeper indexes the dense map's subset itself (dense_subset), so that a growing map's
  // index is extended rather than rebuilt; the core must not thin it again.
  p.target_subset = false;
  live.acceptance.min_inlier_fraction = c.min_inlier_fraction;
  live.acceptance.max_correction_translation = c.max_correction_translation;
  live.acceptance.max_correction_rotation = c.max_correction_rotation_deg * M_PI / 180.0;
  live.acceptance.max_expected_translation = c.max_expected_error;
  live.acceptance.max_expected_rotation = c.max_expected_error_deg * M_PI / 180.0;
  // A large dense map is indexed around the sparse map's reach: as far as the gate lets a
  // correction go, so cropping never hides the answer the gate would accept.
  p.crop_above_points = c.crop_above_points;
  p.crop_max_translation = live.acceptance.max_correction_translation;
  p.crop_max_rotation_deg = c.max_correction_rotation_deg;
  live.min_interval = c.min_interval;
  live.max_markers = static_cast<size_t>(std::max(c.max_markers, 0));
  live.dense_subset = c.dense_subset;
  live.warm_start = c.warm_start;
  live.alignment_share = c.alignment_share;
  live.deadline_periods = c.deadline_periods;
  return live;
}

}  // namespace pda_registration
