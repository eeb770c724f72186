#include "pda_registration/core/turned_start.hpp"

#include <algorithm>
#include <cmath>

namespace pda_registration {

Eigen::Isometry3d turnedAboutSensor(const Eigen::Isometry3d& T_initial, double degrees) {
  Eigen::Isometry3d turn = Eigen::Isometry3d::Identity();
  turn.linear() =
      Eigen::AngleAxisd(degrees * M_PI / 180.0, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const Eigen::Vector3d sensor = T_initial.translation();
  turn.translation() = sensor - turn.linear() * sensor;
  return turn * T_initial;
}

double shareWithinReach(const TargetIndex& index, const PointList& points,
                        const Eigen::Isometry3d& T, double reach, int threads) {
  if (points.empty()) return 0.0;
  size_t within = 0;
#pragma omp parallel for schedule(dynamic, 256) reduction(+ : within) \
    num_threads(std::max(threads, 1))
  for (long long j = 0; j < static_cast<long long>(points.size()); ++j) {
    size_t nearest = 0;
    double squared_distance = 0.0;
    if (index.nearestWithinRadius(T * points[j], 1, reach, &nearest, &squared_distance) > 0) {
      ++within;
    }
  }
  return static_cast<double>(within) / static_cast<double>(points.size());
}

int turnToTry(const std::array<double, kTurnDegrees.size()>& turn_shares, double seed_share) {
  const auto best = std::max_element(turn_shares.begin(), turn_shares.end());
  if (*best < seed_share) return -1;
  return static_cast<int>(best - turn_shares.begin());
}

}  // namespace pda_registration
