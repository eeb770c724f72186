// The M-step solvers minimise the same weighted objective: given the same weights they must land
// on the same transform, and recover it exactly from noise-free correspondences. And the
// extrapolation of the runs that the solver's steps feed.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <limits>
#include <random>
#include <vector>

#include "pda_registration/core/candidate_sets.hpp"
#include "pda_registration/core/ceres_solver.hpp"
#include "pda_registration/core/closed_form_solver.hpp"
#include "pda_registration/core/em_run.hpp"
#include "pda_registration/core/gauss_newton_solver.hpp"
#include "pda_registration/core/noise_shapes.hpp"
#include "pda_registration/core/pose_covariance.hpp"
#include "pda_registration/core/run_extrapolation.hpp"
#include "pda_registration/core/run_rest.hpp"
#include "pda_registration/core/target_index.hpp"

namespace pda_registration {
namespace {

Eigen::Isometry3d someTransform() {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  T.translation() = Eigen::Vector3d(0.5, -1.0, 0.25);
  return T;
}

// Correspondences y = T x + noise with random positive weights and random unit normals.
WeightedCorrespondences makeCorrespondences(const Eigen::Isometry3d& T, double noise,
                                            double inverse_kappa, int count, uint64_t seed) {
  std::mt19937_64 generator(seed);
  std::uniform_real_distribution<double> coordinate(-5.0, 5.0), weight(0.1, 2.0);
  std::normal_distribution<double> gaussian(0.0, 1.0);
  WeightedCorrespondences c;
  for (int i = 0; i < count; ++i) {
    const Point x(coordinate(generator), coordinate(generator), coordinate(generator));
    const Point n =
        Point(gaussian(generator), gaussian(generator), gaussian(generator)).normalized();
    c.source_index.push_back(i);
    c.source.push_back(x);
    c.target_mean.push_back(
        T * x + noise * Point(gaussian(generator), gaussian(generator), gaussian(generator)));
    c.weight.push_back(weight(generator));
    c.normal.push_back(n);
    c.inverse_kappa.push_back(inverse_kappa);
    c.spread_across.push_back(0.0);
    c.spread_along.push_back(0.0);
  }
  return c;
}

double rotationDistance(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  return Eigen::AngleAxisd(a.linear() * b.linear().transpose()).angle();
}

TEST(Solvers, AllRecoverAnExactTransform) {
  const Eigen::Isometry3d truth = someTransform();
  const WeightedCorrespondences c = makeCorrespondences(truth, 0.0, 1.0, 200, 1);
  Eigen::Isometry3d closed = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d newton = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d ceres = Eigen::Isometry3d::Identity();
  ASSERT_TRUE(solveClosedForm(c, &closed));
  ASSERT_TRUE(solveGaussNewton(c, 20, 0.0, 0.0, &newton));
  ASSERT_TRUE(solveWithCeres(c, 50, 1, &ceres));
  for (const Eigen::Isometry3d* T : {&closed, &newton, &ceres}) {
    EXPECT_LT((T->translation() - truth.translation()).norm(), 1e-8);
    EXPECT_LT(rotationDistance(*T, truth), 1e-8);
  }
}

// Isotropic model: the closed form is the exact minimiser; the iterative solvers must agree.
TEST(Solvers, AgreeOnTheIsotropicWeightedProblem) {
  const WeightedCorrespondences c = makeCorrespondences(someTransform(), 0.2, 1.0, 300, 2);
  Eigen::Isometry3d closed = Eigen::Isometry3d::Identity();
  ASSERT_TRUE(solveClosedForm(c, &closed));
  for (bool use_ceres : {false, true}) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    ASSERT_TRUE(use_ceres ? solveWithCeres(c, 100, 1, &T) : solveGaussNewton(c, 50, 0, 0, &T));
    EXPECT_LT((T.translation() - closed.translation()).norm(), 1e-6) << use_ceres;
    EXPECT_LT(rotationDistance(T, closed), 1e-6) << use_ceres;
    EXPECT_NEAR(weightedObjective(c, T), weightedObjective(c, closed),
                1e-9 * weightedObjective(c, closed));
  }
}

// Surface model (kappa = 100): Gauss-Newton and Ceres minimise the same anisotropic objective,
// and its minimum is no higher than the closed form's (which ignores the normals).
TEST(Solvers, GaussNewtonAndCeresAgreeOnTheSurfaceModel) {
  const WeightedCorrespondences c = makeCorrespondences(someTransform(), 0.2, 0.01, 300, 3);
  Eigen::Isometry3d newton = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d ceres = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d closed = Eigen::Isometry3d::Identity();
  ASSERT_TRUE(solveGaussNewton(c, 50, 0, 0, &newton));
  ASSERT_TRUE(solveWithCeres(c, 100, 1, &ceres));
  ASSERT_TRUE(solveClosedForm(c, &closed));
  EXPECT_LT((newton.translation() - ceres.translation()).norm(), 1e-6);
  EXPECT_LT(rotationDistance(newton, ceres), 1e-7);
  EXPECT_LE(weightedObjective(c, newton), weightedObjective(c, closed) + 1e-9);
}

// Points without a normal (M = kappa I) among surface points: Gauss-Newton's structured normal
// equations treat both kinds as Ceres's whitened residuals do.
TEST(Solvers, GaussNewtonAndCeresAgreeWhereSomePointsHaveNoNormal) {
  WeightedCorrespondences c = makeCorrespondences(someTransform(), 0.2, 0.01, 300, 5);
  for (size_t i = 0; i < c.size(); i += 3) c.normal[i].setZero();
  Eigen::Isometry3d newton = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d ceres = Eigen::Isometry3d::Identity();
  ASSERT_TRUE(solveGaussNewton(c, 50, 0, 0, &newton));
  ASSERT_TRUE(solveWithCeres(c, 100, 1, &ceres));
  EXPECT_LT((newton.translation() - ceres.translation()).norm(), 1e-6);
  EXPECT_LT(rotationDistance(newton, ceres), 1e-7);
  EXPECT_NEAR(weightedObjective(c, newton), weightedObjective(c, ceres),
              1e-9 * weightedObjective(c, ceres));
}

TEST(Solvers, RefuseTooFewCorrespondences) {
  const WeightedCorrespondences c = makeCorrespondences(someTransform(), 0.0, 1.0, 2, 4);
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  EXPECT_FALSE(solveClosedForm(c, &T));
  EXPECT_FALSE(solveGaussNewton(c, 5, 0, 0, &T));
  EXPECT_FALSE(solveWithCeres(c, 5, 1, &T));
  EXPECT_TRUE(T.isApprox(Eigen::Isometry3d::Identity()));
}

// The covariance is symmetric positive definite; its noise term scales with sigma^2 and the
// total never claims less than the noise term (pose_covariance.hpp).
TEST(PoseCovariance, PositiveDefiniteWithANoiseTermProportionalToSigmaSquared) {
  const WeightedCorrespondences c = makeCorrespondences(someTransform(), 0.05, 1.0, 500, 5);
  const double gaussian = std::numeric_limits<double>::infinity();
  Eigen::Matrix<double, 6, 6> small, large;
  PoseCovarianceTerms small_terms, large_terms;
  ASSERT_TRUE(computePoseCovariance(c, someTransform(), 0.01, gaussian, &small, &small_terms));
  ASSERT_TRUE(computePoseCovariance(c, someTransform(), 0.04, gaussian, &large, &large_terms));
  EXPECT_TRUE(small.isApprox(small.transpose()));
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 6, 6>> eigen(small);
  EXPECT_GT(eigen.eigenvalues().minCoeff(), 0.0);
  EXPECT_TRUE(large_terms.model.isApprox(4.0 * small_terms.model, 1e-9));
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 6, 6>> excess(small -
                                                                          small_terms.model);
  EXPECT_GE(excess.eigenvalues().minCoeff(), -1e-15);
  // 500 points spread over 10 m with sigma 0.1 m pin the translation to ~0.1/sqrt(500*w) m.
  EXPECT_LT(std::sqrt(small(0, 0)), 0.02);
}

}  // namespace
}  // namespace pda_registration

