#include "pda_registration/core/final_statistics.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "pda_registration/core/association_weights.hpp"
#include "pda_registration/core/competing_shift.hpp"
#include "pda_registration/core/degeneracy.hpp"
#include "pda_registration/core/degrees_of_freedom.hpp"
#include "pda_registration/core/noise_shapes.hpp"
#include "pda_registration/core/outlier_class.hpp"
#include "pda_registration/core/pose_covariance.hpp"

namespace pda_registration {
namespace {

// Source points with a target point within `radius` of them at T. A point with candidates has
// one (the candidates were searched within at most `radius`); the others are looked up.
size_t countOverlap(const TargetIndex& index, const PointList& source,
                    const CandidateSets& candidates, const Eigen::Isometry3d& T, double radius,
                    int threads) {
  size_t overlap = 0;
#pragma omp parallel for schedule(dynamic, 256) reduction(+ : overlap) \
    num_threads(std::max(threads, 1))
  for (long long j = 0; j < static_cast<long long>(candidates.sourceCount()); ++j) {
    if (candidates.candidateCount(j) > 0) {
      ++overlap;
      continue;
    }
    size_t nearest = 0;
    double squared_distance = 0.0;
    overlap += index.nearestWithinRadius(T * source[j], 1, radius, &nearest, &squared_distance);
  }
  return overlap;
}

// Inlier fraction over all used source points and over the overlap, and the mean distance of
// inliers to their nearest candidate, at the final estimate.
void fillInlierStatistics(const PointList& source, const CandidateSets& candidates,
                          const Eigen::Isometry3d& T, double inlier_distance, size_t overlap,
                          RegistrationResult* result) {
  size_t inliers = 0;
  double distance_sum = 0.0;
  for (size_t j = 0; j < candidates.sourceCount(); ++j) {
    if (candidates.candidateCount(j) == 0) continue;
    const Point x = T * source[j];
    double best = std::numeric_limits<double>::infinity();
    for (size_t c = candidates.offsets[j]; c < candidates.offsets[j + 1]; ++c) {
      best = std::min(best, (candidates.points[c] - x).squaredNorm());
    }
    best = std::sqrt(best);
    if (best < inlier_distance) {
      ++inliers;
      distance_sum += best;
    }
  }
  result->inlier_fraction =
      source.empty() ? 0.0 : static_cast<double>(inliers) / static_cast<double>(source.size());
  result->mean_residual = inliers == 0 ? 0.0 : distance_sum / static_cast<double>(inliers);
  result->overlap_points = overlap;
  result->support_fraction =
      overlap == 0 ? 0.0 : static_cast<double>(inliers) / static_cast<double>(overlap);
}

}  // namespace

double supportFractionAt(const TargetIndex& index, const PointList& source,
                         const Eigen::Isometry3d& T, double inlier_distance, double overlap_radius,
                         int threads) {
  size_t overlap = 0;
  size_t inliers = 0;
#pragma omp parallel for schedule(dynamic, 256) reduction(+ : overlap, inliers) \
    num_threads(std::max(threads, 1))
  for (long long j = 0; j < static_cast<long long>(source.size()); ++j) {
    size_t nearest = 0;
    double squared_distance = 0.0;
    if (index.nearestWithinRadius(T * source[j], 1, overlap_radius, &nearest, &squared_distance) ==
        0) {
      continue;
    }
    ++overlap;
    if (squared_distance < inlier_distance * inlier_distance) ++inliers;
  }
  return overlap == 0 ? 0.0 : static_cast<double>(inliers) / static_cast<double>(overlap);
}

// Covariance, inlier statistics and the degeneracy check at the final estimate.
void fillFinalStatistics(const PointList& source, const TargetIndex& index,
                         const SurfaceNormalMap& normal_map, const RegistrationParameters& p,
                         const EmState& state, RegistrationWorkspace* workspace,
                         RegistrationResult* result, Associations* associations) {
  const CandidateSets& candidates = workspace->candidates;
  // The refine runs' normals (at the candidates), as the last run's E-step had them.
  computeShapeInputs(normal_map, source, candidates, state.T, p, NormalLookup::kAtCandidate,
                     /*every_point=*/true, /*measure_thickness=*/false, &workspace->normals,
                     &workspace->spread, &workspace->normal_memos);
  // The degeneracy check needs the normals even when the noise model does not.
  PointList isotropic_normals;
  if (workspace->normals.empty()) {
    lookupNormals(normal_map, source, state.T, p.threads, candidates, NormalLookup::kAtCandidate,
                  /*every_point=*/true, &isotropic_normals);
  }
  const PointList& normals = workspace->normals.empty() ? isotropic_normals : workspace->normals;
  makeNoiseShapes(workspace->normals, workspace->spread, state.sigma_squared, p,
                  &workspace->shapes);
  const NoiseShapes& shapes = workspace->shapes;
  workspace->e_step.second_moments = true;  // for the covariance's observed information
  // The nu the refine runs' E-steps weighed with.
  const double nu =
      nuModeOfRun(p, /*refine_stage=*/true) == NuMode::kEstimated ? nuOfEStep(state.nu) : state.nu;
  // The statistics' candidates are searched within the full radius.
  workspace->e_step.outliers = state.outlier_class
                                   ? outlierClassFor(state.outlier_share, p.radius, nu)
                                   : OutlierClass();
  computeWeightedCorrespondences(source, candidates, shapes, state.T, nu, state.sigma_squared,
                                 p.threads, &workspace->e_step, &workspace->correspondences);
  workspace->e_step.second_moments = false;
  const WeightedCorrespondences& correspondences = workspace->correspondences;
  const auto covariance_start = std::chrono::steady_clock::now();
  PoseCovarianceTerms terms;
  computePoseCovariance(correspondences, state.T, state.sigma_squared, nu,
                        &result->covariance, &terms);
  result->covariance_correlation_length = terms.cell_edge;
  result->disagreeing_halves = terms.disagreeing_cuts;
  // A second peak along the least certain direction, which the curvature at this one cannot see.
  CompetingShiftSettings probe;
  probe.inlier_distance = p.inlier_sigmas * result->sigma;
  probe.search_radius = refineRadius(p, state.sigma_squared);
  probe.reach = p.radius;
  const CompetingShift competitor = findCompetingShift(
      source, normals, state.T, index, result->covariance.topLeftCorner<3, 3>(), probe);
  result->covariance = withCompetingShift(result->covariance, competitor);
  result->competing_shift = competitor.shift.norm();
  result->competing_share = competitor.share;
  result->competing_prominence = competitor.relative_prominence;
  result->covariance_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - covariance_start)
          .count();
  fillInlierStatistics(source, candidates, state.T, p.inlier_sigmas * result->sigma,
                       countOverlap(index, source, candidates, state.T, p.radius, p.threads),
                       result);
  PointList moved(source.size());
  for (size_t j = 0; j < source.size(); ++j) moved[j] = state.T * source[j];
  result->degeneracy_ratio = constraintEigenvalueRatio(moved, normals);
  if (associations) {
    *associations =
        computeAssociations(source, candidates, shapes, state.T, nu, state.sigma_squared);
  }
}

}  // namespace pda_registration
