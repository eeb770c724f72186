// The odds that a calibrated covariance still puts one error outside a range of |error| / sigma
// (calibration_odds.hpp), against closed forms: |error|^2 / sigma^2 is chi-square with as many
// degrees of freedom as equal eigenvalues, over that number.
#include "pda_registration/tools/calibration_odds.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace pda_registration {
namespace {

// P(|z| < x) for a standard normal z.
double normalWithin(double x) { return std::erf(x / std::sqrt(2.0)); }

TEST(CalibrationOdds, OneDirectionIsANormalDeviate) {
  // sigma is that direction's standard deviation: |error| / sigma = |z|.
  const OutsideOdds odds = calibratedOutsideOdds(Eigen::Vector3d(2.0, 0.0, 0.0), 0.5, 2.0);
  EXPECT_NEAR(odds.below, normalWithin(0.5), 0.005);        // 0.383
  EXPECT_NEAR(odds.above, 1.0 - normalWithin(2.0), 0.003);  // 0.046
}

TEST(CalibrationOdds, TwoEqualDirectionsAreChiSquareWithTwoDegrees) {
  // chi-square with 2 degrees of freedom is exponential: P(chi2 / 2 < x^2) = 1 - exp(-x^2).
  const OutsideOdds odds = calibratedOutsideOdds(Eigen::Vector3d(0.0, 1.0, 1.0), 0.5, 2.0);
  EXPECT_NEAR(odds.below, 1.0 - std::exp(-0.25), 0.005);  // 0.221
  EXPECT_NEAR(odds.above, std::exp(-4.0), 0.003);         // 0.018
}

TEST(CalibrationOdds, ThreeEqualDirectionsAreChiSquareWithThreeDegrees) {
  // P(chi2_3 < 3 x^2) = erf(u / sqrt 2) - sqrt(2 / pi) u exp(-u^2 / 2), u = sqrt(3) x.
  auto cdf = [](double x) {
    const double u = std::sqrt(3.0) * x;
    return normalWithin(u) - std::sqrt(2.0 / M_PI) * u * std::exp(-0.5 * u * u);
  };
  const OutsideOdds odds = calibratedOutsideOdds(Eigen::Vector3d(3.0, 3.0, 3.0), 0.5, 2.0);
  EXPECT_NEAR(odds.below, cdf(0.5), 0.005);        // 0.139
  EXPECT_NEAR(odds.above, 1.0 - cdf(2.0), 0.002);  // 0.007
  // One direction holding the variance misses far more often than three sharing it.
  EXPECT_GT(calibratedOutsideOdds(Eigen::Vector3d(1.0, 0.0, 0.0), 0.5, 2.0).either(),
            2.5 * odds.either());
}

TEST(CalibrationOdds, TheSameAnswerOnEveryCall) {
  const Eigen::Vector3d shares(0.7, 0.2, 0.1);
  EXPECT_EQ(calibratedOutsideOdds(shares, 0.5, 2.0).below,
            calibratedOutsideOdds(shares, 0.5, 2.0).below);
}

TEST(CalibrationOdds, TheMedianOfIndependentDrawsMissesLessOften) {
  const OutsideOdds odds{0.3, 0.05};
  EXPECT_DOUBLE_EQ(odds.medianOf(1), 0.35);
  // Three draws: at least two of them below (or above).
  auto twoOfThree = [](double p) { return 3.0 * p * p * (1.0 - p) + p * p * p; };
  EXPECT_NEAR(odds.medianOf(3), twoOfThree(0.3) + twoOfThree(0.05), 1e-12);
  EXPECT_LT(odds.medianOf(5), odds.medianOf(3));
  EXPECT_DOUBLE_EQ(odds.medianOf(0), 0.0);
}

TEST(CalibrationOdds, ChanceOfAtLeastIsThePoissonBinomialTail) {
  EXPECT_DOUBLE_EQ(chanceOfAtLeast({0.5, 0.5}, 0), 1.0);
  EXPECT_DOUBLE_EQ(chanceOfAtLeast({0.5, 0.5}, 1), 0.75);
  EXPECT_DOUBLE_EQ(chanceOfAtLeast({0.5, 0.5}, 2), 0.25);
  EXPECT_DOUBLE_EQ(chanceOfAtLeast({0.5, 0.5}, 3), 0.0);
  // 0.2, 0.4 and 0.9: at least two = 1 - P(none) - P(exactly one).
  const double none = 0.8 * 0.6 * 0.1;
  const double one = 0.2 * 0.6 * 0.1 + 0.8 * 0.4 * 0.1 + 0.8 * 0.6 * 0.9;
  EXPECT_NEAR(chanceOfAtLeast({0.2, 0.4, 0.9}, 2), 1.0 - none - one, 1e-12);
}

}  // namespace
}  // namespace pda_registration
