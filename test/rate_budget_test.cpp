// The source budget that keeps up with the sparse clouds' rate (ros/rate_budget.hpp), driven by
// a simulated alignment whose time grows linearly with its source points.
#include "pda_registration/ros/rate_budget.hpp"

#include <gtest/gtest.h>

#include <cstddef>

namespace pda_registration {
namespace {

constexpr size_t kCap = 15000;
constexpr double kShare = 0.5;

// Clouds every `period` seconds from t = 0.
void arrive(RateBudget* budget, double period, int clouds, double start = 0.0) {
  for (int i = 0; i < clouds; ++i) budget->noteArrival(start + i * period);
}

// Aligns `count` times at `ms_per_point`; returns the last budget.
size_t alignRepeatedly(RateBudget* budget, double ms_per_point, int count, size_t source_points) {
  for (int i = 0; i < count; ++i) {
    const size_t used = std::min(source_points, budget->budget(kCap, kShare));
    budget->noteAlignment(ms_per_point * static_cast<double>(used), used, kCap, kShare);
  }
  return budget->budget(kCap, kShare);
}

TEST(RateBudget, IsTheCapUntilThePeriodIsKnown) {
  RateBudget budget;
  EXPECT_EQ(budget.budget(kCap, kShare), kCap);
  arrive(&budget, 0.1, 3);  // two intervals: not yet a rate
  EXPECT_EQ(budget.period(), 0.0);
  budget.noteAlignment(400.0, kCap, kCap, kShare);
  EXPECT_EQ(budget.budget(kCap, kShare), kCap);
  budget.noteArrival(0.3);
  EXPECT_NEAR(budget.period(), 0.1, 1e-9);
}

TEST(RateBudget, ShrinksUntilAnAlignmentFitsItsShareOfThePeriod) {
  RateBudget budget;
  arrive(&budget, 0.1, 20);  // 10 Hz: an alignment may take 50 ms
  // 100 ms for the whole budget: 7500 points fit.
  const double ms_per_point = 100.0 / kCap;
  budget.noteAlignment(100.0, kCap, kCap, kShare);
  const size_t first = budget.budget(kCap, kShare);
  EXPECT_LT(first, kCap);
  EXPECT_GT(first, 7500u);  // halfway (geometrically): one slow alignment does not halve it
  const size_t settled = alignRepeatedly(&budget, ms_per_point, 20, 30000);
  EXPECT_NEAR(static_cast<double>(settled), 7500.0, 100.0);
  EXPECT_LE(ms_per_point * static_cast<double>(settled), 50.0 * 1.02);
}

TEST(RateBudget, NeverBelowAQuarterOfTheCapAndGrowsBackWhenAlignmentsAreFast) {
  RateBudget budget;
  arrive(&budget, 0.1, 20);
  EXPECT_EQ(alignRepeatedly(&budget, 1.0, 30, 30000), kCap / 4);  // 1 ms per point: never fits
  EXPECT_EQ(alignRepeatedly(&budget, 0.001, 30, 30000), kCap);    // then 15 ms for the cap
}

TEST(RateBudget, ASourceSmallerThanTheBudgetThatFitsKeepsIt) {
  RateBudget budget;
  arrive(&budget, 0.1, 20);
  budget.noteAlignment(100.0, kCap, kCap, kShare);
  const size_t shrunk = budget.budget(kCap, kShare);
  budget.noteAlignment(10.0, 1000, kCap, kShare);  // a small cloud, fast
  EXPECT_EQ(budget.budget(kCap, kShare), shrunk);
}

TEST(RateBudget, OffWithoutShareOrCapAndALoweredCapAppliesAtOnce) {
  RateBudget budget;
  arrive(&budget, 0.1, 20);
  budget.noteAlignment(400.0, kCap, kCap, 0.0);
  EXPECT_EQ(budget.budget(kCap, 0.0), kCap);
  EXPECT_EQ(budget.budget(0, kShare), 0u);  // no budget at all stays none
  budget.noteAlignment(100.0, kCap, kCap, kShare);
  EXPECT_EQ(budget.budget(1000, kShare), 1000u);
}

TEST(RateBudget, GapsInTheStreamAreNotItsRate) {
  RateBudget budget;
  for (double t : {0.0, 10.0, 20.0, 30.0, 40.0}) budget.noteArrival(t);  // a bag paused, or 0.1 Hz
  EXPECT_EQ(budget.period(), 0.0);
  budget.noteAlignment(400.0, kCap, kCap, kShare);
  EXPECT_EQ(budget.budget(kCap, kShare), kCap);
  budget.noteArrival(39.0);  // the clock jumped back (a bag looped): ignored
  EXPECT_EQ(budget.period(), 0.0);
}

}  // namespace
}  // namespace pda_registration
