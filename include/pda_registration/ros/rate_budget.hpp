#pragma once
// The source budget that keeps up with the sparse clouds' rate. An alignment that takes longer
// than the time between two sparse clouds makes every later answer wait for the one before (a
// growing 3M-point office map: ~110 ms per 15k-point alignment at 10 Hz, latency climbing with
// the map). After each alignment the budget is scaled so that the next one takes about `share`
// of the measured period, between a quarter of max_source_points (the approach stage's own
// subset at the default coarse_stride) and max_source_points itself; it moves geometrically
// halfway at each step, so one slow alignment does not halve it. ROS-free: unit-tested.

#include <cstddef>
#include <mutex>

namespace pda_registration {

class RateBudget {
 public:
  /// A sparse cloud was accepted for alignment at `seconds` (wall clock). Intervals longer
  /// than kLongestInterval are gaps in the stream, not its rate.
  void noteArrival(double seconds);

  /// The period between sparse clouds [s]: a running mean of the last intervals, 0 until
  /// three have been seen.
  double period() const;

  /// After an alignment that used `points` source points and took `ms`: the budget for the
  /// next. `cap` is max_source_points (0: no budget, and none is set here either); `share`
  /// the part of the period an alignment may take (0: off, the budget is the cap).
  void noteAlignment(double ms, size_t points, size_t cap, double share);

  /// Source points for the next alignment: the cap until the period and one alignment are
  /// known, never above the cap (a lowered cap applies at once).
  size_t budget(size_t cap, double share) const;

  static constexpr double kLongestInterval = 5.0;  ///< [s]

 private:
  static size_t floorOf(size_t cap) { return cap / 4 > 0 ? cap / 4 : 1; }
  double periodLocked() const;  // period() with mutex_ held

  mutable std::mutex mutex_;
  double last_arrival_ = -1.0;
  double mean_interval_ = 0.0;
  int intervals_ = 0;
  double budget_ = 0.0;  ///< 0: not set yet
};

}  // namespace pda_registration
