#include "pda_registration/core/association_weights.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace pda_registration {
namespace {
constexpr double kDimension = 3.0;
}

void computeCandidateWeights(const double* squared_residuals, size_t count, double nu,
                             double sigma_squared, double* posterior, double* weight) {
  if (count == 0) return;
  const bool gaussian = std::isinf(nu);
  // Log-densities first, normalised with the max subtracted, so tiny sigmas cannot underflow
  // every candidate to zero.
  double max_log = -std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < count; ++i) {
    const double mahalanobis = squared_residuals[i] / sigma_squared;
    posterior[i] = gaussian ? -0.5 * mahalanobis
                            : -0.5 * (nu + kDimension) * std::log1p(mahalanobis / nu);  // eq. 20
    max_log = std::max(max_log, posterior[i]);
  }
  double total = 0.0;
  for (size_t i = 0; i < count; ++i) {
    posterior[i] = std::exp(posterior[i] - max_log);
    total += posterior[i];
  }
  for (size_t i = 0; i < count; ++i) {
    posterior[i] /= total;
    const double mahalanobis = squared_residuals[i] / sigma_squared;
    const double expected_precision =
        gaussian ? 1.0 : (nu + kDimension) / (nu + mahalanobis);  // eq. 16
    weight[i] = posterior[i] * expected_precision;                 // eqs. 15, 21
  }
}

WeightedCorrespondences computeWeightedCorrespondences(const PointList& target,
                                                       const PointList& source,
                                                       const CandidateSets& candidates,
                                                       const Eigen::Isometry3d& T_target_source,
                                                       double nu, double sigma_squared,
                                                       int threads) {
  const size_t n = candidates.sourceCount();
  // Per-source results are written to fixed slots in parallel and compacted serially, so the
  // sums (and therefore the estimate) are the same for any thread count.
  PointList means(n, Point::Zero());
  std::vector<double> weights(n, 0.0);
  std::vector<double> spreads(n, 0.0);

#pragma omp parallel num_threads(std::max(threads, 1))
  {
    std::vector<double> residuals, posterior, rho;
#pragma omp for schedule(dynamic, 256)
    for (long long j = 0; j < static_cast<long long>(n); ++j) {
      const size_t begin = candidates.offsets[j];
      const size_t count = candidates.candidateCount(j);
      if (count == 0) continue;
      residuals.resize(count);
      posterior.resize(count);
      rho.resize(count);
      const Point x = T_target_source * source[j];
      for (size_t i = 0; i < count; ++i) {
        residuals[i] = (target[candidates.target_indices[begin + i]] - x).squaredNorm();
      }
      computeCandidateWeights(residuals.data(), count, nu, sigma_squared, posterior.data(),
                              rho.data());
      double w = 0.0;
      Point mean = Point::Zero();
      for (size_t i = 0; i < count; ++i) {
        w += rho[i];
        mean += rho[i] * target[candidates.target_indices[begin + i]];
      }
      if (!(w > 0.0)) continue;
      mean /= w;
      double spread = 0.0;
      for (size_t i = 0; i < count; ++i) {
        spread += rho[i] * (target[candidates.target_indices[begin + i]] - mean).squaredNorm();
      }
      means[j] = mean;
      weights[j] = w;
      spreads[j] = spread;
    }
  }

  WeightedCorrespondences out;
  for (size_t j = 0; j < n; ++j) {
    if (!(weights[j] > 0.0)) continue;
    out.source_index.push_back(j);
    out.source.push_back(source[j]);
    out.target_mean.push_back(means[j]);
    out.weight.push_back(weights[j]);
    out.spread += spreads[j];
  }
  return out;
}

double weightedObjective(const WeightedCorrespondences& correspondences,
                         const Eigen::Isometry3d& T_target_source) {
  double total = correspondences.spread;
  for (size_t i = 0; i < correspondences.size(); ++i) {
    total += correspondences.weight[i] *
             (correspondences.target_mean[i] - T_target_source * correspondences.source[i])
                 .squaredNorm();
  }
  return total;
}

double estimateSigmaSquared(const WeightedCorrespondences& correspondences,
                            const Eigen::Isometry3d& T_target_source) {
  if (correspondences.size() == 0) return 0.0;
  return weightedObjective(correspondences, T_target_source) /
         (kDimension * static_cast<double>(correspondences.size()));
}

double initialSigmaSquared(const PointList& target, const PointList& source,
                           const CandidateSets& candidates,
                           const Eigen::Isometry3d& T_target_source) {
  double total = 0.0;
  size_t pairs = 0;
  for (size_t j = 0; j < candidates.sourceCount(); ++j) {
    const Point x = T_target_source * source[j];
    for (size_t c = candidates.offsets[j]; c < candidates.offsets[j + 1]; ++c) {
      total += (target[candidates.target_indices[c]] - x).squaredNorm();
      ++pairs;
    }
  }
  return pairs == 0 ? 0.0 : total / (kDimension * static_cast<double>(pairs));
}

}  // namespace pda_registration
