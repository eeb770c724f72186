#pragma once
// 4x4 row-major text matrices (p_target = T * p_source), the format of T_target_source.txt.

#include <Eigen/Geometry>
#include <string>

namespace pda_registration {

/// Parses 16 numbers (any whitespace, '#' comments allowed). Requires a finite rigid transform:
/// last row 0 0 0 1 and an orthonormal rotation (to 1e-3, then snapped). On failure returns
/// false and a one-line reason in *error.
bool parseTransform(const std::string& text, Eigen::Isometry3d* T, std::string* error);
bool readTransformFile(const std::string& path, Eigen::Isometry3d* T, std::string* error);

/// 4 lines of 4 numbers, full double precision.
std::string formatTransform(const Eigen::Isometry3d& T);
bool writeTransformFile(const std::string& path, const Eigen::Isometry3d& T, std::string* error);

}  // namespace pda_registration
