#pragma once
// What every fuzzer checks besides the sanitizers: a violated invariant aborts, so libFuzzer
// saves the input as a crash exactly like an AddressSanitizer report.

#include <Eigen/Geometry>
#include <cstdio>
#include <cstdlib>
#include <string>

namespace pda_registration {
namespace fuzzing {

inline void require(bool condition, const char* invariant, const std::string& detail = "") {
  if (condition) return;
  std::fprintf(stderr, "INVARIANT VIOLATED: %s [%s]\n", invariant, detail.c_str());
  std::abort();
}

/// The tools print errors as one line on stderr and the nodelet logs them as one line.
inline bool isOneLineMessage(const std::string& text) {
  return !text.empty() && text.find_first_of("\n\r") == std::string::npos;
}

/// What any parser may hand on as a pose: finite, with a proper rotation.
inline void requireRigid(const Eigen::Isometry3d& T) {
  const Eigen::Matrix3d R = T.linear();
  require(T.matrix().allFinite(), "accepted transform is finite");
  require((R.transpose() * R - Eigen::Matrix3d::Identity()).norm() < 1e-9 && R.determinant() > 0.0,
          "accepted transform has a proper rotation");
}

}  // namespace fuzzing
}  // namespace pda_registration
