#pragma once
// Whether a stage's runs have come to rest without a step below its epsilons. On a coarse
// target (a map thinned to 0.5 m voxels) a few candidate sets flip between two neighbours from
// run to run and the estimate cycles between two poses 0.2-0.6 mm apart for ever: room_scan's
// refine stage ran into the work bound that way and came back "not converged" at 2.6 cm from the
// truth. A run sequence at rest comes back on itself: over the last kWindow runs the estimate
// ends less than a third of the path it travelled away from where it began. A slide (steps one
// way, however small, as on a wide-sigma plateau before the collapse onto the truth) travels
// nearly its whole path and is left alone; so are the extrapolated jumps, which count as path.
// The approach and settle stages cycle too (the first 1M points of a growing office map: two
// poses 1.4 mm apart, above their 10 epsilons): there it ends the stage, in refine the alignment.
// kWindow is 4, the fewest runs that show a two-pose cycle twice. 6 waited two runs more on every
// cycle: a wide VLP-16 pair's settle stage cycled 1 cm at sigma 0.13 m for 6 runs (176 -> 155 ms
// with 4); on the benchmark's 20 deg rows the successes were the same or one more.

#include <Eigen/Geometry>
#include <deque>
#include <utility>

#include "pda_registration/core/pose_step.hpp"

namespace pda_registration {

class RunRest {
 public:
  static constexpr int kWindow = 4;
  static constexpr double kMaxNetFraction = 1.0 / 3.0;

  explicit RunRest(PoseStep metric) : metric_(std::move(metric)) {}

  /// Forget the runs so far (a new stage).
  void reset() { steps_.clear(); }

  /// A run moved the estimate from `before` to `after` (`after` is where the next run starts);
  /// true when the last kWindow runs came back on themselves.
  bool cameBack(const Eigen::Isometry3d& before, const Eigen::Isometry3d& after);

 private:
  struct Run {
    Eigen::Isometry3d before;
    double length;
  };
  PoseStep metric_;
  std::deque<Run> steps_;
};

}  // namespace pda_registration
