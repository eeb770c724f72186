// The runs' tail (run_tail.hpp): how far linearly converging runs still have to go, read from
// their last two steps; and, on a real case, refine and approach stages that end on it.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "pda_registration/core/error_metrics.hpp"
#include "pda_registration/core/pda_registration.hpp"
#include "pda_registration/core/perturbation.hpp"
#include "pda_registration/core/point_filter.hpp"
#include "pda_registration/core/run_tail.hpp"
#include "test_support/shared_data.hpp"

namespace pda_registration {
namespace {

Eigen::Isometry3d at(double x, double y) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation() = Eigen::Vector3d(x, y, 0.0);
  return T;
}

// Feeds runs ending at the given (x, y), from the origin; returns each run's distance to go.
std::vector<double> toGo(const std::vector<std::pair<double, double>>& ends) {
  RunTail tail(PoseStep(Point::Zero(), 1.0));
  std::vector<double> out;
  Eigen::Isometry3d before = Eigen::Isometry3d::Identity();
  for (const auto& end : ends) {
    const Eigen::Isometry3d after = at(end.first, end.second);
    out.push_back(tail.record(before, after));
    before = after;
  }
  return out;
}

TEST(RunTail, ALinearSequenceHasItsGeometricTailLeft) {
  // Steps of 4, 2, 1 mm one way: half each time, so as far again as the last step is left.
  const std::vector<double> left = toGo({{0.004, 0.0}, {0.006, 0.0}, {0.007, 0.0}});
  EXPECT_TRUE(std::isinf(left[0]));  // one step says nothing about the next
  EXPECT_NEAR(left[1], 0.002, 1e-12);
  EXPECT_NEAR(left[2], 0.001, 1e-12);
}

TEST(RunTail, ASlideHasNoTailToRead) {
  // Equal or growing steps one way: a slide, however small its steps, runs on.
  for (const double growth : {1.0, 1.5}) {
    std::vector<std::pair<double, double>> ends;
    double x = 0.0, step = 0.0004;
    for (int i = 0; i < 6; ++i) {
      x += step;
      step *= growth;
      ends.emplace_back(x, 0.0);
    }
    // Equal steps in floating point shrink by ~1e-16 at most: a tail of metres, not a rest.
    for (const double left : toGo(ends)) EXPECT_GT(left, 1.0) << growth;
  }
}

TEST(RunTail, StepsThatTurnLeaveAboutAStep) {
  // There and back (candidate sets flipping between neighbours): no heading, the jitter's size.
  const std::vector<double> left = toGo({{0.0005, 0.0}, {0.0, 0.0}, {0.0, 0.0003}});
  EXPECT_NEAR(left[1], 0.0005, 1e-12);
  EXPECT_NEAR(left[2], 0.0003, 1e-12);
}

TEST(RunTail, ResetForgetsTheStepBefore) {
  RunTail tail(PoseStep(Point::Zero(), 1.0));
  tail.record(at(0.0, 0.0), at(0.004, 0.0));
  tail.reset();
  EXPECT_TRUE(std::isinf(tail.record(at(0.004, 0.0), at(0.006, 0.0))));
  EXPECT_NEAR(tail.record(at(0.006, 0.0), at(0.007, 0.0)), 0.001, 1e-12);
}

// room_scan's 16-row scan on its dense map thinned to `voxel`, from ten perturbations at 5 deg:
// each converged and as near the truth as before (1.7-2 cm; the ground truth is good to about
// 1 cm / 0.5 deg). Each alignment's traced runs go into *runs_per_seed.
void traceTheThinnedRoom(double voxel, std::vector<std::vector<RunRecord>>* runs_per_seed) {
  testing_support::SharedCase c;
  std::string error;
  ASSERT_TRUE(testing_support::loadSharedCase("room_scan", &c, &error)) << error;
  PdaRegistration registration{RegistrationParameters()};
  std::vector<RunRecord> runs;
  AlignmentTrace trace;
  trace.run = [&runs](const RunRecord& r) { runs.push_back(r); };
  registration.setTrace(trace);
  ASSERT_TRUE(registration.setTarget(voxelDownsample(c.target, voxel)));
  for (uint64_t seed = 1; seed <= 10; ++seed) {
    runs.clear();
    const Eigen::Isometry3d initial = c.T_target_source * randomPerturbation(5.0, 0.25, seed);
    const RegistrationResult r = registration.align(c.source, initial);
    ASSERT_TRUE(r.converged) << "seed " << seed << ": " << r.reason;
    const PoseError e = poseError(c.source, r.T_target_source, c.T_target_source);
    EXPECT_LT(e.mean_distance, 0.03) << "seed " << seed;
    ASSERT_FALSE(runs.empty()) << "seed " << seed;
    runs_per_seed->push_back(runs);
  }
}

// On the 0.5-m map sigma is 0.15 m, and the refine runs used to go on moving 0.2-0.9 mm (a
// thousandth of sigma) until a step fell below 0.1 mm. The stage now ends on its tail where one
// is left: every last run moves less than the negligible tail, and some end still moving more
// than the epsilons (4 of 10 since the parent-voxel normals, whose refine runs settle faster: the
// rest fall below the epsilons first).
TEST(RunTail, TheThinnedRoomEndsItsRefineRunsOnTheTail) {
  std::vector<std::vector<RunRecord>> runs_per_seed;
  ASSERT_NO_FATAL_FAILURE(traceTheThinnedRoom(0.5, &runs_per_seed));
  int ended_on_tail = 0;
  for (const std::vector<RunRecord>& runs : runs_per_seed) {
    const RunRecord& last = runs.back();
    EXPECT_EQ(std::string(last.stage), "refine");
    EXPECT_LT(last.step_translation, kNegligibleTailSigmas * last.sigma);
    ended_on_tail += last.step_translation > RegistrationParameters().translation_epsilon;
  }
  EXPECT_GE(ended_on_tail, 2)
      << "the refine runs ended on a step below the epsilons, not on their tail";
}

// The approach ends on its tail too (10 % of sigma, as the settle stage): on the room's 0.25-m map
// its last runs moved 1-3 mm at sigma 7 cm, a few hundredths of it, each of them a full run of
// EM on the subset, and the settle stage then moved the estimate by as much again. Now some
// approaches end with a step still above their 10 epsilons, and every answer is as near the
// truth as before.
TEST(RunTail, TheThinnedRoomsApproachEndsOnItsTail) {
  std::vector<std::vector<RunRecord>> runs_per_seed;
  ASSERT_NO_FATAL_FAILURE(traceTheThinnedRoom(0.25, &runs_per_seed));
  int ended_on_tail = 0;
  for (const std::vector<RunRecord>& runs : runs_per_seed) {
    const RunRecord* last_approach = nullptr;
    for (const RunRecord& run : runs) {
      if (std::string(run.attempt) == "first" && std::string(run.stage) == "approach") {
        last_approach = &run;
      }
    }
    ASSERT_NE(last_approach, nullptr);
    ended_on_tail += last_approach->step_translation >
                     10.0 * RegistrationParameters().translation_epsilon;
  }
  EXPECT_GE(ended_on_tail, 3) << "the approaches ended on steps below their 10 epsilons";
}

}  // namespace
}  // namespace pda_registration
