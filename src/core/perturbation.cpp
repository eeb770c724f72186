#include "pda_registration/core/perturbation.hpp"

#include <cmath>
#include <random>

namespace pda_registration {
namespace {
Eigen::Vector3d randomUnitVector(std::mt19937_64* generator) {
  std::normal_distribution<double> normal(0.0, 1.0);
  Eigen::Vector3d v;
  do {
    v = Eigen::Vector3d(normal(*generator), normal(*generator), normal(*generator));
  } while (v.norm() < 1e-6);
  return v.normalized();
}
}  // namespace

Eigen::Isometry3d randomPerturbation(double angle_deg, double translation, uint64_t seed) {
  std::mt19937_64 generator(seed);
  Eigen::Isometry3d delta = Eigen::Isometry3d::Identity();
  delta.linear() =
      Eigen::AngleAxisd(angle_deg * M_PI / 180.0, randomUnitVector(&generator)).toRotationMatrix();
  delta.translation() = translation * randomUnitVector(&generator);
  return delta;
}

}  // namespace pda_registration