// Aitken extrapolation of the runs (run_extrapolation.hpp) on a linearly converging iteration:
// each "run" moves the pose a fraction 1 - rho of the way to the solution, as runs do on dense
// clouds. Extrapolated, it needs a fraction of the runs; an oscillating iteration (steps that
// turn back) is never extrapolated.
namespace {
int runsToConverge(double rho, bool extrapolate, double* final_error) {
  using namespace pda_registration;
  Eigen::Isometry3d solution = Eigen::Isometry3d::Identity();
  solution.linear() = Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 2, 3).normalized()).matrix();
  solution.translation() = Eigen::Vector3d(1.0, -2.0, 0.5);
  RunExtrapolation extrapolation(PoseStep(Point(5.0, 0.0, 0.0), 3.0));
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  for (int run = 1; run <= 1000; ++run) {
    // One run: the remaining motion to the solution, scaled by 1 - rho (about the origin).
    const Eigen::Isometry3d remaining = solution * T.inverse();
    const Eigen::AngleAxisd rotation(remaining.linear());
    Eigen::Isometry3d partial = Eigen::Isometry3d::Identity();
    partial.linear() = Eigen::AngleAxisd((1.0 - rho) * rotation.angle(), rotation.axis()).matrix();
    partial.translation() = (1.0 - rho) * remaining.translation();
    const Eigen::Isometry3d before = T;
    T = partial * T;
    if ((T.translation() - before.translation()).norm() < 1e-6) {
      *final_error = (T.translation() - solution.translation()).norm();
      return run;
    }
    if (extrapolate) T = extrapolation.next(before, T, 1e-4, 1e9);
  }
  *final_error = (T.translation() - solution.translation()).norm();
  return 1000;
}
}  // namespace

