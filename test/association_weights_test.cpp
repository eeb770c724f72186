// E-step weights against values worked out by hand from the paper's eqs. 19-21.
#include "pda_registration/core/association_weights.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "pda_registration/core/degrees_of_freedom.hpp"
#include "pda_registration/core/noise_model.hpp"

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

// Posteriors and weights within `relative` of eqs. 16 and 20 in double precision, log E[w]
// within 1e-6, for candidates near and far (the farthest, below 1e-16 of the best, may be dropped).
void expectWeightsOfTheFormula(double nu, double relative) {
  const double residuals[5] = {0.02, 0.5, 3.0, 40.0, 1e9};
  double posterior[5], weight[5], log_precision[5];
  computeCandidateWeights(residuals, 5, nu, 0.7, posterior, weight, log_precision);
  double density[5], total = 0.0;
  for (int i = 0; i < 5; ++i) {
    density[i] = std::pow(1.0 + residuals[i] / 0.7 / nu, -0.5 * (nu + 3.0));
    total += density[i];
  }
  for (int i = 0; i < 5; ++i) {
    const double precision = (nu + 3.0) / (nu + residuals[i] / 0.7);
    const double expected = density[i] / total;
    EXPECT_NEAR(posterior[i], expected, relative * expected + 1e-15) << "nu " << nu << " i " << i;
    EXPECT_NEAR(weight[i], expected * precision, relative * expected * precision + 1e-15);
    if (expected > 1e-12) {
      EXPECT_NEAR(log_precision[i], std::log(precision), 1e-6) << "nu " << nu << " i " << i;
    }
  }
}

// A nu off the grid below (a user's fixed 2.6, say): the E-step takes single-precision logs (and,
// with nu's statistic, log E[w] from the same log). A small, a middling and a huge nu.
TEST(AssociationWeights, NonIntegerNuMatchesTheDoublePrecisionFormula) {
  for (const double nu : {1.37, 2.6, 17.3, 1e7 + 0.5}) expectWeightsOfTheFormula(nu, 1e-6);
}

