// Bad input never crashes and never throws out of the core: it gives converged = false and a
// reason that names the problem.
#include <gtest/gtest.h>

#include <cstring>
#include <limits>

#include "pda_registration/core/pda_registration.hpp"
#include "pda_registration/core/perturbation.hpp"
#include "test_support/synthetic_scene.hpp"

namespace pda_registration {
namespace {

using testing_support::makePlane;
using testing_support::makeSyntheticRoom;
using testing_support::SyntheticCase;
using testing_support::SyntheticOptions;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

RegistrationParameters roomParameters() {
  RegistrationParameters p;
  p.radius = 0.5;
  return p;
}

RegistrationResult alignExpectingFailure(PdaRegistration* registration, const PointList& source,
                                         const Eigen::Isometry3d& initial,
                                         const std::string& reason_part) {
  RegistrationResult r;
  EXPECT_NO_THROW(r = registration->align(source, initial));
  EXPECT_FALSE(r.converged);
  EXPECT_NE(r.reason.find(reason_part), std::string::npos) << "reason was: " << r.reason;
  // A failed alignment returns the seed unchanged (compared bitwise: the seed may hold NaN).
  EXPECT_EQ(0, std::memcmp(r.T_target_source.data(), initial.data(), sizeof(double) * 16));
  return r;
}

class BadInput : public ::testing::Test {
 protected:
  void SetUp() override {
    room_ = makeSyntheticRoom(SyntheticOptions());
    registration_.setParameters(roomParameters());
    ASSERT_TRUE(registration_.setTarget(room_.target));
  }
  SyntheticCase room_;
  PdaRegistration registration_;
};

TEST(BadTarget, EmptyTarget) {
  PdaRegistration registration(roomParameters());
  EXPECT_FALSE(registration.setTarget(PointList()));
  alignExpectingFailure(&registration, makeSyntheticRoom(SyntheticOptions()).source,
                        Eigen::Isometry3d::Identity(), "target cloud is empty");
}

TEST(BadTarget, NoTargetSetAtAll) {
  PdaRegistration registration(roomParameters());
  alignExpectingFailure(&registration, makeSyntheticRoom(SyntheticOptions()).source,
                        Eigen::Isometry3d::Identity(), "target cloud is empty");
}

TEST(BadTarget, AllNaNTarget) {
  PdaRegistration registration(roomParameters());
  EXPECT_FALSE(registration.setTarget(PointList(1000, Point(kNaN, 0.0, 1.0))));
  EXPECT_EQ(registration.targetPointsDropped(), 1000u);
  const RegistrationResult r =
      alignExpectingFailure(&registration, makeSyntheticRoom(SyntheticOptions()).source,
                            Eigen::Isometry3d::Identity(), "target cloud is empty");
  EXPECT_EQ(r.target_points_dropped, 1000u);
}

TEST_F(BadInput, EmptySource) {
  alignExpectingFailure(&registration_, PointList(), room_.T_target_source, "0 finite points");
}

TEST_F(BadInput, TinySource) {
  const PointList five(room_.source.begin(), room_.source.begin() + 5);
  alignExpectingFailure(&registration_, five, room_.T_target_source, "5 finite points");
}

TEST_F(BadInput, AllNaNSource) {
  const PointList nans(500, Point(kNaN, kNaN, kNaN));
  const RegistrationResult r =
      alignExpectingFailure(&registration_, nans, room_.T_target_source, "500 non-finite dropped");
  EXPECT_EQ(r.source_points_dropped, 500u);
}

TEST_F(BadInput, InfinitySourcePointsAreDroppedAndCounted) {
  PointList source = room_.source;
  for (size_t i = 0; i < source.size(); i += 10)
    source[i].y() = std::numeric_limits<double>::infinity();
  const RegistrationResult r = registration_.align(source, room_.T_target_source);
  EXPECT_TRUE(r.converged) << r.reason;
  EXPECT_EQ(r.source_points_dropped, (source.size() + 9) / 10);
  EXPECT_EQ(r.source_points_used, source.size() - r.source_points_dropped);
}

TEST_F(BadInput, NoCorrespondencesWithinRadius) {
  Eigen::Isometry3d far_away = room_.T_target_source;
  far_away.translation() += Eigen::Vector3d(100.0, 0.0, 0.0);
  alignExpectingFailure(&registration_, room_.source, far_away, "no overlap");
}

TEST_F(BadInput, NonRigidOrNaNInitialGuess) {
  Eigen::Isometry3d nan_guess = room_.T_target_source;
  nan_guess.translation().x() = kNaN;
  alignExpectingFailure(&registration_, room_.source, nan_guess, "initial transform");
  Eigen::Isometry3d scaled = room_.T_target_source;
  scaled.linear() *= 2.0;
  alignExpectingFailure(&registration_, room_.source, scaled, "initial transform");
  // Finite but huge: the orthonormality check computes Inf - Inf = NaN, which must not pass.
  Eigen::Isometry3d huge = room_.T_target_source;
  huge.linear() << 2.7e154, -3.4e221, 0, -3.4e221, -1.7e308, -1.2e217, -3.4e221, 0, -1.7e308;
  alignExpectingFailure(&registration_, room_.source, huge, "initial transform");
}

TEST_F(BadInput, AbsurdParameters) {
  RegistrationParameters p = roomParameters();
  p.k = 0;
  registration_.setParameters(p);
  alignExpectingFailure(&registration_, room_.source, room_.T_target_source, "k must be");
  p = roomParameters();
  p.radius = kNaN;
  registration_.setParameters(p);
  alignExpectingFailure(&registration_, room_.source, room_.T_target_source, "radius must be");
  p = roomParameters();
  p.nu = -1.0;
  registration_.setParameters(p);
  alignExpectingFailure(&registration_, room_.source, room_.T_target_source, "nu must be");
  p = roomParameters();
  p.solver = MStepSolver::kClosedForm;  // with the surface model (kappa > 1)
  registration_.setParameters(p);
  alignExpectingFailure(&registration_, room_.source, room_.T_target_source, "closed_form");
  p = roomParameters();
  p.threads = 100000;
  registration_.setParameters(p);
  alignExpectingFailure(&registration_, room_.source, room_.T_target_source, "threads");
}

// A single plane leaves in-plane translation and rotation about the normal unconstrained.
TEST(Degenerate, SinglePlaneIsReported) {
  const PointList plane = makePlane(4.0, 0.02);
  PointList source;
  for (size_t i = 0; i < plane.size(); i += 37) source.push_back(plane[i] + Point(0, 0, 0.01));
  PdaRegistration registration(roomParameters());
  ASSERT_TRUE(registration.setTarget(plane));
  RegistrationResult r;
  EXPECT_NO_THROW(r = registration.align(source, randomPerturbation(1.0, 0.05, 1)));
  EXPECT_FALSE(r.converged);
  EXPECT_NE(r.reason.find("degenerate geometry"), std::string::npos) << r.reason;
  EXPECT_GE(r.degeneracy_ratio, 0.0);
  EXPECT_LT(r.degeneracy_ratio, 1e-3);
}

// The room itself is well constrained: the same check must not fire there.
TEST_F(BadInput, WellConstrainedRoomIsNotDegenerate) {
  const RegistrationResult r = registration_.align(room_.source, room_.T_target_source);
  EXPECT_TRUE(r.converged) << r.reason;
  EXPECT_GT(r.degeneracy_ratio, 1e-2);
}

}  // namespace
}  // namespace pda_registration
