#include "pda_registration/core/association_weights.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "pda_registration/core/noise_model.hpp"

namespace pda_registration {
namespace {

constexpr double kDimension = 3.0;
// Fewer source points on a known surface than this (or a tenth): sigma from the whole residual.
constexpr size_t kMinimumSurfacePoints = 10;
constexpr double kNegligibleDensity = 1e-16;

// base^exponent for base in (0, 1] by repeated multiplication, when 2 * exponent is a small
// integer (nu = 1, 2, 3, ... give (nu + 3) / 2 of that form): a fixed nu's common case. The form
// is decided once per source point, not per candidate.
class IntegerPower {
 public:
  explicit IntegerPower(double exponent) {
    const double twice = 2.0 * exponent;
    applies_ = twice > 0.0 && twice <= 64.0 && twice == std::floor(twice);
    if (applies_) {
      whole_ = static_cast<int>(exponent);
      half_ = (twice - 2.0 * whole_) > 0.5;
    }
  }

  bool applies() const { return applies_; }

  double operator()(double base) const {
    double result = half_ ? std::sqrt(base) : 1.0;
    double square = base;
    for (int bits = whole_; bits > 0; bits >>= 1) {
      if (bits & 1) result *= square;
      square *= square;
    }
    return result;
  }

 private:
  bool applies_ = false;
  int whole_ = 0;
  bool half_ = false;
};

// log1p and exp for the E-step's non-integer powers, x >= 0: single precision (about 1e-7 relative
// error in a posterior, far below anything EM resolves) at half the cost of the double calls.
// Near 0, where 1 + x in single precision would lose x (a large nu), the series to x^3 (error
// below x^4 / 4 <= 2.5e-13).
double fastLog1p(double x) {
  if (x < 1e-3) return x * (1.0 - x * (0.5 - x / 3.0));
  return std::log(static_cast<float>(1.0 + x));
}
double fastExp(double x) { return std::exp(static_cast<float>(x)); }

// The E-step's weights for one nu and sigma^2: what depends only on them is taken once per
// E-step, not once per source point (the negligible-density cut costs an exp and a log).
class CandidateWeighting {
 public:
  CandidateWeighting(double nu, double sigma_squared, bool log_precision)
      : nu_(nu),
        gaussian_(std::isinf(nu)),
        inverse_sigma_squared_(1.0 / sigma_squared),
        exponent_(0.5 * (nu + kDimension)),
        power_(exponent_),
        // An estimated nu is not an integer: pow would cost a log and an exp per candidate, and
        // nu's statistic another log. One log of nu + m_i serves both (the E-step's most
        // expensive part).
        by_logarithm_(!gaussian_ && (log_precision || !power_.applies())),
        // Candidates whose density is below 1e-16 of the best's add nothing a double can hold to
        // the normalisation: their posterior is 0, without a log or an exp.
        negligible_ratio_(by_logarithm_ ? std::exp(-std::log(kNegligibleDensity) / exponent_) - 1.0
                                        : 0.0) {}

