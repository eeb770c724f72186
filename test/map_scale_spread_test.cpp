// The map-scale terms of the pose covariance (map_scale_spread.hpp) on a linearised problem whose
// answer is known: a closed room's six surfaces, residuals along their normals.
#include "pda_registration/core/map_scale_spread.hpp"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <vector>

#include "pda_registration/core/noise_model.hpp"
#include "pda_registration/core/pose_covariance.hpp"

namespace pda_registration {
namespace {

// Points on the floor, ceiling and four walls of a 6 x 6 x 3 m room, with their normals: each
// half of the room, cut along any axis, constrains every pose direction on its own.
struct Room {
  PointList points, normals;
};

Room closedRoom(size_t per_surface, std::mt19937_64* random) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Room room;
  for (int surface = 0; surface < 6; ++surface) {
    for (size_t i = 0; i < per_surface; ++i) {
      const double a = 6.0 * u(*random), b = 6.0 * u(*random), h = 3.0 * u(*random);
      const double side = surface % 2 == 0 ? 0.0 : 1.0;
      Point point, normal;
      if (surface < 2) {
        point = Point(a, b, 3.0 * side);
        normal = Point::UnitZ();
      } else if (surface < 4) {
        point = Point(a, 6.0 * side, h);
        normal = Point::UnitY();
      } else {
        point = Point(6.0 * side, b, h);
        normal = Point::UnitX();
      }
      room.points.push_back(point);
      room.normals.push_back(normal);
    }
  }
  return room;
}

constexpr double kInverseKappa = 0.01;
const Eigen::Vector3d kCentre(3.0, 3.0, 1.5);

// Octant sums at the least-squares optimum of residuals `along` (one per point, along its
// normal), with rotations about the room's centre; *step is the optimum's offset from the truth.
OctantPartition octantsAtOptimum(const Room& room, const std::vector<double>& along,
                                 Matrix6d* hessian, Vector6d* step) {
  OctantPartition octants;
  hessian->setZero();
  Vector6d score = Vector6d::Zero();
  for (size_t i = 0; i < room.points.size(); ++i) {
    const PoseJacobian j = poseJacobian(room.points[i] - kCentre);
    const Eigen::Matrix3d shape = shapeInverse(room.normals[i], kInverseKappa);
    OctantSums& octant = octants[octantOf(room.points[i], kCentre)];
    octant.hessian += j.transpose() * shape * j;
    octant.score += j.transpose() * shape * (along[i] * room.normals[i]);
    ++octant.points;
  }
  for (const OctantSums& octant : octants) *hessian += octant.hessian, score += octant.score;
  *step = hessian->ldlt().solve(score);
  // The linearised scores at the optimum: g_o - H_o step (they sum to zero).
  for (OctantSums& octant : octants) octant.score -= octant.hessian * *step;
  return octants;
}

TEST(MapScaleSpread, IndependentHalvesGiveTheCovarianceOfTheWholeEstimate) {
  // The halves of a room hold different surfaces (one x wall each): the naive (d_low - d_high)^2 /
  // 4 of equal halves would not do. Averaged over draws, each cut's matrix is the spread of the
  // whole estimate.
  std::mt19937_64 random(5);
  const Room room = closedRoom(500, &random);
  std::normal_distribution<double> gauss(0.0, 0.01);
  const int draws = 400;
  Matrix6d empirical = Matrix6d::Zero();
  std::vector<Matrix6d> mean_cuts(3, Matrix6d::Zero());
  for (int d = 0; d < draws; ++d) {
    std::vector<double> along(room.points.size());
    for (double& a : along) a = gauss(random);
    Matrix6d hessian;
    Vector6d step;
    const OctantPartition octants = octantsAtOptimum(room, along, &hessian, &step);
    empirical += step * step.transpose() / draws;
    const std::vector<Matrix6d> cuts =
        halfSplitDisagreements(octants, hessian.inverse(), Eigen::Vector3d(6.0, 6.0, 3.0));
    ASSERT_EQ(cuts.size(), 3u);  // the height is half the room's width: every axis is long
    for (size_t c = 0; c < 3; ++c) mean_cuts[c] += cuts[c] / draws;
  }
  for (size_t c = 0; c < 3; ++c) {
    const double translation =
        mean_cuts[c].topLeftCorner<3, 3>().trace() / empirical.topLeftCorner<3, 3>().trace();
    const double rotation = mean_cuts[c].bottomRightCorner<3, 3>().trace() /
                            empirical.bottomRightCorner<3, 3>().trace();
    EXPECT_NEAR(translation, 1.0, 0.2) << "cut " << c;
    EXPECT_NEAR(rotation, 1.0, 0.2) << "cut " << c;
  }
}

TEST(MapScaleSpread, ThinAxesAndSmallHalvesAreNotCut) {
  std::mt19937_64 random(6);
  const Room room = closedRoom(300, &random);
  std::vector<double> along(room.points.size(), 0.0);
  Matrix6d hessian;
  Vector6d step;
  OctantPartition octants = octantsAtOptimum(room, along, &hessian, &step);
  // A room 40 m long and 3 m high: only its length is cut.
  const Eigen::Vector3d extent(40.0, 6.0, 3.0);
  EXPECT_EQ(halfSplitDisagreements(octants, hessian.inverse(), extent).size(), 1u);
  // A half with under a tenth of the points is no sample of the map.
  for (int o = 0; o < 8; ++o) {
    if (o & 1) octants[o].points = 1;
  }
  EXPECT_EQ(halfSplitDisagreements(octants, hessian.inverse(), extent).size(), 0u);
}

// As the E-step hands them over: one correspondence per point, its target mean moved along the
// normal by `along`.
WeightedCorrespondences correspondencesOf(const Room& room, const std::vector<double>& along) {
  WeightedCorrespondences c;
  for (size_t i = 0; i < room.points.size(); ++i) {
    c.source.push_back(room.points[i]);
    c.target_mean.push_back(room.points[i] + along[i] * room.normals[i]);
    c.normal.push_back(room.normals[i]);
    c.weight.push_back(1.0);
    c.inverse_kappa.push_back(kInverseKappa);
    c.source_index.push_back(i);
  }
  return c;
}

// A map bent over its length (floor and ceiling rise along x as x |x|, as a drifting map's ends
// do): the two halves along x disagree as wholes, and the covariance takes that cut in. With
// white noise alone the test rarely fires (2 of 40 draws here).
TEST(MapScaleSpread, ABentMapWidensTheCovarianceAndWhiteNoiseDoesNot) {
  std::mt19937_64 random(9);
  const Room room = closedRoom(800, &random);
  std::normal_distribution<double> gauss(0.0, 0.005);
  const double gaussian = std::numeric_limits<double>::infinity();
  int noise_cuts = 0;
  const int draws = 40;
  for (int d = 0; d < draws; ++d) {
    std::vector<double> along(room.points.size());
    for (double& a : along) a = gauss(random);
    Matrix6d covariance;
    PoseCovarianceTerms terms;
    ASSERT_TRUE(computePoseCovariance(correspondencesOf(room, along), Eigen::Isometry3d::Identity(),
                                      2.5e-5, gaussian, &covariance, &terms));
    noise_cuts += terms.disagreeing_cuts > 0;
  }
  std::printf("white noise: a cut taken in %d of %d draws\n", noise_cuts, draws);
  EXPECT_LE(noise_cuts, draws / 5);  // a 1-in-20 test per cut, three cuts

  // The bend: +-2 cm at the room's ends along x on the floor and ceiling, plus the noise.
  std::vector<double> along(room.points.size());
  for (size_t i = 0; i < along.size(); ++i) {
    const double x = room.points[i].x() - 3.0;
    along[i] = gauss(random) + (room.normals[i].z() != 0.0 ? 0.02 * x * std::abs(x) / 9.0 : 0.0);
  }
  const WeightedCorrespondences bent = correspondencesOf(room, along);
  Matrix6d covariance;
  PoseCovarianceTerms terms;
  ASSERT_TRUE(computePoseCovariance(bent, Eigen::Isometry3d::Identity(), 2.5e-5, gaussian,
                                    &covariance, &terms));
  EXPECT_GE(terms.disagreeing_cuts, 1u);
  // Taken into the bound, never subtracted: at least the noise term in every direction.
  const Eigen::SelfAdjointEigenSolver<Matrix6d> excess(covariance - terms.model);
  EXPECT_GT(excess.eigenvalues().minCoeff(), -1e-12 * covariance.norm());
}

}  // namespace
}  // namespace pda_registration
