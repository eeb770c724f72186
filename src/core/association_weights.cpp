#include "pda_registration/core/association_weights.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "pda_registration/core/candidate_weighting.hpp"
#include "pda_registration/core/noise_model.hpp"

namespace pda_registration {
namespace {

constexpr double kDimension = CandidateWeighting::kDimension;
// Fewer source points on a known surface than this (or a tenth): sigma from the whole residual.
constexpr size_t kMinimumSurfacePoints = 10;

}  // namespace

void computeCandidateWeights(const double* squared_residuals, size_t count, double nu,
                             double sigma_squared, double* posterior, double* weight,
                             double* log_precision) {
  const CandidateWeighting weighting(nu, sigma_squared);
  weighting(squared_residuals, count, posterior, weight, log_precision);
}

namespace {

// The E-step's pass over the source points, compiled once per weighting form (and with or without
// nu's statistic): a loop that carries only its own form's branches keeps its values in registers
// (the one loop for every form spilled and reloaded a few dozen of them per point).
template <CandidateWeighting::Form kForm, bool kNuStatistic>
void weighSourcePoints(const PointList& source, const CandidateSets& candidates,
                       const NoiseShapes& shapes, const Eigen::Isometry3d& T_target_source,
                       const CandidateWeighting& weighting, int threads, EStepBuffers* buffers) {
  const size_t n = candidates.sourceCount();
  PointList& means = buffers->means;
  std::vector<double>& weights = buffers->weights;
  std::vector<double>& across = buffers->across;
  std::vector<double>& along = buffers->along;
  std::vector<double>& log_u_minus_u = buffers->log_u_minus_u;
  const bool second_moments = buffers->second_moments;
  std::vector<Eigen::Matrix3d>& moments = buffers->moments;
  std::vector<double>& inlier = buffers->inlier;
  const OutlierClass outliers = buffers->outliers;

#pragma omp parallel num_threads(std::max(threads, 1))
  {
    // Per-candidate scratch: on the stack for the usual few candidates, else in vectors.
    constexpr size_t kOnStack = 32;
    constexpr size_t kArrays = 6;
    double stack[kArrays * kOnStack];
    std::vector<double> heap;
#pragma omp for schedule(dynamic, 256)
    for (long long j = 0; j < static_cast<long long>(n); ++j) {
      const size_t count = candidates.candidateCount(j);
      if (count == 0) continue;
      const Point* y = &candidates.points[candidates.offsets[j]];
      double* residuals = stack;
      if (count > kOnStack) {
        heap.resize(kArrays * count);
        residuals = heap.data();
      }
      double* posterior = residuals + count;
      double* rho = posterior + count;
      double* log_u = rho + count;
      double* normal_component = log_u + count;    // n . r_i
      double* squared = normal_component + count;  // |r_i|^2
      const Point x = T_target_source * source[j];
      const Point normal = shapes.normalAt(j);
      const double inverse_kappa = shapes.inverseKappaAt(j);
      const bool has_normal = normal.squaredNorm() > 0.0;
      // r_i = y_i - x in the point's shape (shapedSquaredNorm), keeping its parts for the spread.
      for (size_t i = 0; i < count; ++i) {
        const Point r = y[i] - x;
        squared[i] = r.squaredNorm();
        normal_component[i] = has_normal ? normal.dot(r) : 0.0;
        residuals[i] = shapedSquaredNormFromParts(squared[i], normal_component[i], inverse_kappa);
      }
      // The normalisation, rho_i = P(a_i) u_i and the sums in one pass.
      const double inverse_total =
          1.0 / weighting.unnormalisedAs<kForm, kNuStatistic>(residuals, count, posterior, rho,
                                                              kNuStatistic ? log_u : nullptr);
      double w = 0.0, precision_term = 0.0;
      double sum_across = 0.0, sum_across_squared = 0.0, sum_squared = 0.0;
      Point offset = Point::Zero();  // sum rho_i r_i
      for (size_t i = 0; i < count; ++i) {
        posterior[i] *= inverse_total;
        rho[i] *= posterior[i];  // eqs. 15, 21
        w += rho[i];
        offset += rho[i] * (y[i] - x);
        sum_across += rho[i] * normal_component[i];
        sum_across_squared += rho[i] * normal_component[i] * normal_component[i];
        sum_squared += rho[i] * squared[i];
        // P(a_i) (log u_i - u_i), with P(a_i) u_i = rho_i.
        if constexpr (kNuStatistic) precision_term += posterior[i] * log_u[i] - rho[i];
      }
      if (!(w > 0.0)) continue;
      // The outlier class's share of this point (1 without it) scales every sum it adds.
      double gamma = 1.0;
      if (outliers.on()) {
        const double best = *std::min_element(residuals, residuals + count);
        const double inverse_sigma_squared = weighting.inverseSigmaSquared();
        // Across the surface the variance is sigma^2; without a normal the whole (isotropic) one.
        const double across_inverse =
            has_normal ? inverse_sigma_squared : inverse_sigma_squared * inverse_kappa;
        gamma = inlierResponsibility(outliers, weighting.nu(), best * inverse_sigma_squared,
                                     -std::log(across_inverse),
                                     1.0 / (inverse_total * static_cast<double>(count)));
        w *= gamma;
        offset *= gamma;
        sum_across *= gamma;
        sum_across_squared *= gamma;
        sum_squared *= gamma;
        precision_term *= gamma;
      }
      inlier[j] = gamma;
      // The spread about the weighted mean, sum rho_i |y_i - mean|^2 split across and along the
      // surface, from the sums about x (the residuals are at most the radius: no cancellation
      // worth the second pass over the candidates it saves).
      const double spread_across = std::max(0.0, sum_across_squared - sum_across * sum_across / w);
      const double spread_along =
          std::max(0.0, sum_squared - offset.squaredNorm() / w - spread_across);
      const Point mean = x + offset / w;
      if (second_moments) {
        // sum_i P(a_i) u_i^2 r_i r_i^T, u_i = rho_i / P(a_i): the association's and the
        // t-weight's share of the observed information (pose_covariance.hpp).
        Eigen::Matrix3d moment = Eigen::Matrix3d::Zero();
        for (size_t i = 0; i < count; ++i) {
          if (!(posterior[i] > 0.0)) continue;
          const Point r = y[i] - x;
          moment.noalias() += (rho[i] * rho[i] / posterior[i]) * r * r.transpose();
        }
        moments[j] = gamma * moment;
      }
      means[j] = mean;
      weights[j] = w;
      across[j] = spread_across;
      along[j] = spread_along;
      log_u_minus_u[j] = precision_term;
    }
  }
}

// A t form's pass, with or without nu's statistic (the Gaussian has none).
template <CandidateWeighting::Form kForm>
void weighWithTheT(bool nu_statistic, const PointList& source, const CandidateSets& candidates,
                   const NoiseShapes& shapes, const Eigen::Isometry3d& T_target_source,
                   const CandidateWeighting& weighting, int threads, EStepBuffers* buffers) {
  if (nu_statistic) {
    weighSourcePoints<kForm, true>(source, candidates, shapes, T_target_source, weighting,
                                   threads, buffers);
  } else {
    weighSourcePoints<kForm, false>(source, candidates, shapes, T_target_source, weighting,
                                    threads, buffers);
  }
}

}  // namespace

void computeWeightedCorrespondences(const PointList& source, const CandidateSets& candidates,
                                    const NoiseShapes& shapes,
                                    const Eigen::Isometry3d& T_target_source, double nu,
                                    double sigma_squared, int threads, EStepBuffers* buffers,
                                    WeightedCorrespondences* out_correspondences) {
  const size_t n = candidates.sourceCount();
  // Per-source results are written to fixed slots in parallel and compacted serially, so the
  // sums (and therefore the estimate) are the same for any thread count.
  const EStepBuffers& slots = *buffers;
  // Only a positive weight marks a slot as written (and the others are read only then).
  buffers->weights.assign(n, 0.0);
  buffers->means.resize(n);
  buffers->across.resize(n);
  buffers->along.resize(n);
  buffers->log_u_minus_u.resize(n);
  buffers->inlier.resize(n);
  const bool nu_statistic = buffers->nu_statistic && !std::isinf(nu);
  const CandidateWeighting weighting(nu, sigma_squared);
  const bool second_moments = buffers->second_moments;
  if (second_moments) buffers->moments.resize(n);
  using Form = CandidateWeighting::Form;
  switch (weighting.form()) {
    case Form::kGaussian:
      weighSourcePoints<Form::kGaussian, false>(source, candidates, shapes, T_target_source,
                                                weighting, threads, buffers);
      break;
    case Form::kIntegerPower:
      weighWithTheT<Form::kIntegerPower>(nu_statistic, source, candidates, shapes,
                                         T_target_source, weighting, threads, buffers);
      break;
    case Form::kLogarithm:
      weighWithTheT<Form::kLogarithm>(nu_statistic, source, candidates, shapes, T_target_source,
                                      weighting, threads, buffers);
      break;
  }

  // Compacted in source order: counted first, so that each field is sized once and written by
  // index (EM calls this every iteration; growing nine vectors point by point cost a twentieth
  // of an alignment).
  WeightedCorrespondences& out = *out_correspondences;
  out.sampling = shapes.sampling;
  const size_t count = static_cast<size_t>(
      std::count_if(slots.weights.begin(), slots.weights.end(), [](double w) { return w > 0.0; }));
  out.source_index.resize(count);
  out.source.resize(count);
  out.target_mean.resize(count);
  out.weight.resize(count);
  out.normal.resize(count);
  out.inverse_kappa.resize(count);
  out.spread_across.resize(count);
  out.spread_along.resize(count);
  out.second_moment.resize(second_moments ? count : 0);
  out.inlier_total = 0.0;
  out.inlier_total_with_normal = 0.0;
  double precision_sum = 0.0;
  for (size_t j = 0, c = 0; j < n; ++j) {
    if (!(slots.weights[j] > 0.0)) continue;
    precision_sum += slots.log_u_minus_u[j];
    out.source_index[c] = j;
    out.source[c] = source[j];
    out.target_mean[c] = slots.means[j];
    out.weight[c] = slots.weights[j];
    out.normal[c] = shapes.normalAt(j);
    out.inverse_kappa[c] = shapes.inverseKappaAt(j);
    out.spread_across[c] = slots.across[j];
    out.spread_along[c] = slots.along[j];
    if (second_moments) out.second_moment[c] = slots.moments[j];
    out.inlier_total += slots.inlier[j];
    if (out.normal[c].squaredNorm() > 0.0) out.inlier_total_with_normal += slots.inlier[j];
    ++c;
  }
  out.mean_log_u_minus_u = count == 0 ? 0.0 : precision_sum / out.inlier_total;
}

Associations computeAssociations(const PointList& source, const CandidateSets& candidates,
                                 const NoiseShapes& shapes,
                                 const Eigen::Isometry3d& T_target_source, double nu,
                                 double sigma_squared) {
  Associations out;
  out.offsets.push_back(0);
  std::vector<double> residuals, rho;
  for (size_t j = 0; j < candidates.sourceCount(); ++j) {
    const size_t count = candidates.candidateCount(j);
    if (count == 0) continue;
    const Point x = T_target_source * source[j];
    const Point normal = shapes.normalAt(j);
    const double inverse_kappa = shapes.inverseKappaAt(j);
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

double weightedObjective(const WeightedCorrespondences& c,
                         const Eigen::Isometry3d& T_target_source) {
  double total = 0.0;
  for (size_t i = 0; i < c.size(); ++i) {
    total += c.weight[i] * shapedSquaredNorm(c.target_mean[i] - T_target_source * c.source[i],
                                             c.normal[i], c.inverse_kappa[i]) +
             c.spread_across[i] + c.inverse_kappa[i] * c.spread_along[i];
  }
  return total;
}

double estimateSigmaSquared(const WeightedCorrespondences& c,
                            const Eigen::Isometry3d& T_target_source) {
  if (c.size() == 0) return 0.0;
  if (c.sampling) {
    // sigma is the noise across the surface: measured where the surface (its normal) is known.
    // Along the surface the residual is mostly the target's sampling, which s_j models.
    double across_sum = 0.0;
    size_t with_normal = 0;
    for (size_t i = 0; i < c.size(); ++i) {
      if (!(c.normal[i].squaredNorm() > 0.0)) continue;
      double across = 0.0, along = 0.0;
      splitSquaredResidual(c.target_mean[i] - T_target_source * c.source[i], c.normal[i], &across,
                           &along);
      across_sum += c.weight[i] * across + c.spread_across[i];
      ++with_normal;
    }
    if (with_normal >= std::max(kMinimumSurfacePoints, c.size() / 10) &&
        c.inlier_total_with_normal > 0.0) {
      return across_sum / c.inlier_total_with_normal;
    }
  }
  if (!(c.inlier_total > 0.0)) return 0.0;
  return weightedObjective(c, T_target_source) / (kDimension * c.inlier_total);
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
