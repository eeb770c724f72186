// E-step weights against values worked out by hand from the paper's eqs. 19-21.
#include "pda_registration/core/association_weights.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

using pda_registration::computeCandidateWeights;

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
}

// nu = 5, d = 3, sigma^2 = 1, r^2 = {0, 1, 4}:
//   eq. 20: p ∝ (1 + r^2/5)^-4 = {1, 1.2^-4, 1.8^-4} = {1, 0.4822531, 0.0952599}, sum 1.5775130
//   P = {0.6339092, 0.3057047, 0.0603861}
//   eq. 16: E[w] = 8 / (5 + r^2) = {1.6, 1.3333333, 0.8888889}
//   eq. 21: w = P E[w] = {1.0142547, 0.4076062, 0.0536765}
TEST(AssociationWeights, StudentTMatchesHandComputation) {
  const double residuals[3] = {0.0, 1.0, 4.0};
  double posterior[3], weight[3];
  computeCandidateWeights(residuals, 3, 5.0, 1.0, posterior, weight);
  EXPECT_NEAR(posterior[0], 0.6339092, 1e-6);
  EXPECT_NEAR(posterior[1], 0.3057047, 1e-6);
  EXPECT_NEAR(posterior[2], 0.0603861, 1e-6);
  EXPECT_NEAR(weight[0], 1.0142547, 1e-6);
  EXPECT_NEAR(weight[1], 0.4076062, 1e-6);
  EXPECT_NEAR(weight[2], 0.0536765, 1e-6);
}

// Gaussian (eq. 19), r^2 = {0, 1, 4}: exp(-r^2/2) = {1, 0.6065307, 0.1353353}, sum 1.7418660,
// P = w = {0.5740970, 0.3482074, 0.0776956}.
TEST(AssociationWeights, GaussianMatchesHandComputation) {
  const double residuals[3] = {0.0, 1.0, 4.0};
  double posterior[3], weight[3];
  computeCandidateWeights(residuals, 3, kInf, 1.0, posterior, weight);
  EXPECT_NEAR(weight[0], 0.5740970, 1e-6);
  EXPECT_NEAR(weight[1], 0.3482074, 1e-6);
  EXPECT_NEAR(weight[2], 0.0776956, 1e-6);
  for (int i = 0; i < 3; ++i) EXPECT_DOUBLE_EQ(weight[i], posterior[i]);
}

// Sigma^2 enters as r^2/sigma^2: scaling residuals and sigma^2 together changes nothing.
TEST(AssociationWeights, DependOnlyOnResidualsOverSigma) {
  const double metres[3] = {0.0, 1.0, 4.0};
  const double millimetres[3] = {0.0, 1e6, 4e6};
  double p1[3], w1[3], p2[3], w2[3];
  computeCandidateWeights(metres, 3, 5.0, 1.0, p1, w1);
  computeCandidateWeights(millimetres, 3, 5.0, 1e6, p2, w2);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(w1[i], w2[i], 1e-12);
}

TEST(AssociationWeights, PosteriorSumsToOneAndLargeNuApproachesGaussian) {
  const double residuals[4] = {0.3, 2.0, 9.0, 0.01};
  double p_t[4], w_t[4], p_g[4], w_g[4];
  computeCandidateWeights(residuals, 4, 1e7, 0.5, p_t, w_t);
  computeCandidateWeights(residuals, 4, kInf, 0.5, p_g, w_g);
  double sum = 0.0;
  for (int i = 0; i < 4; ++i) {
    sum += p_t[i];
    EXPECT_NEAR(w_t[i], w_g[i], 1e-5);
  }
  EXPECT_NEAR(sum, 1.0, 1e-12);
}

// Far candidates must not underflow every weight to zero (log-domain normalisation).
TEST(AssociationWeights, TinySigmaStaysFinite) {
  const double residuals[2] = {1.0, 1.5};
  double posterior[2], weight[2];
  computeCandidateWeights(residuals, 2, kInf, 1e-6, posterior, weight);
  EXPECT_NEAR(posterior[0], 1.0, 1e-12);
  EXPECT_TRUE(std::isfinite(weight[1]));
}

// The outlier-downweighting of eq. 16: a far candidate of a lone source point gets
// P = 1 but a small expected precision.
TEST(AssociationWeights, LoneFarCandidateIsDownWeightedByStudentT) {
  const double residuals[1] = {100.0};
  double posterior[1], weight[1];
  computeCandidateWeights(residuals, 1, 5.0, 1.0, posterior, weight);
  EXPECT_DOUBLE_EQ(posterior[0], 1.0);
  EXPECT_NEAR(weight[0], 8.0 / 105.0, 1e-12);
}
