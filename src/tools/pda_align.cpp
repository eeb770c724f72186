// pda_align: align a source cloud to a target cloud with PDA (or PCL's ICP/GICP/NDT) and print
// one JSON line. Exit codes: 0 converged, 1 ran but did not converge, 2 bad input or usage.

#include <algorithm>
#include <cmath>
#include <functional>
#include <iostream>
#include <map>
#include <sstream>
#include <vector>

#include "pda_registration/core/error_metrics.hpp"
#include "pda_registration/core/perturbation.hpp"
#include "pda_registration/core/pose_covariance.hpp"
#include "pda_registration/core/process_memory.hpp"
#include "pda_registration/core/transform_io.hpp"
#include "pda_registration/tools/cloud_io.hpp"
#include "pda_registration/tools/command_line.hpp"
#include "pda_registration/tools/json_line.hpp"
#include "pda_registration/tools/method_runner.hpp"
#include "pda_registration/tools/settings_flags.hpp"
#include "pda_registration/tools/statistics.hpp"
#include "pda_registration/tools/trace_lines.hpp"

using namespace pda_registration;

namespace {

const char* kUsage =
    "usage: pda_align --target T.pcd|ply --source S.pcd|ply [options]\n"
    "  Aligns the source to the target; prints one JSON line. p_target = T * p_source.\n"
    "  --initial FILE          4x4 row-major initial guess (identity)\n"
    "  --perturb DEG,M         apply a random perturbation of DEG degrees and M metres to the\n"
    "                          initial guess (T_initial * delta), seeded by --seed (0)\n"
    "  --output FILE           write the estimate (4x4 row-major)\n"
    "  --aligned-cloud FILE    write the source moved into the target frame (PCD)\n"
    "  --ground-truth FILE     4x4 ground truth: adds mean_distance (eq. 22), rot_err_deg,\n"
    "                          trans_err_m\n"
    "  --method M              pda | icp | gicp | ndt (pda)\n"
    "  --compare M1,M2         also run these methods, interleaved with --method, and report\n"
    "                          median times and time ratios (e.g. --compare icp,gicp)\n"
    "  --repeat N              repetitions for --compare timing (3)\n"
    "  --trace                 PDA: each run and attempt as a JSON line on stderr (stage,\n"
    "                          radius, sigma, nu, step; adopted or why not); not with --compare\n"
    "  --help\n";

int usageError(const std::string& message) { return reportError("pda_align", message); }

}  // namespace