  // Writes the candidates' unnormalised posteriors (relative to the best candidate's) and expected
  // precisions, and returns the posteriors' sum. weight[i] * posterior[i] / sum is rho_i.
  double unnormalised(const double* squared_residuals, size_t count, double* posterior,
                      double* weight, double* log_precision) const {
    if (count == 0) return 0.0;
    const double nu = nu_;
    // weight[] holds the Mahalanobis distances until the last loop. Divisions are taken once per
    // candidate: the E-step runs over every candidate of every EM iteration.
    double best = std::numeric_limits<double>::infinity();
    for (size_t i = 0; i < count; ++i) {
      weight[i] = squared_residuals[i] * inverse_sigma_squared_;
      best = std::min(best, weight[i]);
    }
    // Densities are taken relative to the best candidate's, so tiny sigmas cannot underflow every
    // candidate to zero: for the t (eq. 20) p_i / p_best = ((nu + m_best) / (nu + m_i))^((nu+d)/2).
    // log((nu + m_i) / (nu + m_best)) = log1p((m_i - m_best) / (nu + m_best)): exact for large nu
    // too.
    const double inverse_best = 1.0 / (nu + best);
    const double log_best_precision =
        log_precision && by_logarithm_ ? std::log((nu + kDimension) * inverse_best) : 0.0;
    double total = 0.0;
    for (size_t i = 0; i < count; ++i) {
      const double mahalanobis = weight[i];
      if (gaussian_) {
        posterior[i] = std::exp(-0.5 * (mahalanobis - best));  // eq. 19
        weight[i] = 1.0;
      } else if (by_logarithm_) {
        const double excess = (mahalanobis - best) * inverse_best;
        if (excess > negligible_ratio_) {
          posterior[i] = 0.0;
          weight[i] = 0.0;
          if (log_precision) log_precision[i] = 0.0;
          continue;
        }
        const double log_ratio = fastLog1p(excess);
        posterior[i] = fastExp(-exponent_ * log_ratio);      // eq. 20
        weight[i] = (nu + kDimension) / (nu + mahalanobis);  // expected precision, eq. 16
        if (log_precision) log_precision[i] = log_best_precision - log_ratio;
      } else {
        const double inverse = 1.0 / (nu + mahalanobis);
        posterior[i] = power_((nu + best) * inverse);  // eq. 20
        weight[i] = (nu + kDimension) * inverse;       // expected precision, eq. 16
      }
      total += posterior[i];
    }
    return total;
  }

  void operator()(const double* squared_residuals, size_t count, double* posterior, double* weight,
                  double* log_precision) const {
    if (count == 0) return;
    const double inverse_total =
        1.0 / unnormalised(squared_residuals, count, posterior, weight, log_precision);
    for (size_t i = 0; i < count; ++i) {
      posterior[i] *= inverse_total;
      weight[i] *= posterior[i];  // eqs. 15, 21
    }
  }

