#pragma once
// Aitken extrapolation of the runs' sequence of estimates. Each run is one step of a fixed-point
// iteration (candidate sets, then EM); near a solution such iterations converge linearly, each
// step a fraction rho of the one before in the same direction, and on dense clouds rho is close
// to 1 (the Kinect pair: ~1 cm per run shrinking by ~0.9, 40+ runs). When two successive steps
// point the same way and shrink, their geometric tail rho / (1 - rho) times the last step is
// where the iteration is going; the next run starts there. A run that then turns back ends the
// extrapolation until two fresh steps agree again. Far from a solution (the approach stage, steps
// as wide as sigma) one ratio is weak evidence: there three steps must agree.

#include <Eigen/Geometry>
#include <utility>

#include "pda_registration/core/pose_step.hpp"

namespace pda_registration {

/// How far an extrapolation may go beyond the last estimate, in sigmas: about as far as the
/// candidate sets (or, within a run, the E-step's weights) still describe the clouds.
constexpr double kExtrapolationSigmas = 2.0;

class RunExtrapolation {
 public:
  /// Steps are compared in `metric`: rotations and translations weigh as the displacements
  /// they cause over the source.
  explicit RunExtrapolation(PoseStep metric) : metric_(std::move(metric)) {}

  /// Forget the steps so far (the runs' inputs changed: a new stage).
  void reset() {
    have_previous_ = false;
    agreeing_ = 0;
  }

  /// A run moved the estimate from `before` to `after`; returns where the next run starts
  /// (`after`, or beyond it along the steps' tail). Steps below `min_step` (in the metric above)
  /// are left alone: the iteration is about to converge on its own.
  Eigen::Isometry3d next(const Eigen::Isometry3d& before, const Eigen::Isometry3d& after,
                         double min_step, double max_move);

  int extrapolations() const { return extrapolations_; }

  /// How many successive pairs of steps must agree (same direction, shrinking) before the tail
  /// is taken: 1 = two steps (one ratio); 2 = three steps, whose two ratios must both say
  /// "linear". Far from a solution one ratio is weak evidence of the linear regime.
  void setAgreementsNeeded(int pairs) { agreements_needed_ = pairs < 1 ? 1 : pairs; }

 private:
  using Step = PoseStep::Vector;

  PoseStep metric_;
  bool have_previous_ = false;
  Step previous_ = Step::Zero();
  int agreeing_ = 0;  ///< successive pairs of steps that agreed since the last tail or reset
  int agreements_needed_ = 1;
  int extrapolations_ = 0;
};

}  // namespace pda_registration
