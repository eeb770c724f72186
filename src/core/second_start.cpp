#include "pda_registration/core/second_start.hpp"

#include <algorithm>
#include <cmath>

#include "pda_registration/core/degrees_of_freedom.hpp"

namespace pda_registration {

std::array<Eigen::Isometry3d, 2> secondStartPoses(const Eigen::Isometry3d& T_found,
                                                  const Eigen::Isometry3d& T_initial,
                                                  const Point& centroid) {
  std::array<Eigen::Isometry3d, 2> starts;
  for (Eigen::Isometry3d& start : starts) {
    start = Eigen::Isometry3d::Identity();
    start.linear() = T_found.linear();
  }
  starts[0].translation() = T_initial.translation();
  starts[1].translation() = T_initial * centroid - T_found.linear() * centroid;
  return starts;
}

bool secondStartWarranted(const RegistrationResult& first, const RegistrationParameters& p,
                          const Eigen::Isometry3d& T_initial, const Point& centroid,
                          double final_radius) {
  if (!first.converged || p.max_runs <= 1 || !nuEstimatedAtFloor(p, first.nu)) return false;
  const double centroid_moved = (first.T_target_source * centroid - T_initial * centroid).norm();
  return centroid_moved > final_radius;
}

bool FirstResultBasin::near(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) const {
  const double shift = (a * centroid - b * centroid).norm();
  const double angle = Eigen::AngleAxisd(b.linear() * a.linear().transpose()).angle();
  // Mean of |(R - I)(p - c)|^2 over the points is at most angle^2 times their mean squared
  // distance from the centroid, and the centroid's term adds to it (the cross term averages out).
  return std::hypot(shift, angle * source_rms_radius) < final_radius;
}

bool headingBack(double apart_at_start, double apart_now) {
  return apart_now < 0.5 * apart_at_start;
}

double commonYardstick(const RegistrationParameters& p, double sigma_first, double sigma_second) {
  return p.inlier_sigmas * std::min(sigma_first, sigma_second);
}

bool secondStartIsBetter(const RegistrationResult& second, double second_support,
                         double first_support) {
  return second.converged && !second.out_of_time && second_support > first_support;
}

}  // namespace pda_registration
