#pragma once
// Reproducible initial-guess perturbations for tests and benchmarks: a rotation of exactly
// `angle_deg` about a random axis and a translation of exactly `translation` in a random
// direction, applied in the source frame: T_initial = T_ground_truth * delta.

#include <Eigen/Geometry>
#include <cstdint>

namespace pda_registration {

Eigen::Isometry3d randomPerturbation(double angle_deg, double translation, uint64_t seed);

}  // namespace pda_registration
