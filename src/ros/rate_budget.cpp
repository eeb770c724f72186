#include "pda_registration/ros/rate_budget.hpp"

#include <algorithm>
#include <cmath>

namespace pda_registration {
namespace {
// The running mean weighs the newest interval by this much: a stream that changes rate is
// followed within ~10 clouds; single late clouds barely move it.
constexpr double kIntervalWeight = 0.2;
constexpr int kIntervalsNeeded = 3;
}  // namespace

void RateBudget::noteArrival(double seconds) {
  std::lock_guard<std::mutex> lock(mutex_);
  const double interval = seconds - last_arrival_;
  const bool first = last_arrival_ < 0.0;
  last_arrival_ = seconds;
  if (first || !(interval > 0.0) || interval > kLongestInterval) return;  // gap or clock jump
  mean_interval_ = intervals_ == 0
                       ? interval
                       : (1.0 - kIntervalWeight) * mean_interval_ + kIntervalWeight * interval;
  ++intervals_;
}

double RateBudget::period() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return periodLocked();
}

double RateBudget::periodLocked() const {
  return intervals_ >= kIntervalsNeeded ? mean_interval_ : 0.0;
}

void RateBudget::noteAlignment(double ms, size_t points, size_t cap, double share) {
  std::lock_guard<std::mutex> lock(mutex_);
  const double period_s = periodLocked();
  if (cap == 0 || !(share > 0.0) || !(period_s > 0.0) || !(ms > 0.0) || points == 0) {
    budget_ = 0.0;
    return;
  }
  const double current = budget_ > 0.0 ? budget_ : static_cast<double>(cap);
  // A source smaller than the budget that fits says nothing about a larger one: keep it.
  const double target_ms = share * 1e3 * period_s;
  if (points < static_cast<size_t>(std::lround(current)) && ms <= target_ms) return;
  // Time grows about linearly with the source points (the runs' search and E-step).
  const double wanted = static_cast<double>(points) * target_ms / ms;
  const double next = std::sqrt(current * wanted);
  budget_ = std::clamp(next, static_cast<double>(floorOf(cap)), static_cast<double>(cap));
}

size_t RateBudget::budget(size_t cap, double share) const {
  std::lock_guard<std::mutex> lock(mutex_);
  if (cap == 0 || !(share > 0.0) || !(budget_ > 0.0)) return cap;
  return std::clamp(static_cast<size_t>(std::lround(budget_)), floorOf(cap), cap);
}

}  // namespace pda_registration
