// The pose covariance (pose_covariance.hpp) against the error it stands for: Monte Carlo on a
// linearised problem (the covariance of the least-squares step is known exactly there), and end
// to end on a simulated office whose ground truth is exact.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <random>
#include <tuple>
#include <vector>

#include "pda_registration/core/pda_registration.hpp"
#include "pda_registration/core/pose_covariance.hpp"
#include "pda_registration/core/pose_jacobian.hpp"
#include "pda_registration/simulation/map_simulation.hpp"

namespace pda_registration {
namespace {

// Points on the floor and two walls of a 6 x 6 x 3 m corner (every pose direction constrained),
// each with its plane's normal, as the E-step hands them over (one correspondence per point,
// weight 1, the normal-only shape of a surface point).
WeightedCorrespondences cornerCorrespondences(size_t per_plane, std::mt19937_64* random) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  WeightedCorrespondences c;
  for (int plane = 0; plane < 3; ++plane) {
    for (size_t i = 0; i < per_plane; ++i) {
      const double a = 6.0 * u(*random), b = 6.0 * u(*random), h = 3.0 * u(*random);
      Point p, n;
      if (plane == 0) p = Point(a, b, 0.0), n = Point::UnitZ();
      if (plane == 1) p = Point(a, 0.0, h), n = Point::UnitY();
      if (plane == 2) p = Point(0.0, b, h), n = Point::UnitX();
      c.source.push_back(p);
      c.target_mean.push_back(p);
      c.normal.push_back(n);
      c.weight.push_back(1.0);
      c.inverse_kappa.push_back(0.01);  // along the surface counts 100x less
      c.source_index.push_back(c.source_index.size());
    }
  }
  return c;
}

// The Gauss-Newton step the residuals pull the pose by: what the estimate's error would be.
Vector6d leastSquaresStep(const WeightedCorrespondences& c) {
  Matrix6d h = Matrix6d::Zero();
  Vector6d g = Vector6d::Zero();
  for (size_t i = 0; i < c.size(); ++i) {
    const PoseJacobian j = poseJacobian(c.source[i]);
    const Eigen::Matrix3d m = c.inverse_kappa[i] * Eigen::Matrix3d::Identity() +
                              (1.0 - c.inverse_kappa[i]) * c.normal[i] * c.normal[i].transpose();
    h += c.weight[i] * j.transpose() * m * j;
    g += c.weight[i] * j.transpose() * m * (c.target_mean[i] - c.source[i]);
  }
  return h.ldlt().solve(g);
}

// Residuals along the normal: white noise of `noise`, plus a common offset per 1 m patch of
// `patch_offset` (a surface sampled or warped a little off, shared by its neighbours). The
// residuals are recentred so that the least-squares step is zero, as at an optimum.
struct Realisation {
  Vector6d error;  // the step before recentring: the error these residuals make
  Matrix6d covariance, model;
};

Realisation realise(WeightedCorrespondences c, double noise, double patch_offset,
                    std::mt19937_64* random) {
  std::normal_distribution<double> gauss(0.0, 1.0);
  std::map<std::tuple<int, int, int>, double> patch;
  for (size_t i = 0; i < c.size(); ++i) {
    const Point& p = c.source[i];
    const auto key = std::make_tuple(static_cast<int>(std::floor(p.x())),
                                     static_cast<int>(std::floor(p.y())),
                                     static_cast<int>(std::floor(p.z())));
    if (!patch.count(key)) patch[key] = patch_offset * gauss(*random);
    c.target_mean[i] = p + (noise * gauss(*random) + patch[key]) * c.normal[i];
  }
  Realisation r;
  r.error = leastSquaresStep(c);
  // The estimate sits where the step is zero: move the source by it.
  const Eigen::Isometry3d T = applyIncrement(Eigen::Isometry3d::Identity(), r.error);
  double squared = 0.0;
  for (size_t i = 0; i < c.size(); ++i) {
    const double along = c.normal[i].dot(c.target_mean[i] - T * c.source[i]);
    squared += along * along;
  }
  PoseCovarianceTerms terms;
  // Gaussian weights: the Monte Carlo residuals are Gaussian and the step above is least squares.
  EXPECT_TRUE(computePoseCovariance(c, T, squared / static_cast<double>(c.size()),
                                    std::numeric_limits<double>::infinity(), &r.covariance,
                                    &terms));
  r.model = terms.model;
  return r;
}

struct Spread {
  double error_rms_t = 0, error_rms_r = 0, sigma_t = 0, sigma_r = 0, model_t = 0, model_r = 0;
};

Spread monteCarlo(double noise, double patch_offset, int draws) {
  std::mt19937_64 random(7);
  const WeightedCorrespondences c = cornerCorrespondences(3000, &random);
  Spread s;
  for (int d = 0; d < draws; ++d) {
    const Realisation r = realise(c, noise, patch_offset, &random);
    s.error_rms_t += r.error.head<3>().squaredNorm() / draws;
    s.error_rms_r += r.error.tail<3>().squaredNorm() / draws;
    const ExpectedError total = expectedError(r.covariance), model = expectedError(r.model);
    s.sigma_t += total.translation * total.translation / draws;
    s.sigma_r += total.rotation * total.rotation / draws;
    s.model_t += model.translation * model.translation / draws;
    s.model_r += model.rotation * model.rotation / draws;
  }
  for (double* v : {&s.error_rms_t, &s.error_rms_r, &s.sigma_t, &s.sigma_r, &s.model_t,
                    &s.model_r}) {
    *v = std::sqrt(*v);
  }
  return s;
}

TEST(PoseCovariance, IndependentNoiseGivesTheSpreadOfTheEstimate) {
  const Spread s = monteCarlo(0.01, 0.0, 60);
  // The noise term alone is right here; the total errs on the safe side (the upper bound of the
  // noise term and of structure estimates that each hold the noise again).
  EXPECT_NEAR(s.model_t / s.error_rms_t, 1.0, 0.25);
  EXPECT_GT(s.sigma_t / s.error_rms_t, 0.8);
  EXPECT_LT(s.sigma_t / s.error_rms_t, 1.8);
  EXPECT_GT(s.sigma_r / s.error_rms_r, 0.8);
  EXPECT_LT(s.sigma_r / s.error_rms_r, 1.8);
}

TEST(PoseCovariance, ErrorsSharedByNeighboursAreNotCountedAsIndependent) {
  // 5 mm of white noise, 5 mm offsets shared per 1 m patch: the patches, not the 9000 points,
  // are the independent constraints. The noise term alone is far too confident.
  const Spread s = monteCarlo(0.005, 0.005, 60);
  EXPECT_GT(s.error_rms_t / s.model_t, 4.0);
  EXPECT_GT(s.error_rms_r / s.model_r, 4.0);
  EXPECT_GT(s.sigma_t / s.error_rms_t, 0.5);
  EXPECT_LT(s.sigma_t / s.error_rms_t, 2.0);
  EXPECT_GT(s.sigma_r / s.error_rms_r, 0.5);
  EXPECT_LT(s.sigma_r / s.error_rms_r, 2.0);
}

TEST(PoseCovariance, ExpectedErrorIsTheRootTraceOfEachBlock) {
  Matrix6d c = Matrix6d::Zero();
  c.diagonal() << 1e-4, 2e-4, 1e-4, 1e-6, 2e-6, 1e-6;
  const ExpectedError e = expectedError(c);
  EXPECT_NEAR(e.translation, 0.02, 1e-12);
  EXPECT_NEAR(e.rotation, 0.002, 1e-12);
}

// The observed information: a point whose posterior spreads over two candidates sigma apart
// along its normal holds less about the pose than one with a single sure candidate. With the
// candidates' second moments the model term grows (never shrinks); without them it is the
// complete-data one.
TEST(PoseCovariance, AnAssociationLeftOpenWidensTheModelTerm) {
  std::mt19937_64 random(3);
  WeightedCorrespondences sure = cornerCorrespondences(500, &random);
  const double sigma_squared = 1e-4, nu = 5.0;
  const Eigen::Isometry3d identity = Eigen::Isometry3d::Identity();
  Matrix6d complete, certain, open;
  PoseCovarianceTerms complete_terms, certain_terms, open_terms;
  ASSERT_TRUE(computePoseCovariance(sure, identity, sigma_squared, nu, &complete, &complete_terms));
  // Second moments of one candidate at the point itself (residual 0): nothing is left open but
  // the t-weight's spread, which is zero at a zero residual.
  WeightedCorrespondences with_moments = sure;
  with_moments.second_moment.assign(sure.size(), Eigen::Matrix3d::Zero());
  ASSERT_TRUE(
      computePoseCovariance(with_moments, identity, sigma_squared, nu, &certain, &certain_terms));
  EXPECT_NEAR(expectedError(certain_terms.model).translation,
              expectedError(complete_terms.model).translation, 1e-12);
  // Two equally likely candidates at +-sigma / 2 along the normal (mean on the point). Per point
  // along its normal, information W = u against u - (1 + 2 / 8) u^2 / 4 observed: 1.9x the
  // variance, 1.38x sigma.
  for (size_t i = 0; i < sure.size(); ++i) {
    const Eigen::Vector3d r = 0.5 * std::sqrt(sigma_squared) * sure.normal[i];
    const double u = (nu + 3.0) / (nu + 0.25);  // the t-weight at sigma / 2
    with_moments.weight[i] = u;
    with_moments.second_moment[i] = u * u * r * r.transpose();
  }
  WeightedCorrespondences same_weights = with_moments;
  same_weights.second_moment.clear();
  ASSERT_TRUE(
      computePoseCovariance(same_weights, identity, sigma_squared, nu, &complete, &complete_terms));
  ASSERT_TRUE(computePoseCovariance(with_moments, identity, sigma_squared, nu, &open, &open_terms));
  const ExpectedError wide = expectedError(open_terms.model);
  const ExpectedError narrow = expectedError(complete_terms.model);
  EXPECT_NEAR(wide.translation / narrow.translation, 1.38, 0.05);
  EXPECT_NEAR(wide.rotation / narrow.rotation, 1.38, 0.05);
}

// The same alignment with the source frame's origin 50 m and 1 km from the overlap (a sparse map
// accumulated over a long drive): the same covariance, once expressed about the same point. The
// terms are bounded with rotations about the overlap's centre, so where the origin lies cannot
// mix rotation into translation (bounded about the source origin, this case read 1.18x in
// rotation and 1.54x in translation at 50 m).
TEST(PoseCovariance, DoesNotDependOnWhereTheSourceOriginLies) {
  std::mt19937_64 random(11);
  WeightedCorrespondences near = cornerCorrespondences(2000, &random);
  std::normal_distribution<double> gauss(0.0, 1.0);
  for (size_t i = 0; i < near.size(); ++i) {
    // 5 mm of noise and a slow warp along the normal: structure for the correlogram to find.
    const Point& p = near.source[i];
    near.target_mean[i] +=
        (0.005 * gauss(random) + 0.004 * std::sin(p.x() + 2.0 * p.y())) * near.normal[i];
  }
  const double sigma_squared = 5e-5, nu = 5.0;
  Matrix6d reference;
  ASSERT_TRUE(
      computePoseCovariance(near, Eigen::Isometry3d::Identity(), sigma_squared, nu, &reference));
  const double reference_t = expectedError(reference).translation;
  const double reference_r = expectedError(reference).rotation;
  for (const Eigen::Vector3d& offset :
       {Eigen::Vector3d(50.0, -20.0, 3.0), Eigen::Vector3d(1000.0, 400.0, 0.0)}) {
    // The same moved points: source coordinates shifted by -offset, the pose by +offset.
    WeightedCorrespondences far = near;
    for (Point& p : far.source) p -= offset;
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.translation() = offset;
    Matrix6d covariance;
    ASSERT_TRUE(computePoseCovariance(far, T, sigma_squared, nu, &covariance));
    // A rotation w about the far origin is the same rotation about the near one plus a shift
    // w x (near - far): v_near = v_far + offset x w.
    Matrix6d to_near = Matrix6d::Identity();
    to_near.topRightCorner<3, 3>() << 0.0, -offset.z(), offset.y(), offset.z(), 0.0, -offset.x(),
        -offset.y(), offset.x(), 0.0;
    const ExpectedError e = expectedError(to_near * covariance * to_near.transpose());
    EXPECT_NEAR(e.rotation / reference_r, 1.0, 1e-3) << "origin at " << offset.transpose();
    EXPECT_NEAR(e.translation / reference_t, 1.0, 1e-3) << "origin at " << offset.transpose();
  }
}

// End to end: simulated maps with an exact ground truth, aligned from a 5 deg / 0.25 m seed with
// the defaults. |error| / sigma for translation and rotation, as pda_covariance_check reports it.
struct CovarianceCheck {
  double t_ratio = 0.0, r_ratio = 0.0;
  RegistrationResult result;
};

CovarianceCheck alignAndCompare(const simulation::MapSimulationOptions& options) {
  const simulation::SimulatedMaps maps = simulation::simulateMaps(options);
  PdaRegistration registration{RegistrationParameters()};
  CovarianceCheck check;
  EXPECT_TRUE(registration.setTarget(maps.dense));
  Eigen::Isometry3d seed = maps.T_target_source;
  seed.linear() =
      Eigen::AngleAxisd(5.0 * M_PI / 180.0, Eigen::Vector3d(1, 2, 3).normalized()) * seed.linear();
  seed.translation() += Eigen::Vector3d(0.15, -0.15, 0.1);
  check.result = registration.align(maps.sparse, seed);
  EXPECT_TRUE(check.result.converged) << check.result.reason;
  const ExpectedError expected = expectedError(check.result.covariance);
  const Eigen::Isometry3d& T = check.result.T_target_source;
  check.t_ratio =
      (T.translation() - maps.T_target_source.translation()).norm() / expected.translation;
  check.r_ratio =
      Eigen::AngleAxisd(T.linear() * maps.T_target_source.linear().transpose()).angle() /
      expected.rotation;
  return check;
}

// The office (Kinect 2 map, VLP-16 scan): the reported covariance matches the error made.
TEST(PoseCovariance, SimulatedOfficeErrorIsWithinHalfToTwiceTheReportedSigma) {
  simulation::MapSimulationOptions options;
  options.seed = 11;
  const CovarianceCheck check = alignAndCompare(options);
  EXPECT_GT(check.result.covariance_correlation_length, 0.0);
  EXPECT_GT(check.t_ratio, 0.5);
  EXPECT_LT(check.t_ratio, 2.0);
  EXPECT_GT(check.r_ratio, 0.5);
  EXPECT_LT(check.r_ratio, 2.0);
  EXPECT_LT(check.result.covariance_ms, 0.1 * check.result.time_ms);
}

// A pair of simulated RGB-D fragments (Kinect scans of the first and the last 60 % of the
// office's walkway) with the dense one warped by 1 % (pda_simulate --sparse-sensor kinect
// --distortion 0.01); the ground truth is the warp's best rigid fit. The halves of the overlap
// disagree as wholes, at a scale the correlogram does not reach: before the cut halves were
// tested (map_scale_spread.hpp), sigma was 3.5x smaller than the translation error here; now
// 1.6x (1.8x before the least-squares polish of warp_polish.hpp moved the estimate; 1.2x since the
// refine runs read the normals at the candidates, in the benchmark at dc946fd). The bound is
// the hard one: no sigma more than 3x smaller than the error.
TEST(PoseCovariance, WarpedRgbdFragmentSigmaIsNotThreeTimesSmallerThanTheError) {
  simulation::MapSimulationOptions options;
  options.seed = 2;
  options.sparse_sensor = simulation::SparseSensor::kKinectFragment;
  options.distortion = 0.01;
  const CovarianceCheck check = alignAndCompare(options);
  std::printf("warped fragments: |t error| / sigma_t %.2f, |r error| / sigma_r %.2f\n",
              check.t_ratio, check.r_ratio);
  EXPECT_GT(check.t_ratio, 0.3);
  EXPECT_LT(check.t_ratio, 3.0);
  EXPECT_GT(check.r_ratio, 0.3);
  EXPECT_LT(check.r_ratio, 3.0);
}

// |error| / sigma of three noise draws of the outdoor scene of seed 3 with a 64-beam dense map
// (kept whole, as pda_simulate does), each sorted, printed under `name`; their medians must be
// within [0.5, 2].
struct DrawRatios {
  std::vector<double> t, r;
};
DrawRatios outdoorDraws(bool same_pose, const char* name) {
  DrawRatios ratios;
  for (uint64_t draw = 1; draw <= 3; ++draw) {
    simulation::MapSimulationOptions options;
    options.seed = 3;
    options.noise_seed = draw;
    options.scene = simulation::SceneKind::kOutdoor;
    options.dense_sensor = simulation::DenseSensor::kLidar64;
    options.same_pose = same_pose;
    options.dense_voxel_size = 0.0;
    const CovarianceCheck check = alignAndCompare(options);
    ratios.t.push_back(check.t_ratio);
    ratios.r.push_back(check.r_ratio);
  }
  std::sort(ratios.t.begin(), ratios.t.end());
  std::sort(ratios.r.begin(), ratios.r.end());
  std::printf(
      "%s, three draws: |t error| / sigma_t %.2f %.2f %.2f, |r error| / sigma_r %.2f %.2f %.2f\n",
      name, ratios.t[0], ratios.t[1], ratios.t[2], ratios.r[0], ratios.r[1], ratios.r[2]);
  // One noise draw is one error, so the draws are pooled (median), as pda_covariance_check
  // --pool-draws does.
  EXPECT_GT(ratios.t[1], 0.5);
  EXPECT_LT(ratios.t[1], 2.0);
  EXPECT_GT(ratios.r[1], 0.5);
  EXPECT_LT(ratios.r[1], 2.0);
  return ratios;
}

// A car park (64-beam lidar map, VLP-16 scan): a 360-degree scan's residuals are correlated along
// each ring over tens of metres and cancel between its sides. The 40-block sandwich counted
// blocks of ~20 m as independent and was too cautious here (medians 0.58 / 0.18 over these
// three draws: the rotation fails); the correlogram sees the cancelling (0.95 / 0.99). One noise
// draw is one error, so three are pooled (median), as pda_covariance_check --pool-draws does.
TEST(PoseCovariance, SimulatedCarParkErrorIsWithinHalfToTwiceTheReportedSigma) {
  outdoorDraws(false, "car park");
}

// A same-sensor lattice (a 64-beam map accumulated at the scan's own pose, the same azimuth
// grid): each source point's posterior spreads over the lattice's samples, which are as far apart
// as the noise. With the complete-data information alone sigma was 3x smaller than the error
// (these three draws: translation 1.56 / 2.02 / 4.97, rotation 2.44 / 2.98 / 3.66); with the
// observed information 0.55 / 0.72 / 1.93 and 1.49 / 1.89 / 2.16.
TEST(PoseCovariance, SimulatedSameSensorLatticeErrorIsWithinHalfToTwiceTheReportedSigma) {
  const DrawRatios ratios = outdoorDraws(true, "64-beam lattice");
  EXPECT_LT(ratios.t[2], 3.0);  // no draw's error more than 3x its sigma
}

}  // namespace
}  // namespace pda_registration
