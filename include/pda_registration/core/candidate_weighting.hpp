#pragma once
// The per-candidate weights of the E-step (paper eqs. 14-16, 19-21) for one source point: the
// posterior association probabilities P(a_i) over its candidate set and the expected Student-t
// precisions E[w_i] (association_weights.hpp has the whole E-step). What depends only on nu and
// sigma^2 is taken once, when the object is made, because the E-step asks for every source point
// of every EM iteration; the object is inline so that the E-step's loop can fold it in.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>

namespace pda_registration {
namespace candidate_weighting_detail {

// base^exponent for base in (0, 1] by repeated multiplication and square roots, when 8 * exponent
// is a small integer: nu = 1, 1.25, 1.5, ... give (nu + 3) / 2 of that form (a fixed nu's common
// case, and the quarter-unit grid an estimated nu is weighed on: degrees_of_freedom.hpp). The
// form is decided once per E-step, not per candidate.
class IntegerPower {
 public:
  explicit IntegerPower(double exponent) {
    const double eighths = 8.0 * exponent;
    applies_ = eighths > 0.0 && eighths <= 256.0 && eighths == std::floor(eighths);
    if (applies_) {
      whole_ = static_cast<int>(exponent);
      eighths_ = static_cast<int>(eighths) - 8 * whole_;
    }
  }

  bool applies() const { return applies_; }

  double operator()(double base) const {
    // The fraction in eighths: the square root for a half, its root for a quarter, that one's
    // root for an eighth (the common half alone as before: one root).
    double result = 1.0;
    if (eighths_ != 0) {
      const double root = std::sqrt(base);
      if (eighths_ == 4) {
        result = root;
      } else {
        const double fourth_root = std::sqrt(root);
        result = (eighths_ & 4) ? root : 1.0;
        if (eighths_ & 2) result *= fourth_root;
        if (eighths_ & 1) result *= std::sqrt(fourth_root);
      }
    }
    // Exponents up to 4.5 (nu up to 6) written out: the loop's products in the loop's order,
    // without its branch per bit (the E-step takes one power per candidate).
    switch (whole_) {
      case 0:
        return result;
      case 1:
        return result * base;
      case 2:
        return result * (base * base);
      case 3:
        return (result * base) * (base * base);
      case 4: {
        const double square = base * base;
        return result * (square * square);
      }
      default:
        break;
    }
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
  int eighths_ = 0;  // exponent - whole_, in eighths
};

// log1p and exp for the E-step's non-integer powers, x >= 0: single precision (about 1e-7 relative
// error in a posterior, far below anything EM resolves) at half the cost of the double calls.
// Near 0, where 1 + x in single precision would lose x (a large nu), the series to x^3 (error
// below x^4 / 4 <= 2.5e-13).
inline double fastLog1p(double x) {
  if (x < 1e-3) return x * (1.0 - x * (0.5 - x / 3.0));
  return std::log(static_cast<float>(1.0 + x));
}
inline double fastExp(double x) { return std::exp(static_cast<float>(x)); }

}  // namespace candidate_weighting_detail

// The E-step's weights for one nu and sigma^2: what depends only on them is taken once per
// E-step, not once per source point (the negligible-density cut costs an exp and a log).
class CandidateWeighting {
 public:
  static constexpr double kDimension = 3.0;
  /// Candidates whose density is below this fraction of the best's get posterior 0.
  static constexpr double kNegligibleDensity = 1e-16;

  CandidateWeighting(double nu, double sigma_squared)
      : nu_(nu),
        gaussian_(std::isinf(nu)),
        inverse_sigma_squared_(1.0 / sigma_squared),
        exponent_(0.5 * (nu + kDimension)),
        power_(exponent_),
        // Any other nu costs a log and an exp per candidate (one log serving nu's statistic too):
        // an E-step twice as long as by products and square roots.
        by_logarithm_(!gaussian_ && !power_.applies()),
        // Candidates whose density is below 1e-16 of the best's add nothing a double can hold to
        // the normalisation: their posterior is 0, without a log or an exp.
        negligible_ratio_(by_logarithm_ ? std::exp(-std::log(kNegligibleDensity) / exponent_) - 1.0
                                        : 0.0) {}

