// parseTransform: the 4x4 text matrices of --initial and --ground-truth. The input is the file's
// text. Accepted ⇒ a finite rigid transform; refused ⇒ a one-line reason.
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz_invariant.hpp"
#include "pda_registration/core/transform_io.hpp"

using namespace pda_registration;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  Eigen::Isometry3d T;
  std::string error;
  if (parseTransform(text, &T, &error)) {
    const Eigen::Matrix3d R = T.linear();
    fuzzing::require(T.matrix().allFinite(), "accepted matrix is finite");
    fuzzing::require(
        (R.transpose() * R - Eigen::Matrix3d::Identity()).norm() < 1e-9 && R.determinant() > 0.0,
        "accepted matrix has a proper rotation");
    // What was accepted must read back the same (the tools write with formatTransform).
    Eigen::Isometry3d again;
    fuzzing::require(parseTransform(formatTransform(T), &again, &error) && again.isApprox(T),
                     "formatTransform output parses to the same transform", error);
  } else {
    fuzzing::require(fuzzing::isOneLineMessage(error), "refusal is a one-line reason", error);
  }
  return 0;
}