TEST(RunExtrapolation, CutsTheRunsOfALinearlyConvergingIteration) {
  double plain_error = 0.0, extrapolated_error = 0.0;
  const int plain = runsToConverge(0.9, false, &plain_error);
  const int extrapolated = runsToConverge(0.9, true, &extrapolated_error);
  EXPECT_GT(plain, 100);
  EXPECT_LT(extrapolated, plain / 3) << "plain " << plain;
  EXPECT_LT(extrapolated_error, 1e-4);
}

TEST(RunExtrapolation, LeavesTurningStepsAlone) {
  pda_registration::RunExtrapolation extrapolation(
      pda_registration::PoseStep(pda_registration::Point::Zero(), 1.0));
  Eigen::Isometry3d a = Eigen::Isometry3d::Identity(), b = a, c = a;
  b.translation() = Eigen::Vector3d(0.1, 0, 0);
  c.translation() = Eigen::Vector3d(0.05, 0, 0);  // turned back
  EXPECT_TRUE(extrapolation.next(a, b, 1e-6, 1e9).isApprox(b));
  EXPECT_TRUE(extrapolation.next(b, c, 1e-6, 1e9).isApprox(c));
  EXPECT_EQ(extrapolation.extrapolations(), 0);
}

// In the approach stage three steps must agree: the first agreeing pair only counts.
TEST(RunExtrapolation, WaitsForThreeAgreeingStepsWhenAsked) {
  pda_registration::RunExtrapolation extrapolation(
      pda_registration::PoseStep(pda_registration::Point::Zero(), 1.0));
  extrapolation.setAgreementsNeeded(2);
  Eigen::Isometry3d before = Eigen::Isometry3d::Identity();
  double x = 0.0, step = 0.1;
  for (int run = 1; run <= 3; ++run) {
    Eigen::Isometry3d after = Eigen::Isometry3d::Identity();
    x += step;
    step *= 0.5;  // shrinking steps, one way: linear convergence
    after.translation() = Eigen::Vector3d(x, 0, 0);
    const Eigen::Isometry3d next = extrapolation.next(before, after, 1e-6, 1e9);
    if (run < 3) {
      EXPECT_TRUE(next.isApprox(after)) << "run " << run;
    } else {
      // The tail of the third step (rho = 0.5: one more step) is taken.
      EXPECT_NEAR(next.translation().x(), x + 0.025, 1e-12);
    }
    before = next;
  }
  EXPECT_EQ(extrapolation.extrapolations(), 1);
}

// The rest test (run_rest.hpp): runs that cycle between two poses come back on themselves and
// are at rest; a slide of equally small steps one way, and a slide that zigzags, are not.
namespace {
Eigen::Isometry3d shifted(double x, double y) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation() = Eigen::Vector3d(x, y, 0.0);
  return T;
}
// Feeds runs ending at `xs`/`ys` (starting at the origin); returns the run at which the test
// first says "came back", 0 if never.
int restAt(const std::vector<double>& xs, const std::vector<double>& ys) {
  pda_registration::RunRest rest(pda_registration::PoseStep(pda_registration::Point::Zero(), 1.0));
  Eigen::Isometry3d before = Eigen::Isometry3d::Identity();
  for (size_t i = 0; i < xs.size(); ++i) {
    const Eigen::Isometry3d after = shifted(xs[i], ys[i]);
    if (rest.cameBack(before, after)) return static_cast<int>(i) + 1;
    before = after;
  }
  return 0;
}
}  // namespace

TEST(RunRest, ACycleBetweenTwoPosesIsAtRest) {
  std::vector<double> xs, ys;
  for (int i = 0; i < 20; ++i) {
    xs.push_back(i % 2 ? 0.0 : 0.0005);  // 0.5 mm there and back, as room_scan on a 0.5 m map
    ys.push_back(0.0);
  }
  EXPECT_EQ(restAt(xs, ys), pda_registration::RunRest::kWindow);
}

