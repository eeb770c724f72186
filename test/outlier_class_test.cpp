// The outlier class of a local start (outlier_class.hpp, local_start.hpp): sigma follows the points
// that have a counterpart even when they are the fewer, and a local start's answer is kept only
// near the seed.
#include "pda_registration/core/outlier_class.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "pda_registration/core/association_weights.hpp"
#include "pda_registration/core/degrees_of_freedom.hpp"
#include "pda_registration/core/local_start.hpp"

namespace pda_registration {
namespace {

// A third of the source points lie on the target's plane (across-surface noise 5 mm), two thirds
// have no counterpart: their candidates, on the same plane's samples, lie 0.2-0.9 m across.
struct PlaneWithStrays {
  PointList source;
  CandidateSets candidates;
  NoiseShapes shapes;
  size_t with_counterpart = 0;
};

PlaneWithStrays planeWithStrays(size_t points) {
  PlaneWithStrays scene;
  std::mt19937 random(11);
  std::normal_distribution<double> noise(0.0, 0.005);
  std::uniform_real_distribution<double> along(-0.05, 0.05), stray(0.2, 0.9), unit(-1.0, 1.0);
  scene.candidates.offsets.push_back(0);
  scene.shapes.sampling = true;  // sigma is the noise across the surface (the default model)
  for (size_t j = 0; j < points; ++j) {
    const Point x(3.0 * unit(random), 3.0 * unit(random), 0.0);
    scene.source.push_back(x);
    const bool counterpart = j % 3 == 0;
    scene.with_counterpart += counterpart;
    const double across = counterpart ? noise(random) : (unit(random) > 0 ? 1 : -1) * stray(random);
    for (int c = 0; c < 3; ++c) {
      scene.candidates.points.push_back(x + Point(along(random), along(random), across));
      scene.candidates.target_indices.push_back(scene.candidates.target_indices.size());
    }
    scene.candidates.offsets.push_back(scene.candidates.points.size());
    scene.shapes.normal.push_back(Point::UnitZ());
    scene.shapes.inverse_kappa.push_back(1e-3);
  }
  return scene;
}

// sigma's EM update alone (the pose held at the truth), from 0.15 m, with or without the class.
double settledSigma(const PlaneWithStrays& scene, bool outlier_class, double* inlier_share) {
  const double nu = 5.0, radius = 1.0;
  double sigma_squared = 0.15 * 0.15, share = 0.5;
  EStepBuffers buffers;
  WeightedCorrespondences correspondences;
  for (int iteration = 0; iteration < 40; ++iteration) {
    buffers.outliers = outlier_class ? outlierClassFor(share, radius, nu) : OutlierClass();
    computeWeightedCorrespondences(scene.source, scene.candidates, scene.shapes,
                                   Eigen::Isometry3d::Identity(), nu, sigma_squared, 1, &buffers,
                                   &correspondences);
    share = 1.0 - correspondences.inlier_total / static_cast<double>(correspondences.size());
    sigma_squared = estimateSigmaSquared(correspondences, Eigen::Isometry3d::Identity());
  }
  *inlier_share = 1.0 - share;
  return std::sqrt(sigma_squared);
}

// The t alone cannot shrink sigma below the strays' residuals once they outnumber 1 / (nu + 3) of
// the points; with the class, sigma is the plane's noise and the inlier share the third.
TEST(OutlierClass, SigmaFollowsTheFewerPointsThatHaveACounterpart) {
  const PlaneWithStrays scene = planeWithStrays(3000);
  double t_only_share = 0.0, with_class_share = 0.0;
  const double t_only = settledSigma(scene, false, &t_only_share);
  const double with_class = settledSigma(scene, true, &with_class_share);
  EXPECT_DOUBLE_EQ(t_only_share, 1.0);  // no class: every point counts in full
  EXPECT_GT(t_only, 0.1);
  EXPECT_LT(with_class, 0.008);
  EXPECT_GT(with_class, 0.003);
  const double third = static_cast<double>(scene.with_counterpart) / scene.source.size();
  EXPECT_NEAR(with_class_share, third, 0.03);
}

TEST(OutlierClass, NearPointsCountFarPointsDoNot) {
  const OutlierClass outliers = outlierClassFor(0.5, 1.0, 5.0);
  ASSERT_TRUE(outliers.on());
  const double log_variance = std::log(0.01 * 0.01);                               // sigma 1 cm
  EXPECT_GT(inlierResponsibility(outliers, 5.0, 1.0, log_variance, 1.0), 0.95);    // 1 sigma
  EXPECT_LT(inlierResponsibility(outliers, 5.0, 400.0, log_variance, 1.0), 0.01);  // 20 sigma
  EXPECT_DOUBLE_EQ(inlierResponsibility(OutlierClass(), 5.0, 400.0, log_variance, 1.0), 1.0);
  EXPECT_FALSE(outlierClassFor(0.5, 0.0, 5.0).on());
}

TEST(LocalStart, RunsWhereTheFirstFailedOrSlidAndStaysNearTheSeed) {
  PointList source;
  for (int i = 0; i < 10; ++i) source.push_back(Point(i, -i, 0.5 * i));
  const Eigen::Isometry3d seed = Eigen::Isometry3d::Identity();
  RegistrationParameters p;  // radius 1 m
  const Eigen::Isometry3d near_seed(Eigen::Translation3d(0.3, 0.2, 0.0));
  EXPECT_NEAR(rmsDisplacement(source, near_seed, seed), std::hypot(0.3, 0.2), 1e-12);
  EXPECT_TRUE(localStartStaysNear(source, near_seed, seed, p));
  // A fit beyond the seed's candidates: the local start stops there, and is not kept.
  EXPECT_FALSE(localStartStaysNear(source, Eigen::Isometry3d(Eigen::Translation3d(2.6, 0, 0)),
                                   seed, p));
  // 6 deg about the origin moves these points (up to 12.7 m out) 0.79 m in RMS; 8 deg 1.05 m.
  EXPECT_TRUE(localStartStaysNear(
      source, Eigen::Isometry3d(Eigen::AngleAxisd(6.0 * M_PI / 180.0, Point::UnitZ())), seed, p));
  EXPECT_FALSE(localStartStaysNear(
      source, Eigen::Isometry3d(Eigen::AngleAxisd(8.0 * M_PI / 180.0, Point::UnitZ())), seed, p));

  RegistrationResult first;
  first.source_points_used = 1000;
  EXPECT_TRUE(localStartWarranted(first, p, 0.0));
  first.out_of_time = true;
  EXPECT_FALSE(localStartWarranted(first, p, 0.0));  // the deadline's verdict, not the data's
  first.out_of_time = false;
  first.converged = true;
  first.nu = kMinDegreesOfFreedom;
  EXPECT_FALSE(localStartWarranted(first, p, 0.5));  // converged within the seed's candidates
  EXPECT_TRUE(localStartWarranted(first, p, 2.7));   // slid away, half the points fit
  first.nu = 3.0;
  EXPECT_FALSE(localStartWarranted(first, p, 2.7));  // slid away onto a fit of the whole overlap
  first.nu = kMinDegreesOfFreedom;
  p.nu_mode = NuMode::kFixed;
  EXPECT_FALSE(localStartWarranted(first, p, 2.7));  // nu at the floor says nothing when fixed
}

}  // namespace
}  // namespace pda_registration