  /// Which of the three forms the weights take for this nu: fixed for the E-step, so that its
  /// loop can be compiled once per form (unnormalisedAs), free of the others' branches.
  enum class Form {
    kGaussian,      ///< nu = infinity (eq. 19)
    kLogarithm,     ///< any other nu through one log and one exp (and nu's statistic)
    kIntegerPower,  ///< (nu + 3) / 2 a multiple of 1/2: repeated multiplication
  };
  double nu() const { return nu_; }
  double inverseSigmaSquared() const { return inverse_sigma_squared_; }
  Form form() const {
    return gaussian_ ? Form::kGaussian : (by_logarithm_ ? Form::kLogarithm : Form::kIntegerPower);
  }

  // Writes the candidates' unnormalised posteriors (relative to the best candidate's) and expected
  // precisions, and returns the posteriors' sum. weight[i] * posterior[i] / sum is rho_i.
  double unnormalised(const double* squared_residuals, size_t count, double* posterior,
                      double* weight, double* log_precision) const {
    switch (form()) {
      case Form::kGaussian:
        return unnormalisedAs<Form::kGaussian, false>(squared_residuals, count, posterior, weight,
                                                      nullptr);
      case Form::kIntegerPower:
        return log_precision ? unnormalisedAs<Form::kIntegerPower, true>(
                                   squared_residuals, count, posterior, weight, log_precision)
                             : unnormalisedAs<Form::kIntegerPower, false>(
                                   squared_residuals, count, posterior, weight, nullptr);
      case Form::kLogarithm:
        break;
    }
    return log_precision ? unnormalisedAs<Form::kLogarithm, true>(squared_residuals, count,
                                                                  posterior, weight, log_precision)
                         : unnormalisedAs<Form::kLogarithm, false>(squared_residuals, count,
                                                                   posterior, weight, nullptr);
  }

  /// unnormalised() for this object's form() (kForm must be it), writing log_precision only when
  /// kLogPrecision (kLogarithm only).
  template <Form kForm, bool kLogPrecision>
  double unnormalisedAs(const double* squared_residuals, size_t count, double* posterior,
                        double* weight, double* log_precision) const {
    static_assert(!kLogPrecision || kForm != Form::kGaussian, "nu's statistic is the t's");
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
        kLogPrecision ? std::log((nu + kDimension) * inverse_best) : 0.0;
    double total = 0.0;
    for (size_t i = 0; i < count; ++i) {
      const double mahalanobis = weight[i];
      if constexpr (kForm == Form::kGaussian) {
        posterior[i] = std::exp(-0.5 * (mahalanobis - best));  // eq. 19
        weight[i] = 1.0;
      } else if constexpr (kForm == Form::kLogarithm) {
        const double excess = (mahalanobis - best) * inverse_best;
        if (excess > negligible_ratio_) {
          posterior[i] = 0.0;
          weight[i] = 0.0;
          if constexpr (kLogPrecision) log_precision[i] = 0.0;
          continue;
        }
        const double log_ratio = candidate_weighting_detail::fastLog1p(excess);
        posterior[i] = candidate_weighting_detail::fastExp(-exponent_ * log_ratio);  // eq. 20
        weight[i] = (nu + kDimension) / (nu + mahalanobis);  // expected precision, eq. 16
        if constexpr (kLogPrecision) log_precision[i] = log_best_precision - log_ratio;
      } else {
        const double inverse = 1.0 / (nu + mahalanobis);
        posterior[i] = power_((nu + best) * inverse);  // eq. 20
        weight[i] = (nu + kDimension) * inverse;       // expected precision, eq. 16
        if constexpr (kLogPrecision) log_precision[i] = std::log(static_cast<float>(weight[i]));
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
  candidate_weighting_detail::IntegerPower power_;
  bool by_logarithm_;
  double negligible_ratio_;
};

}  // namespace pda_registration
