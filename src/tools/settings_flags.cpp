#include "pda_registration/tools/settings_flags.hpp"

#include <iostream>
#include <limits>
#include <sstream>

namespace pda_registration {

std::set<std::string> settingsFlagNames() {
  return {"k",
          "radius",
          "nu",
          "runs",
          "em-iterations",
          "solver",
          "sigma-mode",
          "nu-mode",
          "fixed-sigma",
          "threads",
          "source-voxel",
          "target-voxel",
          "translation-epsilon",
          "rotation-epsilon",
          "min-correspondences",
          "min-support",
          "max-source",
          "spread-budget",
          "target-subset",
          "max-iterations",
          "ndt-resolution",
          "ndt-step-size",
          "anisotropy",
          "sampling-scale",
          "normal-voxel",
          "solver-iterations",
          "coarse-stride",
          "ndt-epsilon",
          "min-radius",
          "crop-above",
          "crop-translation",
          "crop-rotation"};
}

CommandLine commandLineWithSettings(const std::set<std::string>& tool_value_flags,
                                    const std::set<std::string>& tool_switches) {
  std::set<std::string> value_flags = settingsFlagNames();
  value_flags.insert(tool_value_flags.begin(), tool_value_flags.end());
  std::set<std::string> switches = {"help"};
  switches.insert(tool_switches.begin(), tool_switches.end());
  return CommandLine(value_flags, switches);
}

std::string settingsFlagsHelp() {
  const RegistrationParameters p;
  const BaselineParameters b;
  std::ostringstream help;
  help << "  --k N                   candidates per source point (" << p.k << ")\n"
       << "  --radius R              candidate radius [m]; ICP/GICP max correspondence distance ("
       << p.radius << ")\n"
       << "  --min-radius R          later runs shrink the radius to 6 sigma, not below R [m] ("
       << p.min_radius << ")\n"
       << "  --nu V                  Student-t degrees of freedom, 'inf' = Gaussian; the start\n"
       << "                          of the refine runs' estimate under --nu-mode refine (" << p.nu
       << ")\n"
       << "  --runs N                max candidate-set recomputations, 1 = single run ("
       << p.max_runs << ")\n"
       << "  --em-iterations N       max EM iterations per run (" << p.max_em_iterations << ")\n"
       << "  --coarse-stride N       early runs use every N-th source point, 1 = off ("
       << p.coarse_stride << ")\n"
       << "  --solver S              gauss_newton | closed_form | ceres (" << toString(p.solver)
       << ")\n"
       << "  --solver-iterations N   GN/LM iterations per M-step (" << p.solver_max_iterations
       << ")\n"
       << "  --anisotropy K          surface anisotropy kappa, 1 = paper's isotropic model ("
       << p.surface_anisotropy << ")\n"
       << "  --sampling-scale S      sampling model: along-surface tolerance in units of the\n"
       << "                          target's local sampling spread, 0 = constant kappa ("
       << p.sampling_scale << ")\n"
       << "  --normal-voxel V        finest voxel of the target normal map [m], raised to\n"
       << "                          the target's scan-line scale where larger ("
       << p.normal_voxel_size << ")\n"
       << "  --sigma-mode M          estimated | fixed (" << toString(p.sigma_mode) << ")\n"
       << "  --nu-mode M             fixed | estimated by EM from --nu on |\n"
       << "                          refine: --nu until the refine runs, then estimated ("
       << toString(p.nu_mode) << ")\n"
       << "  --fixed-sigma S         sigma in fixed mode [m] (" << p.fixed_sigma << ")\n"
       << "  --threads N             worker threads (" << p.threads << ")\n"
       << "  --source-voxel V        source voxel size [m], 0 = off (" << p.source_voxel_size
       << ")\n"
       << "  --target-voxel V        target voxel size [m], 0 = off (" << p.target_voxel_size
       << ")\n"
       << "  --translation-epsilon E convergence threshold [m] (" << p.translation_epsilon << ")\n"
       << "  --rotation-epsilon E    convergence threshold [rad] (" << p.rotation_epsilon << ")\n"
       << "  --min-support F         fewer inliers than this fraction of the source points\n"
       << "                          that have a target point within --radius = not\n"
       << "                          converged (" << p.min_support_fraction << ")\n"
       << "  --max-source N          align a random subsample of at most N source points, as the\n"
       << "                          nodelet's max_source_points; 0 = all (" << p.max_source_points
       << ")\n"
       << "  --spread-budget 0|1     1: the subsample of --max-source is spread over the space\n"
       << "                          the source covers, its densest voxels thinned first (a\n"
       << "                          lidar map whose near objects changed) ("
       << (p.spread_source_budget ? 1 : 0) << ")\n"
       << "  --target-subset 0|1     a source thinned to --max-source is aligned to the target's\n"
       << "                          voxel means at its spacing, when the target is 2x finer;\n"
       << "                          0 = every target point (" << (p.target_subset ? 1 : 0) << ")\n"
       << "  --min-correspondences N fewer source points with candidates = failure ("
       << p.min_correspondences << ")\n"
       << "  --crop-above N          targets with more points are indexed only around the\n"
       << "                          source's reach, 0 = never (" << p.crop_above_points << ")\n"
       << "  --crop-translation M    largest correction a cropped target allows [m] ("
       << p.crop_max_translation << ")\n"
       << "  --crop-rotation DEG     largest rotation a cropped target allows [deg] ("
       << p.crop_max_rotation_deg << ")\n"
       << "  --max-iterations N      ICP/GICP/NDT iterations (" << b.max_iterations << ")\n"
       << "  --ndt-resolution R      NDT cell size [m] (" << b.ndt_resolution << ")\n"
       << "  --ndt-step-size S       NDT step size [m] (" << b.ndt_step_size << ")\n"
       << "  --ndt-epsilon E         NDT transformation epsilon (" << b.ndt_transformation_epsilon
       << ")\n";
  return help.str();
}

bool readSettingsFlags(CommandLine* cl, MethodSettings* settings,
                       const std::set<std::string>& skip) {
  RegistrationParameters& p = settings->pda;
  BaselineParameters& b = settings->baseline;
  const double inf = std::numeric_limits<double>::infinity();
  // Skipped flags are left to the caller (e.g. pda_bag_eval reads them as lists).
  const auto integer = [&](const char* flag, int* value, int min, int max) {
    return skip.count(flag) > 0 || cl->integer(flag, value, min, max);
  };
  const auto number = [&](const char* flag, double* value, double min, double max) {
    return skip.count(flag) > 0 || cl->number(flag, value, min, max);
  };
  const auto given = [&](const char* flag) { return skip.count(flag) == 0 && cl->has(flag); };
  int target_subset = p.target_subset ? 1 : 0;
  int spread_budget = p.spread_source_budget ? 1 : 0;
  if (!integer("k", &p.k, 1, 1000) || !number("radius", &p.radius, 1e-9, 1e9) ||
      !number("nu", &p.nu, 1e-6, inf) || !integer("runs", &p.max_runs, 1, 1000) ||
      !integer("em-iterations", &p.max_em_iterations, 1, 1000) ||
      !number("fixed-sigma", &p.fixed_sigma, 1e-12, 1e9) ||
      !integer("threads", &p.threads, 1, 256) ||
      !number("source-voxel", &p.source_voxel_size, 0.0, 1e6) ||
      !number("target-voxel", &p.target_voxel_size, 0.0, 1e6) ||
      !number("translation-epsilon", &p.translation_epsilon, 0.0, 1e6) ||
      !number("rotation-epsilon", &p.rotation_epsilon, 0.0, 3.2) ||
      !integer("min-correspondences", &p.min_correspondences, 3, 100000000) ||
      !number("min-support", &p.min_support_fraction, 0.0, 1.0) ||
      !integer("max-source", &p.max_source_points, 0, 1000000000) ||
      !integer("target-subset", &target_subset, 0, 1) ||
      !integer("spread-budget", &spread_budget, 0, 1) ||
      !integer("max-iterations", &b.max_iterations, 1, 100000) ||
      !number("ndt-resolution", &b.ndt_resolution, 1e-6, 1e6) ||
      !number("ndt-step-size", &b.ndt_step_size, 1e-9, 1e6) ||
      !number("anisotropy", &p.surface_anisotropy, 1.0, 1e12) ||
      !number("sampling-scale", &p.sampling_scale, 0.0, 1e6) ||
      !number("normal-voxel", &p.normal_voxel_size, 1e-9, 1e6) ||
      !integer("solver-iterations", &p.solver_max_iterations, 1, 1000) ||
      !integer("coarse-stride", &p.coarse_stride, 1, 1000) ||
      !number("ndt-epsilon", &b.ndt_transformation_epsilon, 0.0, 1e3) ||
      !number("min-radius", &p.min_radius, 1e-9, 1e9) ||
      !integer("crop-above", &p.crop_above_points, 0, 2000000000) ||
      !number("crop-translation", &p.crop_max_translation, 0.0, 1e9) ||
      !number("crop-rotation", &p.crop_max_rotation_deg, 0.0, 180.0)) {
    return false;
  }
  if (given("solver") && !parseSolver(cl->text("solver"), &p.solver)) {
    return cl->setError("--solver: " + quoted(cl->text("solver")) +
                        " is not gauss_newton, closed_form or ceres");
  }
  if (given("nu-mode") && !parseNuMode(cl->text("nu-mode"), &p.nu_mode)) {
    return cl->setError("--nu-mode: " + quoted(cl->text("nu-mode")) +
                        " is not fixed, estimated or refine");
  }
  if (given("sigma-mode") && !parseSigmaMode(cl->text("sigma-mode"), &p.sigma_mode)) {
    return cl->setError("--sigma-mode: " + quoted(cl->text("sigma-mode")) +
                        " is not estimated or fixed");
  }
  p.target_subset = target_subset != 0;
  p.spread_source_budget = spread_budget != 0;
  // The baselines share the inputs' limits: same radius, same voxel sizes.
  b.max_correspondence_distance = p.radius;
  b.source_voxel_size = p.source_voxel_size;
  b.target_voxel_size = p.target_voxel_size;
  // Flags that pass one by one can still clash (closed_form needs anisotropy 1): a usage error
  // now, not a failed alignment after the clouds have loaded. (With grids, the skipped flags
  // are not in `p` yet: the grid's own sets are checked where they are made.)
  if (skip.empty()) {
    const std::string clash = validateParameters(p);
    if (!clash.empty()) return cl->setError(clash);
  }
  return true;
}

int startRegistrationTool(const std::string& tool, const char* usage, int argc, char** argv,
                          CommandLine* cl, MethodSettings* settings) {
  if (!cl->parse(argc, argv)) return reportError(tool, cl->error());
  if (cl->has("help")) {
    std::cout << usage << settingsFlagsHelp();
    return 0;
  }
  if (!readSettingsFlags(cl, settings)) return reportError(tool, cl->error());
  return -1;
}

}  // namespace pda_registration
