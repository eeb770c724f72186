#include "pda_registration/core/em_run.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

#include "pda_registration/core/association_weights.hpp"
#include "pda_registration/core/ceres_solver.hpp"
#include "pda_registration/core/closed_form_solver.hpp"
#include "pda_registration/core/degrees_of_freedom.hpp"
#include "pda_registration/core/gauss_newton_solver.hpp"
#include "pda_registration/core/noise_shapes.hpp"
#include "pda_registration/core/outlier_class.hpp"
#include "pda_registration/core/run_extrapolation.hpp"

namespace pda_registration {

Increment incrementBetween(const Eigen::Isometry3d& from, const Eigen::Isometry3d& to) {
  const Eigen::AngleAxisd rotation(to.linear() * from.linear().transpose());
  return {(to.translation() - from.translation()).norm(), std::abs(rotation.angle())};
}

bool isSmall(const Increment& increment, const RegistrationParameters& p) {
  return increment.translation <= p.translation_epsilon && increment.rotation <= p.rotation_epsilon;
}

namespace {

bool runMStep(const WeightedCorrespondences& correspondences, const RegistrationParameters& p,
              Eigen::Isometry3d* T) {
  switch (p.solver) {
    case MStepSolver::kClosedForm:
      return solveClosedForm(correspondences, T);
    case MStepSolver::kCeres:
      return solveWithCeres(correspondences, p.solver_max_iterations, p.threads, T);
    case MStepSolver::kGaussNewton:
      break;
  }
  // The EM loop checks convergence itself; inner steps only need to be a little finer.
  return solveGaussNewton(correspondences, p.solver_max_iterations, 0.1 * p.translation_epsilon,
                          0.1 * p.rotation_epsilon, T);
}

}  // namespace

void lookupNormals(const SurfaceNormalMap& map, const PointList& source, const Eigen::Isometry3d& T,
                   int threads, const CandidateSets& candidates, NormalLookup normals_at,
                   bool every_point, PointList* normals,
                   std::vector<SurfaceNormalMap::Memo>* memos) {
  normals->resize(source.size());
  if (memos && memos->size() < source.size()) memos->resize(source.size());
  SurfaceNormalMap::Memo* memo = memos ? memos->data() : nullptr;
#pragma omp parallel for schedule(static) num_threads(std::max(threads, 1))
  for (long long j = 0; j < static_cast<long long>(source.size()); ++j) {
    const bool has_candidates =
        static_cast<size_t>(j) < candidates.sourceCount() && candidates.candidateCount(j) > 0;
    SurfaceNormalMap::Memo* point_memo = memo ? memo + j : nullptr;
    if (has_candidates && normals_at == NormalLookup::kAtCandidate) {
      // The candidates are nearest first.
      (*normals)[j] = map.normalAt(candidates.points[candidates.offsets[j]], point_memo);
    } else if (has_candidates || every_point) {
      (*normals)[j] = map.normalAt(T * source[j], point_memo);
    } else {
      (*normals)[j] = Point::Zero();
    }
  }
}

double computeShapeInputs(const SurfaceNormalMap& normal_map, const PointList& source,
                          const CandidateSets& candidates, const Eigen::Isometry3d& T,
                          const RegistrationParameters& p, NormalLookup normals_at,
                          bool every_point, bool measure_thickness, PointList* normals,
                          std::vector<double>* spread, std::vector<SurfaceNormalMap::Memo>* memos) {
  normals->clear();
  spread->clear();
  if (p.surface_anisotropy > 1.0) {
    lookupNormals(normal_map, source, T, p.threads, candidates, normals_at, every_point, normals,
                  memos);
  }
  if (!usesSamplingModel(p)) return 0.0;
  *spread = candidateSpread(candidates, p.threads);
  return measure_thickness ? targetThickness(candidates, *normals) : 0.0;
}

// One run: EM on the workspace's candidate sets (fixed during the run) until a step is below the
// epsilons or max_em_iterations. Returns false when the M-step cannot solve.
bool runEm(const PointList& source, const SurfaceNormalMap& normal_map, NormalLookup normals_at,
           const RegistrationParameters& p, const PoseStep* step_metric,
           RegistrationWorkspace* workspace, EmState* state, bool* settled, int* em_iterations) {
  const bool estimate_sigma = p.sigma_mode == SigmaMode::kEstimated;
  const CandidateSets& candidates = workspace->candidates;
  // The normals go straight into the shapes, which keep them for every iteration of the run.
  PointList& normals = workspace->shapes.normal;
  // A run whose radius cuts the candidate sets short uses the thickness measured on whole ones
  // (below) and does not measure its own.
  const bool whole_sets = state->search_radius >= p.radius;
  const bool measure_thickness = whole_sets || state->whole_set_thickness <= 0.0;
  double thickness = computeShapeInputs(normal_map, source, candidates, state->T, p, normals_at,
                                        /*every_point=*/false, measure_thickness, &normals,
                                        &workspace->spread, &workspace->normal_memos);
  // A floor keeps the t-weights defined when the clouds match exactly (sigma -> 0); the sampling
  // model's is the target's own thickness about its surface, a property of the map, measured on
  // whole candidate sets. A refine run's radius (6 sigma) cuts a sparse map's sets short, and the
  // median then came from the few points that kept three candidates: the floor followed the
  // radius, which follows sigma, which sat on the floor. The room's scan on its 0.25-m map: 5.0 ->
  // 3.2 candidates a point, the floor 6.7 -> 3.5 cm over five refine runs; factory_p64 on its
  // 0.5-m map: 356 of 12,874 points at radius 0.25 m, the radius swinging 0.25-0.51 m for seven.
  if (whole_sets) {
    state->whole_set_thickness = thickness;
  } else if (!measure_thickness) {
    thickness = state->whole_set_thickness;
  }
  const double sigma_squared_floor = std::max(std::pow(1e-6 * p.radius, 2), thickness);
  if (estimate_sigma && state->sigma_squared == 0.0) {
    state->sigma_squared =
        std::max(initialSigmaSquared(source, candidates, state->T), sigma_squared_floor);
  }
  workspace->e_step.nu_statistic = p.nu_mode == NuMode::kEstimated;
  *settled = false;
  // On fixed candidate sets EM converges linearly, each step about half the one before (the
  // room's scan on its 0.25-m map: 2.2, 1.1, 0.65, 0.40, 0.24 mm), so a run of five iterations
  // ends well short of where it is going. Two steps that agree point at their tail: EM continues
  // from there, and the step after it is usually below the epsilons (the same fixed point, a
  // fifth fewer E-steps over the whole source on the thinned room).
  std::optional<RunExtrapolation> extrapolation;
  if (step_metric) extrapolation.emplace(*step_metric);
  const bool nu_walks = p.nu_mode == NuMode::kEstimated;
  for (int iteration = 0; iteration < p.max_em_iterations; ++iteration) {
    const double e_step_nu = nu_walks ? nuOfEStep(state->nu) : state->nu;
    workspace->e_step.outliers =
        state->outlier_class
            ? outlierClassFor(state->outlier_share, state->search_radius, e_step_nu)
            : OutlierClass();
    makeNoiseShapes(normals, workspace->spread, state->sigma_squared, p, &workspace->shapes);
    computeWeightedCorrespondences(source, candidates, workspace->shapes, state->T, e_step_nu,
                                   state->sigma_squared, p.threads, &workspace->e_step,
                                   &workspace->correspondences);
    const WeightedCorrespondences& correspondences = workspace->correspondences;
    if (state->outlier_class && correspondences.size() > 0) {
      state->outlier_share =
          1.0 - correspondences.inlier_total / static_cast<double>(correspondences.size());
    }
    Eigen::Isometry3d T_next = state->T;
    if (!runMStep(correspondences, p, &T_next)) return false;
    if (estimate_sigma) {
      state->sigma_squared =
          std::max(estimateSigmaSquared(correspondences, T_next), sigma_squared_floor);
    }
    if (nu_walks) {
      state->nu =
          walkDegreesOfFreedom(state->nu, e_step_nu, correspondences.mean_log_u_minus_u, 3.0);
    }
    const Increment step = incrementBetween(state->T, T_next);
    ++*em_iterations;
    if (isSmall(step, p)) {
      state->T = T_next;
      *settled = true;
      break;
    }
    state->T = extrapolation
                   ? extrapolation->next(state->T, T_next, p.translation_epsilon,
                                         kExtrapolationSigmas * std::sqrt(state->sigma_squared))
                   : T_next;
  }
  return true;
}

}  // namespace pda_registration