int main(int argc, char** argv) {
  CommandLine cl =
      commandLineWithSettings({"target", "source", "initial", "perturb", "seed", "output",
                               "aligned-cloud", "ground-truth", "method", "compare", "repeat"},
                              {"trace"});
  MethodSettings settings;
  const int exit_code = startRegistrationTool("pda_align", kUsage, argc, argv, &cl, &settings);
  if (exit_code >= 0) return exit_code;
  if (!cl.has("target") || !cl.has("source"))
    return usageError("--target and --source are required");
  const std::string method = cl.text("method", "pda");
  if (!isKnownMethod(method))
    return usageError("--method: " + quoted(method) + " is not pda, icp, gicp or ndt");
  const std::vector<std::string> compared = splitList(cl.text("compare"));
  for (const std::string& m : compared) {
    if (!isKnownMethod(m))
      return usageError("--compare: " + quoted(m) + " is not pda, icp, gicp or ndt");
  }
  int repeat = 3;
  if (!cl.integer("repeat", &repeat, 1, 1000)) return usageError(cl.error());
  const bool traced = cl.has("trace");
  if (traced && method != "pda") return usageError("--trace: only PDA's runs can be traced");
  if (traced && !compared.empty()) {
    return usageError("--trace: traces one alignment; it cannot be combined with --compare");
  }

  std::string error;
  Eigen::Isometry3d initial = Eigen::Isometry3d::Identity();
  if (cl.has("initial") && !readTransformFile(cl.text("initial"), &initial, &error)) {
    return usageError("--initial: " + error);
  }
  if (cl.has("perturb")) {
    std::vector<double> perturbation;
    if (!cl.numberList("perturb", &perturbation, 0.0, 1e6) || perturbation.size() != 2) {
      return usageError("--perturb: expected DEG,METRES (e.g. 5,0.25)");
    }
    int seed = 0;
    if (!cl.integer("seed", &seed, 0, 1 << 30)) return usageError(cl.error());
    initial = initial * randomPerturbation(perturbation[0], perturbation[1], seed);
  }
  Eigen::Isometry3d ground_truth = Eigen::Isometry3d::Identity();
  const bool has_ground_truth = cl.has("ground-truth");
  if (has_ground_truth && !readTransformFile(cl.text("ground-truth"), &ground_truth, &error)) {
    return usageError("--ground-truth: " + error);
  }

  PointList target, source;
  if (!loadPointCloudFile(cl.text("target"), &target, &error))
    return usageError("--target: " + error);
  if (!loadPointCloudFile(cl.text("source"), &source, &error))
    return usageError("--source: " + error);
  std::function<double(const Eigen::Isometry3d&)> error_from_truth;
  if (has_ground_truth) {
    error_from_truth = [&](const Eigen::Isometry3d& T) {
      return poseError(source, T, ground_truth).mean_distance;
    };
  }

  // Timing comparison: every method runs `repeat` times, interleaved, on identical inputs.
  std::vector<std::string> methods = {method};
  for (const std::string& m : compared) {
    if (std::find(methods.begin(), methods.end(), m) == methods.end()) methods.push_back(m);
  }
  const int rounds = compared.empty() ? 1 : repeat;
  std::map<std::string, std::vector<double>> times;
  std::map<std::string, MethodOutcome> last;
  for (int round = 0; round < rounds; ++round) {
    for (const std::string& m : methods) {
      last[m] = runMethod(m, target, source, initial, settings,
                          traced ? jsonLinesTrace(&std::cerr, error_from_truth) : AlignmentTrace());
      times[m].push_back(last[m].result.time_ms);
    }
  }

  const MethodOutcome& outcome = last[method];
  const RegistrationResult& r = outcome.result;
  JsonLine json;
  json.add("method", method).add("converged", r.converged).add("reason", r.reason);
  json.add("time_ms", compared.empty() ? r.time_ms : median(times[method]));
  if (outcome.pda_fields) {
    json.add("runs", r.runs).add("em_iterations", r.em_iterations).add("sigma", r.sigma);
    json.add("nu", r.nu);
    json.add("inlier_fraction", r.inlier_fraction).add("mean_residual", r.mean_residual);
    json.add("overlap_points", r.overlap_points).add("support_fraction", r.support_fraction);
    json.add("source_points", r.source_points_used).add("source_dropped", r.source_points_dropped);
    json.add("target_points", r.target_points_used).add("target_dropped", r.target_points_dropped);
    json.add("target_points_total", r.target_points_total).add("target_cropped", r.target_cropped);
    json.add("target_subset_voxel", r.target_subset_voxel);
    json.add("normal_voxel_size", r.normal_voxel_size);
    json.add("roles_swapped", r.roles_swapped);
    json.add("search_widened", r.search_widened);
    json.add("local_start", r.local_start);
    json.add("near_search", r.near_search);
    json.add("warp_polished", r.warp_polished);
    json.add("target_index_ms", r.target_index_ms);
    json.add("source_with_candidates", r.source_points_with_candidates);
    json.add("degeneracy_ratio", r.degeneracy_ratio);
    std::ostringstream diagonal;
    diagonal.precision(6);
    diagonal << '[';
    for (int i = 0; i < 6; ++i) diagonal << (i ? "," : "") << r.covariance(i, i);
    diagonal << ']';
    json.addRaw("covariance_diagonal", diagonal.str());
    const ExpectedError expected = expectedError(r.covariance);
    json.add("expected_error_m", expected.translation)
        .add("expected_error_deg", expected.rotation * 180.0 / M_PI);
    json.add("competing_shift_m", r.competing_shift).add("competing_share", r.competing_share);
    json.add("competing_prominence", r.competing_prominence);
    json.add("covariance_ms", r.covariance_ms);
  } else {
    json.addRaw("runs", "null")
        .addRaw("sigma", "null")
        .addRaw("nu", "null")
        .addRaw("inlier_fraction", "null");
    json.add("fitness", outcome.fitness);
  }
  if (has_ground_truth) {
    const PoseError e = poseError(source, r.T_target_source, ground_truth);
    const PoseError initial_error = poseError(source, initial, ground_truth);
    json.add("mean_distance", e.mean_distance).add("rot_err_deg", e.rotation_deg);
    json.add("trans_err_m", e.translation)
        .add("initial_mean_distance", initial_error.mean_distance);
  }
  if (!compared.empty()) {
    JsonLine speed;
    speed.add("repeat", rounds);
    for (const std::string& m : methods) speed.add(m + "_ms", median(times[m]));
    for (const std::string& m : methods) {
      if (m != method) speed.add(method + "_over_" + m, median(times[method]) / median(times[m]));
    }
    if (has_ground_truth) {
      for (const std::string& m : methods) {
        speed.add(m + "_mean_distance",
                  poseError(source, last[m].result.T_target_source, ground_truth).mean_distance);
      }
    }
    json.addRaw("compare", speed.str());
  }
  json.add("T", r.T_target_source);
  json.add("peak_rss_mb", processMemory().peak_mb);
  std::cout << json.str() << std::endl;

  if (cl.has("output") && !writeTransformFile(cl.text("output"), r.T_target_source, &error)) {
    return usageError("--output: " + error);
  }
  if (cl.has("aligned-cloud")) {
    PointList aligned;
    aligned.reserve(source.size());
    for (const Point& p : source) {
      if (p.allFinite()) aligned.push_back(r.T_target_source * p);
    }
    if (!savePointCloudFile(cl.text("aligned-cloud"), aligned, &error)) {
      return usageError("--aligned-cloud: " + error);
    }
  }
  return r.converged ? 0 : 1;
}
