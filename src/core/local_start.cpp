#include "pda_registration/core/local_start.hpp"

#include <cmath>

#include "pda_registration/core/degrees_of_freedom.hpp"

namespace pda_registration {

bool localStartWarranted(const RegistrationResult& first, const RegistrationParameters& p,
                         double moved_from_seed) {
  if (first.out_of_time || p.max_runs <= 1 || p.sigma_mode != SigmaMode::kEstimated ||
      first.source_points_used < static_cast<size_t>(p.min_correspondences)) {
    return false;
  }
  if (!first.converged) return true;
  return nuEstimatedAtFloor(p, first.nu) && moved_from_seed >= p.radius;
}

double rmsDisplacement(const PointList& source, const Eigen::Isometry3d& T_a,
                       const Eigen::Isometry3d& T_b) {
  if (source.empty()) return 0.0;
  double sum = 0.0;
  for (const Point& x : source) sum += (T_a * x - T_b * x).squaredNorm();
  return std::sqrt(sum / static_cast<double>(source.size()));
}

bool localStartStaysNear(const PointList& source, const Eigen::Isometry3d& T,
                         const Eigen::Isometry3d& T_initial, const RegistrationParameters& p) {
  return rmsDisplacement(source, T, T_initial) < p.radius;
}

}  // namespace pda_registration
