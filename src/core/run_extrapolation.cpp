#include "pda_registration/core/run_extrapolation.hpp"

#include <algorithm>
#include <cmath>

namespace pda_registration {
namespace {
constexpr double kMaxRatio = 0.95;  // beyond: too slow a shrink to trust its tail
constexpr double kMaxFactor = 8.0;  // the extrapolation never exceeds 8 of the last steps
}  // namespace

Eigen::Isometry3d RunExtrapolation::next(const Eigen::Isometry3d& before,
                                         const Eigen::Isometry3d& after, double min_step,
                                         double max_move) {
  const Step step = metric_.between(before, after);
  const double size = step.norm();
  if (!(size > min_step) || !step.allFinite()) {
    have_previous_ = false;
    agreeing_ = 0;
    return after;
  }
  if (!have_previous_) {  // every path that forgets the last step also zeroes agreeing_
    previous_ = step;
    have_previous_ = true;
    return after;
  }
  const StepSuccession follows = succession(previous_, step);
  const double ratio = follows.ratio;
  previous_ = step;
  if (!follows.sameDirection() || ratio >= kMaxRatio) {
    agreeing_ = 0;
    return after;
  }
  ++agreeing_;
  if (agreeing_ < agreements_needed_) return after;
  agreeing_ = 0;
  // The tail rho + rho^2 + ... of the last step, then two fresh steps before the next one.
  const double factor = std::min({ratio / (1.0 - ratio), kMaxFactor, max_move / size});
  have_previous_ = false;
  ++extrapolations_;
  const Eigen::AngleAxisd rotation(after.linear() * before.linear().transpose());
  const Point pivot = after * metric_.centroid();
  Eigen::Isometry3d extra = Eigen::Isometry3d::Identity();
  extra.linear() = Eigen::AngleAxisd(factor * rotation.angle(), rotation.axis()).toRotationMatrix();
  extra.translation() = pivot + factor * step.tail<3>() - extra.linear() * pivot;
  return extra * after;
}

}  // namespace pda_registration
