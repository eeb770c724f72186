#include "pda_registration/core/run_tail.hpp"

#include <cmath>

namespace pda_registration {

double RunTail::record(const Eigen::Isometry3d& before, const Eigen::Isometry3d& after) {
  constexpr double kUnknown = std::numeric_limits<double>::infinity();
  const PoseStep::Vector step = metric_.between(before, after);
  if (!step.allFinite()) {
    have_previous_ = false;
    return kUnknown;
  }
  const bool had_previous = have_previous_;
  const PoseStep::Vector previous = previous_;
  previous_ = step;
  have_previous_ = true;
  const double size = step.norm(), previous_size = previous.norm();
  if (!had_previous || !(previous_size > 0.0)) return kUnknown;
  if (!(size > 0.0)) return 0.0;
  const StepSuccession follows = succession(previous, step);
  // Steps that turn are not heading anywhere: the estimate jitters about its rest (candidate sets
  // that flip between neighbours), by about a step.
  if (!follows.sameDirection()) return size;
  if (follows.ratio >= 1.0) return kUnknown;
  return size * follows.ratio / (1.0 - follows.ratio);
}

}  // namespace pda_registration
