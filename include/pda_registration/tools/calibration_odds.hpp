#pragma once
// How often a perfectly calibrated covariance would still put an error outside an accepted range
// of |error| / sigma, sigma = sqrt(trace) of a 3x3 block (pda_covariance_check's rule). For an
// error drawn from N(0, C), |error|^2 / trace C = sum_i w_i z_i^2 with w_i = C's eigenvalues over
// their sum and z_i standard normal: it is 1 on average, but one draw spreads widely, the more so
// the more one direction holds the variance (one direction alone: below 0.5 with probability
// 0.38; three equal ones: 0.14). One such draw is what a table row of one scene holds, so these
// odds say whether a row outside the range is evidence against the covariance or chance.

#include <Eigen/Core>
#include <cstddef>
#include <vector>

namespace pda_registration {

/// The odds that |error| / sigma falls below `low` or above `high` for an error from N(0, C),
/// C with these eigenvalues (any scale, none negative, not all zero). A fixed-seed Monte Carlo of
/// 100000 draws: the same answer on every call, within about 0.002 of the exact one.
struct OutsideOdds {
  double below = 0.0, above = 0.0;
  double either() const { return below + above; }
  /// The same odds for the median of `draws` independent such errors (a row that pools noise
  /// draws whose errors are independent; the middle two must both be out for an even count).
  double medianOf(size_t draws) const;
};
OutsideOdds calibratedOutsideOdds(const Eigen::Vector3d& eigenvalues, double low, double high);

/// The probability that at least `count` of independent events with these probabilities happen
/// (the Poisson-binomial tail).
double chanceOfAtLeast(const std::vector<double>& probabilities, size_t count);

}  // namespace pda_registration
