// End-to-end registration on a synthetic room with a known transform: accuracy with noise and
// outliers (against nearest-neighbour ICP), unit invariance, thread invariance, independence of
// earlier alignments on the same object, every solver.
#include <gtest/gtest.h>

#include "pda_registration/core/error_metrics.hpp"
#include "pda_registration/core/pda_registration.hpp"
#include "pda_registration/core/perturbation.hpp"
#include "pda_registration/tools/pcl_baselines.hpp"
#include "test_support/synthetic_scene.hpp"

namespace pda_registration {
namespace {

using testing_support::makeSyntheticRoom;
using testing_support::SyntheticCase;
using testing_support::SyntheticOptions;

RegistrationResult alignCase(const SyntheticCase& c, const RegistrationParameters& p,
                             const Eigen::Isometry3d& initial) {
  PdaRegistration registration(p);
  EXPECT_TRUE(registration.setTarget(c.target));
  return registration.align(c.source, initial);
}

// Parameterised over the M-step solver and the noise model, as small_gicp tests its factors.
struct Variant {
  MStepSolver solver;
  double anisotropy;
  double nu;
};

class SyntheticRegistration : public ::testing::TestWithParam<Variant> {};

TEST_P(SyntheticRegistration, RecoversKnownTransformWithNoiseAndOutliers) {
  SyntheticOptions options;
  options.outlier_fraction = 0.3;
  const SyntheticCase c = makeSyntheticRoom(options);
  RegistrationParameters p;
  p.solver = GetParam().solver;
  p.surface_anisotropy = GetParam().anisotropy;
  p.nu = GetParam().nu;
  p.radius = 0.5;
  const Eigen::Isometry3d initial = c.T_target_source * randomPerturbation(3.0, 0.15, 7);

  const RegistrationResult r = alignCase(c, p, initial);
  ASSERT_TRUE(r.converged) << r.reason;
  const PoseError error = poseError(c.source, r.T_target_source, c.T_target_source);
  EXPECT_LT(error.translation, 0.015);  // measured up to 1.03 cm (sampling-aware model)
  EXPECT_LT(error.rotation_deg, 0.2);
  EXPECT_GT(r.runs, 1);
  // 600 outliers among 2600 points (77% inliers, 1 cm noise): the inlier share says so.
  EXPECT_GT(r.inlier_fraction, 0.5);
  EXPECT_LT(r.inlier_fraction, 0.85);
  // Outliers far from every wall drop out of the overlap, so the support (inliers among the
  // overlapping points) is at least the inlier fraction.
  EXPECT_LE(r.overlap_points, r.source_points_used);
  EXPECT_GE(r.support_fraction, r.inlier_fraction);
  EXPECT_LE(r.support_fraction, 1.0);
  EXPECT_LT(r.sigma, 0.05);
}

INSTANTIATE_TEST_SUITE_P(SolversAndModels, SyntheticRegistration,
                         ::testing::Values(Variant{MStepSolver::kGaussNewton, 1000.0, 5.0},
                                           Variant{MStepSolver::kCeres, 1000.0, 5.0},
                                           Variant{MStepSolver::kClosedForm, 1.0, 5.0},
                                           Variant{MStepSolver::kGaussNewton, 1.0, 5.0},
                                           Variant{MStepSolver::kGaussNewton, 1000.0, 3.0}),
                         [](const ::testing::TestParamInfo<Variant>& info) {
                           return std::string(toString(info.param.solver)) + "_kappa" +
                                  std::to_string(static_cast<int>(info.param.anisotropy)) + "_nu" +
                                  std::to_string(static_cast<int>(info.param.nu));
                         });

// PCL's point-to-point ICP on the same case, same radius: PDA (t-weights) must be more accurate.
TEST(SyntheticRegistration, MoreAccurateThanNearestNeighbourIcpWithOutliers) {
  SyntheticOptions options;
  options.outlier_fraction = 0.3;
  options.source_noise = 0.02;
  const SyntheticCase c = makeSyntheticRoom(options);
  const Eigen::Isometry3d initial = c.T_target_source * randomPerturbation(3.0, 0.15, 11);
  RegistrationParameters p;
  p.radius = 0.5;
  const RegistrationResult pda = alignCase(c, p, initial);
  BaselineParameters icp_parameters;
  icp_parameters.max_correspondence_distance = p.radius;
  const BaselineResult icp =
      runBaseline(BaselineMethod::kIcp, c.target, c.source, initial, icp_parameters);
  const double pda_error =
      poseError(c.source, pda.T_target_source, c.T_target_source).mean_distance;
  const double icp_error =
      poseError(c.source, icp.T_target_source, c.T_target_source).mean_distance;
  // The sampling-aware noise model measured 0.52x ICP's error here (1.35 vs 2.57 cm).
  EXPECT_LT(pda_error, 0.6 * icp_error) << "pda " << pda_error << " icp " << icp_error;
}

// The same case in metres and in millimetres (all lengths x1000) gives the same transform,
// because sigma is estimated; the fixed-sigma mode (paper: Sigma = I) does not.
TEST(SyntheticRegistration, EstimatedSigmaMakesTheResultUnitInvariant) {
  SyntheticOptions metres_options, millimetres_options;
  metres_options.outlier_fraction = millimetres_options.outlier_fraction = 0.2;
  millimetres_options.scale = 1000.0;
  const SyntheticCase metres = makeSyntheticRoom(metres_options);
  const SyntheticCase millimetres = makeSyntheticRoom(millimetres_options);
  const Eigen::Isometry3d perturbation = randomPerturbation(3.0, 0.15, 3);
  Eigen::Isometry3d perturbation_mm = perturbation;
  perturbation_mm.translation() *= 1000.0;

  RegistrationParameters in_metres;
  in_metres.radius = 0.5;
  RegistrationParameters in_millimetres = in_metres;
  in_millimetres.radius *= 1000.0;
  in_millimetres.min_radius *= 1000.0;
  in_millimetres.normal_voxel_size *= 1000.0;
  in_millimetres.translation_epsilon *= 1000.0;

  const RegistrationResult m = alignCase(metres, in_metres, metres.T_target_source * perturbation);
  const RegistrationResult mm =
      alignCase(millimetres, in_millimetres, millimetres.T_target_source * perturbation_mm);
  ASSERT_TRUE(m.converged && mm.converged) << m.reason << " / " << mm.reason;
  EXPECT_LT((m.T_target_source.linear() - mm.T_target_source.linear()).norm(), 1e-6);
  EXPECT_LT((1000.0 * m.T_target_source.translation() - mm.T_target_source.translation()).norm(),
            1e-3);  // 1 micrometre
  EXPECT_NEAR(1000.0 * m.sigma, mm.sigma, 1e-3 * mm.sigma);
  EXPECT_EQ(m.runs, mm.runs);

  // Fixed sigma = 1 (the paper's unit covariance) weighs millimetre residuals very differently.
  in_metres.sigma_mode = in_millimetres.sigma_mode = SigmaMode::kFixed;
  const RegistrationResult fixed_m =
      alignCase(metres, in_metres, metres.T_target_source * perturbation);
  const RegistrationResult fixed_mm =
      alignCase(millimetres, in_millimetres, millimetres.T_target_source * perturbation_mm);
  EXPECT_GT(
      (1000.0 * fixed_m.T_target_source.translation() - fixed_mm.T_target_source.translation())
          .norm(),
      0.01);
}

// Threads split the work, never the arithmetic: the estimate is bit-identical.
TEST(SyntheticRegistration, ResultDoesNotDependOnThreadCount) {
  SyntheticOptions options;
  options.outlier_fraction = 0.2;
  const SyntheticCase c = makeSyntheticRoom(options);
  const Eigen::Isometry3d initial = c.T_target_source * randomPerturbation(3.0, 0.15, 5);
  RegistrationParameters one, two;
  one.radius = two.radius = 0.5;
  two.threads = 2;
  const RegistrationResult a = alignCase(c, one, initial);
  const RegistrationResult b = alignCase(c, two, initial);
  EXPECT_TRUE(a.T_target_source.isApprox(b.T_target_source, 0.0));
  EXPECT_EQ(a.em_iterations, b.em_iterations);
}

// The paper's single-run mode improves on the initial guess, and multiple runs improve on it.
TEST(SyntheticRegistration, MultipleRunsBeatASingleRun) {
  const SyntheticCase c = makeSyntheticRoom(SyntheticOptions());
  const Eigen::Isometry3d initial = c.T_target_source * randomPerturbation(5.0, 0.25, 9);
  RegistrationParameters single;
  single.radius = 0.5;
  single.max_runs = 1;
  single.max_em_iterations = 100;
  RegistrationParameters multiple = single;
  multiple.max_runs = 30;
  multiple.max_em_iterations = 5;
  const double initial_error = poseError(c.source, initial, c.T_target_source).mean_distance;
  const RegistrationResult s = alignCase(c, single, initial);
  const RegistrationResult m = alignCase(c, multiple, initial);
  const double single_error =
      poseError(c.source, s.T_target_source, c.T_target_source).mean_distance;
  const double multi_error =
      poseError(c.source, m.T_target_source, c.T_target_source).mean_distance;
  EXPECT_EQ(s.runs, 1);
  EXPECT_LT(single_error, initial_error);
  EXPECT_LT(multi_error, 0.5 * single_error);
  EXPECT_LT(multi_error, 0.015);  // measured 1.11 cm with the sampling-aware noise model
}

// time_limit_ms (the nodelet's deadline for warm alignments): no run starts after it, and a result
// still moving then is "out of time", not converged; a limit it never reaches changes nothing.
TEST(SyntheticRegistration, TimeLimitStopsAnAlignmentStillMoving) {
  const SyntheticCase c = makeSyntheticRoom(SyntheticOptions());
  const Eigen::Isometry3d initial = c.T_target_source * randomPerturbation(5.0, 0.25, 9);
  RegistrationParameters unlimited;
  unlimited.radius = 0.5;
  RegistrationParameters generous = unlimited, tight = unlimited;
  generous.time_limit_ms = 1e6;
  tight.time_limit_ms = 1e-6;
  const RegistrationResult free_run = alignCase(c, unlimited, initial);
  const RegistrationResult in_time = alignCase(c, generous, initial);
  const RegistrationResult cut = alignCase(c, tight, initial);
  ASSERT_TRUE(free_run.converged) << free_run.reason;
  EXPECT_GT(free_run.runs, 1);
  EXPECT_TRUE(in_time.converged);
  EXPECT_FALSE(in_time.out_of_time);
  EXPECT_TRUE(in_time.T_target_source.isApprox(free_run.T_target_source, 0.0));
  EXPECT_EQ(cut.runs, 1);  // the first run always runs
  EXPECT_TRUE(cut.out_of_time);
  EXPECT_FALSE(cut.converged);
  EXPECT_NE(cut.reason.find("out of time"), std::string::npos) << cut.reason;

  RegistrationParameters invalid = unlimited;
  invalid.time_limit_ms = -1.0;
  const RegistrationResult refused = alignCase(c, invalid, initial);
  EXPECT_FALSE(refused.converged);
  EXPECT_NE(refused.reason.find("time_limit_ms"), std::string::npos) << refused.reason;
}

// Re-using one registration object for several sources re-uses the target index.
TEST(SyntheticRegistration, TargetIndexIsBuiltOnceAndReused) {
  const SyntheticCase c = makeSyntheticRoom(SyntheticOptions());
  RegistrationParameters p;
  p.radius = 0.5;
  PdaRegistration registration(p);
  ASSERT_TRUE(registration.setTarget(c.target));
  // With target_subset (default) the first source decides how the target is indexed.
  EXPECT_EQ(registration.target(), nullptr);
  ASSERT_TRUE(registration.align(c.source, c.T_target_source).converged);
  const std::shared_ptr<const TargetIndex> index = registration.target();
  ASSERT_NE(index, nullptr);
  EXPECT_EQ(index->size(), c.target.size()) << "a source within the budget gets the whole target";
  for (uint64_t seed = 1; seed <= 3; ++seed) {
    const RegistrationResult r =
        registration.align(c.source, c.T_target_source * randomPerturbation(2.0, 0.1, seed));
    EXPECT_TRUE(r.converged) << r.reason;
    EXPECT_EQ(registration.target(), index);
  }
  p.k = 5;  // a search parameter: no re-index
  registration.setParameters(p);
  EXPECT_EQ(registration.target(), index);
  p.target_voxel_size = 0.1;  // changes the indexed points: re-index
  registration.setParameters(p);
  EXPECT_NE(registration.target(), index);
  EXPECT_LT(registration.target()->size(), index->size());
}

// One object keeps its working memory between alignments (registration_workspace.hpp): what an
// earlier alignment left there (a larger source, more candidates, another noise model) must not
// change the next result. Each result equals a fresh object's, to the bit.
TEST(SyntheticRegistration, ResultDoesNotDependOnEarlierAlignments) {
  SyntheticOptions large_options;
  large_options.source_points = 3000;
  large_options.outlier_fraction = 0.2;
  const SyntheticCase large = makeSyntheticRoom(large_options);
  SyntheticOptions small_options;
  small_options.source_points = 800;
  small_options.seed = 2;
  const SyntheticCase small = makeSyntheticRoom(small_options);
  RegistrationParameters anisotropic;
  anisotropic.radius = 0.5;
  RegistrationParameters isotropic = anisotropic;
  isotropic.surface_anisotropy = 1.0;  // no normals, no shapes: empty buffers in the workspace
  isotropic.k = 3;

  struct Step {
    const SyntheticCase* c;
    const RegistrationParameters* p;
    uint64_t seed;
  };
  const Step steps[] = {{&large, &anisotropic, 1},
                        {&small, &isotropic, 2},
                        {&large, &isotropic, 3},
                        {&small, &anisotropic, 4},
                        {&large, &anisotropic, 1}};
  PdaRegistration reused(anisotropic);
  ASSERT_TRUE(reused.setTarget(large.target));  // the small room's target differs only by noise
  for (const Step& step : steps) {
    const Eigen::Isometry3d initial =
        step.c->T_target_source * randomPerturbation(3.0, 0.15, step.seed);
    reused.setParameters(*step.p);
    const RegistrationResult again = reused.align(step.c->source, initial);
    PdaRegistration fresh(*step.p);
    ASSERT_TRUE(fresh.setTarget(large.target));
    const RegistrationResult first = fresh.align(step.c->source, initial);
    EXPECT_TRUE(first.converged) << first.reason;
    EXPECT_TRUE(again.T_target_source.isApprox(first.T_target_source, 0.0)) << "seed " << step.seed;
    EXPECT_EQ(again.sigma, first.sigma);
    EXPECT_EQ(again.em_iterations, first.em_iterations);
    EXPECT_TRUE(again.covariance.isApprox(first.covariance, 0.0));
    EXPECT_EQ(again.inlier_fraction, first.inlier_fraction);
  }
}

}  // namespace
}  // namespace pda_registration