// The quarter-unit grid an estimated nu is weighed on (degrees_of_freedom.hpp): (nu + 3) / 2 a
// multiple of 1/8, its power by products and square roots, nu's statistic by one log a candidate.
TEST(AssociationWeights, QuarterUnitNuMatchesTheDoublePrecisionFormula) {
  for (const double nu : {1.0, 1.25, 1.5, 1.75, 2.0, 2.25, 3.5, 12.75, 60.0}) {
    expectWeightsOfTheFormula(nu, 1e-12);
  }
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

// The E-step's reduction (association_weights.hpp): per source point, W |y_bar - z|^2_M + S equals
// sum_k rho_k |y_k - z|^2_M for any z, with S split across and along the surface. Checked against
// the candidates one by one, for every weighting form, on a map 2 km from its origin (the spread
// is taken from sums about the source point, which must not cancel there).
TEST(AssociationWeights, ReducedCorrespondencesKeepEveryCandidatesObjective) {
  using pda_registration::Point;
  std::mt19937 random(7);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const Point far(2000.0, -1500.0, 30.0);
  pda_registration::PointList source;
  pda_registration::CandidateSets candidates;
  pda_registration::NoiseShapes shapes;
  candidates.offsets.push_back(0);
  for (int j = 0; j < 40; ++j) {
    const Point x = far + 5.0 * Point(unit(random), unit(random), unit(random));
    source.push_back(x);
    const int count = 1 + j % 6;
    for (int c = 0; c < count; ++c) {
      candidates.points.push_back(x + 0.2 * Point(unit(random), unit(random), unit(random)));
      candidates.target_indices.push_back(candidates.target_indices.size());
    }
    candidates.offsets.push_back(candidates.points.size());
    // Every third point has no normal (an isotropic shape).
    shapes.normal.push_back(j % 3 == 0 ? Point::Zero()
                                       : Point(unit(random), unit(random), 1.0).normalized());
    shapes.inverse_kappa.push_back(j % 3 == 0 ? 1.0 : 0.01 + 0.5 * (unit(random) + 1.0));
  }
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translate(Point(0.01, -0.02, 0.005));
  T.rotate(Eigen::AngleAxisd(0.002, Point::UnitZ()));
  const double sigma_squared = 0.01;
  for (const double nu : {kInf, 5.0, 3.7}) {
    pda_registration::EStepBuffers buffers;
    buffers.nu_statistic = true;
    pda_registration::WeightedCorrespondences reduced;
    pda_registration::computeWeightedCorrespondences(source, candidates, shapes, T, nu,
                                                     sigma_squared, 1, &buffers, &reduced);
    ASSERT_EQ(reduced.size(), source.size());
    for (size_t j = 0; j < source.size(); ++j) {
      const size_t first = candidates.offsets[j], count = candidates.candidateCount(j);
      const Point x = T * source[j];
      const Point& n = shapes.normal[j];
      const double inverse_kappa = shapes.inverse_kappa[j];
      std::vector<double> residuals(count), posterior(count), rho(count), log_precision(count);
      for (size_t c = 0; c < count; ++c) {
        residuals[c] =
            pda_registration::shapedSquaredNorm(candidates.points[first + c] - x, n, inverse_kappa);
      }
      // With nu's statistic, as the E-step above computes it (the same form of the weights).
      computeCandidateWeights(residuals.data(), count, nu, sigma_squared, posterior.data(),
                              rho.data(), log_precision.data());
      double w = 0.0;
      Point mean = Point::Zero();
      for (size_t c = 0; c < count; ++c) {
        w += rho[c];
        mean += rho[c] * candidates.points[first + c];
      }
      mean /= w;
      double across = 0.0, along = 0.0;
      for (size_t c = 0; c < count; ++c) {
        double a = 0.0, b = 0.0;
        pda_registration::splitSquaredResidual(candidates.points[first + c] - mean, n, &a, &b);
        across += rho[c] * a;
        along += rho[c] * b;
      }
      const double scale = w * 0.04;  // rho times the candidates' squared spread (0.2 m)
      EXPECT_NEAR(reduced.weight[j], w, 1e-12 * w);
      EXPECT_LT((reduced.target_mean[j] - mean).norm(), 1e-9);
      EXPECT_NEAR(reduced.spread_across[j], across, 1e-12 * scale) << "nu " << nu << " j " << j;
      EXPECT_NEAR(reduced.spread_along[j], along, 1e-12 * scale) << "nu " << nu << " j " << j;
      // The identity itself, at a pose other than the E-step's.
      const Point z = source[j] + Point(0.03, 0.01, -0.02);
      double direct = 0.0;
      for (size_t c = 0; c < count; ++c) {
        direct += rho[c] * pda_registration::shapedSquaredNorm(candidates.points[first + c] - z, n,
                                                               inverse_kappa);
      }
      const double from_reduced =
          reduced.weight[j] *
              pda_registration::shapedSquaredNorm(reduced.target_mean[j] - z, n, inverse_kappa) +
          reduced.spread_across[j] + inverse_kappa * reduced.spread_along[j];
      EXPECT_NEAR(from_reduced, direct, 1e-10 * direct);
    }
  }
}

// nu's ECM update (degrees_of_freedom.hpp).
TEST(DegreesOfFreedom, DigammaMatchesKnownValues) {
  using pda_registration::digamma;
  EXPECT_NEAR(digamma(1.0), -0.5772156649015329, 1e-10);  // -Euler's gamma
  EXPECT_NEAR(digamma(0.5), -1.9635100260214235, 1e-10);  // -gamma - 2 ln 2
  EXPECT_NEAR(digamma(10.0), 2.2517525890667211, 1e-10);
}

// Residuals drawn from a 3-d Student-t with nu degrees of freedom (one candidate per point, so
// P(a) = 1): iterating the update as EM does lands near nu, and Gaussian residuals go towards the
// upper bound.
double estimatedNu(double true_nu, double start_nu) {
  std::mt19937_64 generator(11);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::vector<double> squared(50000);
  for (double& m : squared) {
    const double scale =
        std::isinf(true_nu)
            ? 1.0
            : std::gamma_distribution<double>(0.5 * true_nu, 2.0 / true_nu)(generator);
    double r2 = 0.0;
    for (int i = 0; i < 3; ++i) r2 += std::pow(normal(generator), 2);
    m = r2 / scale;
  }
  double nu = start_nu;
  for (int iteration = 0; iteration < 50; ++iteration) {
    double statistic = 0.0;
    for (double m : squared) {
      const double u = (nu + 3.0) / (nu + m);
      statistic += std::log(u) - u;
    }
    nu = pda_registration::updateDegreesOfFreedom(nu, statistic / squared.size(), 3.0);
  }
  return nu;
}

// The walk with its E-steps on the quarter-unit grid (walkDegreesOfFreedom) against the walk with
// them at nu itself, from the same start: step for step within the grid's reach, to the same end,
// and onto the floor when the tails are heavier than it allows (the rules that read the floor
// need it reached, not held a grid step above).
std::vector<std::pair<double, double>> walksSideBySide(double true_nu, double start_nu,
                                                        int iterations) {
  std::mt19937_64 generator(11);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::vector<double> squared(50000);
  for (double& m : squared) {
    const double scale = std::gamma_distribution<double>(0.5 * true_nu, 2.0 / true_nu)(generator);
    double r2 = 0.0;
    for (int i = 0; i < 3; ++i) r2 += std::pow(normal(generator), 2);
    m = r2 / scale;
  }
  const auto statistic = [&](double nu) {
    double sum = 0.0;
    for (double m : squared) {
      const double u = (nu + 3.0) / (nu + m);
      sum += std::log(u) - u;
    }
    return sum / squared.size();
  };
  std::vector<std::pair<double, double>> walks;
  double exact = start_nu, on_grid = start_nu;
  for (int iteration = 0; iteration < iterations; ++iteration) {
    exact = pda_registration::updateDegreesOfFreedom(exact, statistic(exact), 3.0);
    const double e_step_nu = pda_registration::nuOfEStep(on_grid);
    on_grid = pda_registration::walkDegreesOfFreedom(on_grid, e_step_nu, statistic(e_step_nu), 3.0);
    walks.emplace_back(exact, on_grid);
  }
  return walks;
}

TEST(DegreesOfFreedom, WalkOnTheQuarterUnitGridKeepsThePace) {
  using pda_registration::nuOfEStep;
  EXPECT_EQ(nuOfEStep(2.12), 2.0);
  EXPECT_EQ(nuOfEStep(2.13), 2.25);
  EXPECT_EQ(nuOfEStep(0.3), pda_registration::kMinDegreesOfFreedom);
  EXPECT_EQ(nuOfEStep(100.0), pda_registration::kMaxDegreesOfFreedom);
  for (const auto& [exact, on_grid] : walksSideBySide(2.0, 5.0, 60)) {
    EXPECT_NEAR(on_grid, exact, 0.1 * exact);
  }
  const auto to_floor = walksSideBySide(0.9, 5.0, 150);
  EXPECT_EQ(to_floor.back().first, pda_registration::kMinDegreesOfFreedom);
  EXPECT_EQ(to_floor.back().second, pda_registration::kMinDegreesOfFreedom);
}

TEST(DegreesOfFreedom, EmUpdateRecoversTheTailsOfTheData) {
  EXPECT_NEAR(estimatedNu(4.0, 20.0), 4.0, 1.0);
  EXPECT_NEAR(estimatedNu(10.0, 2.0), 10.0, 2.0);
  EXPECT_GT(estimatedNu(kInf, 5.0), 30.0);  // towards the bound: a flat likelihood, slow steps
  // A statistic that is not a number leaves nu as it was.
  EXPECT_EQ(pda_registration::updateDegreesOfFreedom(7.0, std::nan(""), 3.0), 7.0);
}
