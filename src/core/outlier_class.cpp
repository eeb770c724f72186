#include "pda_registration/core/outlier_class.hpp"

#include <algorithm>
#include <cmath>

namespace pda_registration {

OutlierClass outlierClassFor(double share, double radius, double nu) {
  OutlierClass outliers;
  if (!(radius > 0.0)) return outliers;
  const double w = std::clamp(share, 1e-3, 0.999);
  outliers.odds = w / (1.0 - w) / (2.0 * radius);
  outliers.log_constant = std::isinf(nu) ? -0.5 * std::log(2.0 * M_PI)
                                         : std::lgamma(0.5 * (nu + 1.0)) - std::lgamma(0.5 * nu) -
                                               0.5 * std::log(nu * M_PI);
  return outliers;
}

double inlierResponsibility(const OutlierClass& outliers, double nu, double best_mahalanobis,
                            double log_across_variance, double relative_density_mean) {
  if (!outliers.on()) return 1.0;
  const double log_kernel = std::isinf(nu) ? -0.5 * best_mahalanobis
                                           : -0.5 * (nu + 3.0) * std::log1p(best_mahalanobis / nu);
  const double log_inlier = outliers.log_constant - 0.5 * log_across_variance + log_kernel +
                            std::log(relative_density_mean);
  return 1.0 / (1.0 + outliers.odds * std::exp(-log_inlier));
}

}  // namespace pda_registration
