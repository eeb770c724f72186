#pragma once
// The nodelet's ~initial_transform parameter: a list of numbers read from the parameter server,
// turned into a rigid transform. Its own file so the parser can be tested and fuzzed without a
// roscore.

#include <Eigen/Geometry>
#include <string>
#include <vector>

namespace pda_registration {

/// 16 numbers (4x4 row-major), 6 (x y z roll pitch yaw) or 7 (x y z qx qy qz qw). False with a
/// one-line reason on NaN/Inf, a non-rotation 3x3 block, a zero quaternion or another count.
bool initialTransformFromList(const std::vector<double>& values, Eigen::Isometry3d* T,
                              std::string* error);

}  // namespace pda_registration
