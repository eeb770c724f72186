#include "pda_registration/core/association_weights.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "pda_registration/core/noise_model.hpp"

namespace pda_registration {
namespace {

constexpr double kDimension = 3.0;

// base^exponent for base in (0, 1]: repeated multiplication when 2*exponent is a small integer
// (nu = 1, 3, 5, ... and nu = 2, 4, ... give (nu + 3) / 2 of that form), std::pow otherwise.
// The E-step spends most of its time here, and integer nu is the common case.
double powerOf(double base, double exponent) {
  const double twice = 2.0 * exponent;
  if (twice > 0.0 && twice <= 64.0 && twice == std::floor(twice)) {
    const int whole = static_cast<int>(exponent);
    double result = (twice - 2.0 * whole) > 0.5 ? std::sqrt(base) : 1.0;
    double square = base;
    for (int bits = whole; bits > 0; bits >>= 1) {
      if (bits & 1) result *= square;
      square *= square;
    }
    return result;
  }
  return std::pow(base, exponent);
}

}  // namespace

void computeCandidateWeights(const double* squared_residuals, size_t count, double nu,
                             double sigma_squared, double* posterior, double* weight) {
  if (count == 0) return;
  const bool gaussian = std::isinf(nu);
  // Densities are taken relative to the best candidate's, so tiny sigmas cannot underflow every
  // candidate to zero: for the t (eq. 20) p_i / p_best = ((nu + m_best) / (nu + m_i))^((nu+d)/2).
  const double best =
      *std::min_element(squared_residuals, squared_residuals + count) / sigma_squared;
  const double exponent = 0.5 * (nu + kDimension);
  double total = 0.0;
  for (size_t i = 0; i < count; ++i) {
    const double mahalanobis = squared_residuals[i] / sigma_squared;
    posterior[i] = gaussian ? std::exp(-0.5 * (mahalanobis - best))                 // eq. 19
                            : powerOf((nu + best) / (nu + mahalanobis), exponent);  // eq. 20
    total += posterior[i];
  }
  for (size_t i = 0; i < count; ++i) {
    posterior[i] /= total;
    const double mahalanobis = squared_residuals[i] / sigma_squared;
    const double expected_precision =
        gaussian ? 1.0 : (nu + kDimension) / (nu + mahalanobis);  // eq. 16
    weight[i] = posterior[i] * expected_precision;                // eqs. 15, 21
  }
}

WeightedCorrespondences computeWeightedCorrespondences(
    const PointList& source, const CandidateSets& candidates, const PointList& normals,
    double inverse_kappa, const Eigen::Isometry3d& T_target_source, double nu, double sigma_squared,
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
      const size_t count = candidates.candidateCount(j);
      if (count == 0) continue;
      const Point* y = &candidates.points[candidates.offsets[j]];
      residuals.resize(count);
      posterior.resize(count);
      rho.resize(count);
      const Point x = T_target_source * source[j];
      const Point normal = normals.empty() ? Point::Zero() : normals[j];
      for (size_t i = 0; i < count; ++i) {
        residuals[i] = shapedSquaredNorm(y[i] - x, normal, inverse_kappa);
      }
      computeCandidateWeights(residuals.data(), count, nu, sigma_squared, posterior.data(),
                              rho.data());
      double w = 0.0;
      Point mean = Point::Zero();
      for (size_t i = 0; i < count; ++i) {
        w += rho[i];
        mean += rho[i] * y[i];
      }
      if (!(w > 0.0)) continue;
      mean /= w;
      double spread = 0.0;
      for (size_t i = 0; i < count; ++i) {
        spread += rho[i] * shapedSquaredNorm(y[i] - mean, normal, inverse_kappa);
      }
      means[j] = mean;
      weights[j] = w;
      spreads[j] = spread;
    }
  }

  WeightedCorrespondences out;
  out.inverse_kappa = inverse_kappa;
  const size_t used = static_cast<size_t>(
      std::count_if(weights.begin(), weights.end(), [](double w) { return w > 0.0; }));
  out.source_index.reserve(used);
  out.source.reserve(used);
  out.target_mean.reserve(used);
  out.weight.reserve(used);
  out.normal.reserve(used);
  for (size_t j = 0; j < n; ++j) {
    if (!(weights[j] > 0.0)) continue;
    out.source_index.push_back(j);
    out.source.push_back(source[j]);
    out.target_mean.push_back(means[j]);
    out.weight.push_back(weights[j]);
    out.normal.push_back(normals.empty() ? Point::Zero() : normals[j]);
    out.spread += spreads[j];
  }
  return out;
}

Associations computeAssociations(const PointList& source, const CandidateSets& candidates,
                                 const PointList& normals, double inverse_kappa,
                                 const Eigen::Isometry3d& T_target_source, double nu,
                                 double sigma_squared) {
  Associations out;
  out.offsets.push_back(0);
  std::vector<double> residuals, rho;
  for (size_t j = 0; j < candidates.sourceCount(); ++j) {
    const size_t count = candidates.candidateCount(j);
    if (count == 0) continue;
    const Point x = T_target_source * source[j];
    const Point normal = normals.empty() ? Point::Zero() : normals[j];
    const Point* y = &candidates.points[candidates.offsets[j]];
    residuals.resize(count);
    rho.resize(count);
    for (size_t i = 0; i < count; ++i)
      residuals[i] = shapedSquaredNorm(y[i] - x, normal, inverse_kappa);
    const size_t first = out.posterior.size();
    out.posterior.resize(first + count);
    computeCandidateWeights(residuals.data(), count, nu, sigma_squared, &out.posterior[first],
                            rho.data());
    out.source_points.push_back(x);
    out.candidates.insert(out.candidates.end(), y, y + count);
    out.offsets.push_back(out.candidates.size());
  }
  return out;
}

double weightedObjective(const WeightedCorrespondences& correspondences,
                         const Eigen::Isometry3d& T_target_source) {
  double total = correspondences.spread;
  for (size_t i = 0; i < correspondences.size(); ++i) {
    total += correspondences.weight[i] *
             shapedSquaredNorm(
                 correspondences.target_mean[i] - T_target_source * correspondences.source[i],
                 correspondences.normal[i], correspondences.inverse_kappa);
  }
  return total;
}

double estimateSigmaSquared(const WeightedCorrespondences& correspondences,
                            const Eigen::Isometry3d& T_target_source) {
  if (correspondences.size() == 0) return 0.0;
  return weightedObjective(correspondences, T_target_source) /
         (kDimension * static_cast<double>(correspondences.size()));
}

double initialSigmaSquared(const PointList& source, const CandidateSets& candidates,
                           const Eigen::Isometry3d& T_target_source) {
  double total = 0.0;
  size_t pairs = 0;
  for (size_t j = 0; j < candidates.sourceCount(); ++j) {
    const Point x = T_target_source * source[j];
    for (size_t c = candidates.offsets[j]; c < candidates.offsets[j + 1]; ++c) {
      total += (candidates.points[c] - x).squaredNorm();
      ++pairs;
    }
  }
  return pairs == 0 ? 0.0 : total / (kDimension * static_cast<double>(pairs));
}

}  // namespace pda_registration
