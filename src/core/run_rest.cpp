#include "pda_registration/core/run_rest.hpp"

namespace pda_registration {

bool RunRest::cameBack(const Eigen::Isometry3d& before, const Eigen::Isometry3d& after) {
  steps_.push_back({before, metric_.between(before, after).norm()});
  if (static_cast<int>(steps_.size()) > kWindow) steps_.pop_front();
  if (static_cast<int>(steps_.size()) < kWindow) return false;
  double path = 0.0;
  for (const Run& run : steps_) path += run.length;
  const double net = metric_.between(steps_.front().before, after).norm();
  return path > 0.0 && net < kMaxNetFraction * path;
}

}  // namespace pda_registration
