#include "pda_registration/core/run_tail.hpp"

#include <cmath>

namespace pda_registration {
namespace {
// Steps this close in direction (cosine) are one linear sequence (as for the extrapolation).
constexpr double kSameDirection = 0.9;
}  // namespace

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
  const double cosine = step.dot(previous) / (size * previous_size);
  const double ratio = size / previous_size;
  // Steps that turn are not heading anywhere: the estimate jitters about its rest (candidate sets
  // that flip between neighbours), by about a step.
  if (cosine < kSameDirection) return size;
  if (ratio >= 1.0) return kUnknown;
  return size * ratio / (1.0 - ratio);
}

}  // namespace pda_registration