TEST(RunRest, ASlideIsNotAtRestHoweverSmallItsSteps) {
  std::vector<double> xs, ys, zig_xs, zig_ys;
  for (int i = 1; i <= 40; ++i) {
    xs.push_back(0.0004 * i);  // 0.4 mm a run one way: the plateau before a collapse
    ys.push_back(0.0);
    zig_xs.push_back(0.0004 * i);  // the same slide, zigzagging 0.4 mm across it
    zig_ys.push_back(i % 2 ? 0.0004 : 0.0);
  }
  EXPECT_EQ(restAt(xs, ys), 0);
  EXPECT_EQ(restAt(zig_xs, zig_ys), 0);
}

// EM inside one run (em_run.hpp) takes the same tail: on fixed candidate sets it must end where
// plain EM converges, in fewer iterations. Plain EM is written out here from the E-step and the
// Gauss-Newton M-step; sigma and nu are fixed, so that only the pose iterates.
namespace {
// Three walls of a room corner and a sloped roof, sampled every `spacing` from `offset`.
pda_registration::PointList cornerScene(double spacing, double offset) {
  pda_registration::PointList points;
  for (double a = offset; a < 2.0; a += spacing) {
    for (double b = offset; b < 2.0; b += spacing) {
      points.emplace_back(0.0, a, b);
      points.emplace_back(a, 0.0, b);
      points.emplace_back(a, b, 0.0);
      points.emplace_back(a, b, 2.0 + 0.3 * a);
    }
  }
  return points;
}
}  // namespace

TEST(EmRun, ExtrapolatedStepsEndWherePlainEmConvergesInFewerIterations) {
  using namespace pda_registration;
  const TargetIndex target(cornerScene(0.05, 0.0));
  const PointList source = cornerScene(0.1, 0.025);  // other samples of the same surfaces
  Eigen::Isometry3d start = Eigen::Isometry3d::Identity();
  start.linear() = Eigen::AngleAxisd(0.02, Eigen::Vector3d(1, 2, 3).normalized()).matrix();
  start.translation() = Eigen::Vector3d(0.03, -0.02, 0.01);

  RegistrationParameters p;
  p.surface_anisotropy = 1.0;  // the paper's isotropic noise: no normals needed
  p.sigma_mode = SigmaMode::kFixed;
  p.fixed_sigma = 0.03;
  p.nu_mode = NuMode::kFixed;
  p.translation_epsilon = 1e-7;
  p.rotation_epsilon = 1e-7;
  p.max_em_iterations = 500;
  const double sigma_squared = p.fixed_sigma * p.fixed_sigma;
  const CandidateSets candidates = findCandidateSets(target, source, start, p.k, p.radius, 1);

  // Plain EM: iterations until a step is below the epsilons, then on to its limit.
  NoiseShapes shapes;
  makeNoiseShapes({}, {}, sigma_squared, p, &shapes);
  EStepBuffers buffers;
  WeightedCorrespondences correspondences;
  Eigen::Isometry3d plain = start;
  int plain_iterations = 0;
  for (int iteration = 1; iteration <= 2000; ++iteration) {
    computeWeightedCorrespondences(source, candidates, shapes, plain, p.nu, sigma_squared, 1,
                                   &buffers, &correspondences);
    Eigen::Isometry3d next = plain;
    ASSERT_TRUE(solveGaussNewton(correspondences, 1, 0.0, 0.0, &next));
    const Increment step = incrementBetween(plain, next);
    plain = next;
    if (plain_iterations == 0 && isSmall(step, p)) plain_iterations = iteration;
    if (step.translation < 1e-13 && step.rotation < 1e-13) break;
  }
  ASSERT_GT(plain_iterations, 10) << "the test needs a slowly converging run";

  RegistrationWorkspace workspace;
  workspace.candidates = candidates;
  EmState state;
  state.T = start;
  state.nu = p.nu;
  state.sigma_squared = sigma_squared;
  bool settled = false;
  int iterations = 0;
  const PoseStep step_metric = PoseStep::over(source);
  ASSERT_TRUE(runEm(source, SurfaceNormalMap(), NormalLookup::kAtCandidate, p, &step_metric,
                    &workspace, &state, &settled, &iterations));
  EXPECT_TRUE(settled);
  EXPECT_LT(iterations, plain_iterations * 2 / 3) << "plain EM: " << plain_iterations;
  const Increment off = incrementBetween(plain, state.T);
  EXPECT_LT(off.translation, 1e-6);
  EXPECT_LT(off.rotation, 1e-6);
}
