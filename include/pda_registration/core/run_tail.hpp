#pragma once
// How far the runs still have to go, read from their last two steps. Near a fixed point the runs
// converge linearly: each step a fraction rho of the one before, in the same direction, so the
// distance still to go is the geometric tail rho / (1 - rho) of the last step. A stage may end
// once that tail is negligible against the residual scale sigma (a share of it far below what
// the pose's uncertainty, sigma over the root of the independent constraints, resolves) even
// while the step itself is still above the epsilons: on a target thinned to 0.5 m sigma is
// 0.15 m, and runs of 0.2-0.9 mm, a thousandth of it, only repeated the last digits. A slide
// (ratios near 1) has a long tail and runs on; steps that turn have no tail to read.

#include <Eigen/Geometry>
#include <limits>
#include <utility>

#include "pda_registration/core/pose_step.hpp"

namespace pda_registration {

/// The share of sigma below which the distance still to go no longer matters (the refine stage's;
/// the earlier stages take ten times it, as they take ten epsilons).
constexpr double kNegligibleTailSigmas = 0.01;

class RunTail {
 public:
  /// Steps are measured in `metric` (rotations as the displacement they cause over the source).
  explicit RunTail(PoseStep metric) : metric_(std::move(metric)) {}

  /// Forget the steps so far (a new stage, or a jump that was not a run's own step).
  void reset() { have_previous_ = false; }

  /// A run moved the estimate from `before` to `after` (its own step, before any extrapolation).
  /// Returns the distance still to go, in the metric: infinity unless this step and the one
  /// before point the same way and this one is shorter.
  double record(const Eigen::Isometry3d& before, const Eigen::Isometry3d& after);

 private:
  PoseStep metric_;
  bool have_previous_ = false;
  PoseStep::Vector previous_ = PoseStep::Vector::Zero();
};

}  // namespace pda_registration
