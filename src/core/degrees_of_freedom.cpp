#include "pda_registration/core/degrees_of_freedom.hpp"

#include <algorithm>
#include <cmath>

namespace pda_registration {

bool nuEstimatedAtFloor(const RegistrationParameters& p, double nu) {
  return p.nu_mode != NuMode::kFixed && nu <= kMinDegreesOfFreedom;
}

double digamma(double x) {
  // Recurrence psi(x) = psi(x + 1) - 1/x up to x >= 10, then the asymptotic series to x^-8
  // (the next term is below 1e-12 there).
  double result = 0.0;
  while (x < 10.0) {
    result -= 1.0 / x;
    x += 1.0;
  }
  const double inverse = 1.0 / x, s = inverse * inverse;
  result += std::log(x) - 0.5 * inverse -
            s * (1.0 / 12.0 - s * (1.0 / 120.0 - s * (1.0 / 252.0 - s * (1.0 / 240.0))));
  return result;
}

double updateDegreesOfFreedom(double nu_old, double mean_log_u_minus_u, double dimension) {
  if (!std::isfinite(mean_log_u_minus_u) || !std::isfinite(nu_old)) return nu_old;
  const double half_old = 0.5 * (nu_old + dimension);
  const double constant = 1.0 + mean_log_u_minus_u + digamma(half_old) - std::log(half_old);
  // f(nu) = log(nu/2) - psi(nu/2) + constant decreases in nu (log x - psi(x) falls from +inf to 0).
  const auto f = [constant](double nu) {
    return std::log(0.5 * nu) - digamma(0.5 * nu) + constant;
  };
  double low = kMinDegreesOfFreedom, high = kMaxDegreesOfFreedom;
  if (f(high) >= 0.0) return high;  // tails as light as a Gaussian's
  if (f(low) <= 0.0) return low;
  for (int i = 0; i < 40; ++i) {  // bisection on log nu
    const double middle = std::sqrt(low * high);
    (f(middle) > 0.0 ? low : high) = middle;
  }
  return std::sqrt(low * high);
}

double nuOfEStep(double nu) {
  if (!std::isfinite(nu)) return nu;
  return std::clamp(0.25 * std::round(4.0 * nu), kMinDegreesOfFreedom, kMaxDegreesOfFreedom);
}

double walkDegreesOfFreedom(double nu, double e_step_nu, double mean_log_u_minus_u,
                            double dimension) {
  const double updated = updateDegreesOfFreedom(e_step_nu, mean_log_u_minus_u, dimension);
  if (updated <= kMinDegreesOfFreedom && e_step_nu <= kMinDegreesOfFreedom) {
    return kMinDegreesOfFreedom;
  }
  if (updated >= kMaxDegreesOfFreedom && e_step_nu >= kMaxDegreesOfFreedom) {
    return kMaxDegreesOfFreedom;
  }
  return std::clamp(nu + (updated - e_step_nu), kMinDegreesOfFreedom, kMaxDegreesOfFreedom);
}

}  // namespace pda_registration
