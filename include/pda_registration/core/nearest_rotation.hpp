#pragma once
// One check for "is this 3x3 block a rotation?", shared by every place a pose comes in from
// outside (the matrix files, ~initial_transform, the core's initial guess).

#include <Eigen/Core>

namespace pda_registration {

/// True when `r` is within 1e-3 (Frobenius) of orthonormal with a positive determinant; then
/// writes the nearest rotation (SVD) to *rotation, so rounded text matrices are snapped back.
/// NaN fails: huge finite entries make the orthonormality error Inf - Inf = NaN, and the test is
/// written so that NaN does not pass (NaN > 1e-3 is false; the fuzzers found that hole).
bool nearestRotation(const Eigen::Matrix3d& r, Eigen::Matrix3d* rotation);

}  // namespace pda_registration