 private:
  double nu_;
  bool gaussian_;
  double inverse_sigma_squared_;
  double exponent_;
  IntegerPower power_;
  bool by_logarithm_;
  double negligible_ratio_;
};

}  // namespace

void computeCandidateWeights(const double* squared_residuals, size_t count, double nu,
                             double sigma_squared, double* posterior, double* weight,
                             double* log_precision) {
  const CandidateWeighting weighting(nu, sigma_squared, log_precision != nullptr);
  weighting(squared_residuals, count, posterior, weight, log_precision);
}

void computeWeightedCorrespondences(const PointList& source, const CandidateSets& candidates,
                                    const NoiseShapes& shapes,
                                    const Eigen::Isometry3d& T_target_source, double nu,
                                    double sigma_squared, int threads, EStepBuffers* buffers,
                                    WeightedCorrespondences* out_correspondences) {
  const size_t n = candidates.sourceCount();
  // Per-source results are written to fixed slots in parallel and compacted serially, so the
  // sums (and therefore the estimate) are the same for any thread count.
  PointList& means = buffers->means;
  std::vector<double>& weights = buffers->weights;
  std::vector<double>& across = buffers->across;
  std::vector<double>& along = buffers->along;
  std::vector<double>& log_u_minus_u = buffers->log_u_minus_u;
  // Only a positive weight marks a slot as written (and the others are read only then).
  weights.assign(n, 0.0);
  means.resize(n);
  across.resize(n);
  along.resize(n);
  log_u_minus_u.resize(n);
  const bool nu_statistic = buffers->nu_statistic && !std::isinf(nu);
  const CandidateWeighting weighting(nu, sigma_squared, nu_statistic);
  const bool second_moments = buffers->second_moments;
  std::vector<Eigen::Matrix3d>& moments = buffers->moments;
  if (second_moments) moments.resize(n);

#pragma omp parallel num_threads(std::max(threads, 1))
  {
    // Per-candidate scratch: on the stack for the usual few candidates, else in vectors.
    constexpr size_t kOnStack = 32;
    double stack[4 * kOnStack];
    std::vector<double> heap;
#pragma omp for schedule(dynamic, 256)
    for (long long j = 0; j < static_cast<long long>(n); ++j) {
      const size_t count = candidates.candidateCount(j);
      if (count == 0) continue;
      const Point* y = &candidates.points[candidates.offsets[j]];
      double* residuals = stack;
      if (count > kOnStack) {
        heap.resize(4 * count);
        residuals = heap.data();
      }
      double* posterior = residuals + count;
      double* rho = posterior + count;
      double* log_u = rho + count;
      const Point x = T_target_source * source[j];
      const Point normal = shapes.normalAt(j);
      const double inverse_kappa = shapes.inverseKappaAt(j);
      for (size_t i = 0; i < count; ++i) {
        residuals[i] = shapedSquaredNorm(y[i] - x, normal, inverse_kappa);
      }
      // The normalisation, rho_i = P(a_i) u_i and the sums in one pass.
      const double inverse_total = 1.0 / weighting.unnormalised(residuals, count, posterior, rho,
                                                                nu_statistic ? log_u : nullptr);
      double w = 0.0, precision_term = 0.0;
      Point mean = Point::Zero();
      for (size_t i = 0; i < count; ++i) {
        posterior[i] *= inverse_total;
        rho[i] *= posterior[i];  // eqs. 15, 21
        w += rho[i];
        mean += rho[i] * y[i];
        // P(a_i) (log u_i - u_i), with P(a_i) u_i = rho_i.
        if (nu_statistic) precision_term += posterior[i] * log_u[i] - rho[i];
      }
      if (!(w > 0.0)) continue;
      mean /= w;
      double spread_across = 0.0, spread_along = 0.0;
      for (size_t i = 0; i < count; ++i) {
        double a = 0.0, b = 0.0;
        splitSquaredResidual(y[i] - mean, normal, &a, &b);
        spread_across += rho[i] * a;
        spread_along += rho[i] * b;
      }
      if (second_moments) {
        // sum_i P(a_i) u_i^2 r_i r_i^T, u_i = rho_i / P(a_i): the association's and the
        // t-weight's share of the observed information (pose_covariance.hpp).
        Eigen::Matrix3d moment = Eigen::Matrix3d::Zero();
        for (size_t i = 0; i < count; ++i) {
          if (!(posterior[i] > 0.0)) continue;
          const Point r = y[i] - x;
          moment.noalias() += (rho[i] * rho[i] / posterior[i]) * r * r.transpose();
        }
        moments[j] = moment;
      }
      means[j] = mean;
      weights[j] = w;
      across[j] = spread_across;
      along[j] = spread_along;
      log_u_minus_u[j] = precision_term;
    }
  }

  WeightedCorrespondences& out = *out_correspondences;
  out.sampling = shapes.sampling;
  out.source_index.clear();
  out.source.clear();
  out.target_mean.clear();
  out.weight.clear();
  out.normal.clear();
  out.inverse_kappa.clear();
  out.spread_across.clear();
  out.spread_along.clear();
  out.second_moment.clear();
  double precision_sum = 0.0;
  for (size_t j = 0; j < n; ++j) {
    if (!(weights[j] > 0.0)) continue;
    precision_sum += log_u_minus_u[j];
    out.source_index.push_back(j);
    out.source.push_back(source[j]);
    out.target_mean.push_back(means[j]);
    out.weight.push_back(weights[j]);
    out.normal.push_back(shapes.normalAt(j));
    out.inverse_kappa.push_back(shapes.inverseKappaAt(j));
    out.spread_across.push_back(across[j]);
    out.spread_along.push_back(along[j]);
    if (second_moments) out.second_moment.push_back(moments[j]);
  }
  out.mean_log_u_minus_u = out.size() == 0 ? 0.0 : precision_sum / static_cast<double>(out.size());
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
    if (with_normal >= std::max(kMinimumSurfacePoints, c.size() / 10)) {
      return across_sum / static_cast<double>(with_normal);
    }
  }
  return weightedObjective(c, T_target_source) / (kDimension * static_cast<double>(c.size()));
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
