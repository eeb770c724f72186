#include "pda_registration/tools/calibration_odds.hpp"

#include <algorithm>
#include <random>

namespace pda_registration {

double OutsideOdds::medianOf(size_t draws) const {
  if (draws == 0) return 0.0;
  const size_t needed = draws / 2 + 1;  // odd: the middle one; even: both middle ones
  return chanceOfAtLeast(std::vector<double>(draws, below), needed) +
         chanceOfAtLeast(std::vector<double>(draws, above), needed);
}

OutsideOdds calibratedOutsideOdds(const Eigen::Vector3d& eigenvalues, double low, double high) {
  const Eigen::Vector3d weights = eigenvalues.cwiseMax(0.0) / eigenvalues.cwiseMax(0.0).sum();
  constexpr int kDraws = 100000;
  std::mt19937_64 random(20261129);  // fixed: a report must not change between runs
  std::normal_distribution<double> gauss(0.0, 1.0);
  const double below = low * low, above = high * high;
  int below_low = 0, above_high = 0;
  for (int i = 0; i < kDraws; ++i) {
    double squared = 0.0;
    for (int axis = 0; axis < 3; ++axis) {
      const double z = gauss(random);
      squared += weights[axis] * z * z;
    }
    if (squared < below) ++below_low;
    if (squared > above) ++above_high;
  }
  return {static_cast<double>(below_low) / kDraws, static_cast<double>(above_high) / kDraws};
}

double chanceOfAtLeast(const std::vector<double>& probabilities, size_t count) {
  // exactly[k]: the probability that k of the events so far happened.
  std::vector<double> exactly(probabilities.size() + 1, 0.0);
  exactly[0] = 1.0;
  for (size_t n = 0; n < probabilities.size(); ++n) {
    const double p = std::clamp(probabilities[n], 0.0, 1.0);
    for (size_t k = n + 1; k > 0; --k) exactly[k] = exactly[k] * (1.0 - p) + exactly[k - 1] * p;
    exactly[0] *= 1.0 - p;
  }
  double tail = 0.0;
  for (size_t k = count; k < exactly.size(); ++k) tail += exactly[k];
  return std::min(tail, 1.0);
}

}  // namespace pda_registration
