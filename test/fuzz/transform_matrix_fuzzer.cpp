// parseTransform: the 4x4 text matrices of --initial and --ground-truth. The input is the file's
// text. Accepted ⇒ a finite rigid transform, close to the matrix written (its rotation block
// within the parser's 1e-3 tolerance, its translation exact); refused ⇒ a one-line reason.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

#include "fuzz_invariant.hpp"
#include "pda_registration/core/transform_io.hpp"

using namespace pda_registration;

namespace {

// The numbers as written (comments after '#' dropped), read independently of the parser.
std::vector<double> writtenNumbers(const std::string& text) {
  std::vector<double> numbers;
  std::istringstream lines(text);
  std::string line, word;
  while (std::getline(lines, line)) {
    std::istringstream words(line.substr(0, line.find('#')));
    while (words >> word) numbers.push_back(std::strtod(word.c_str(), nullptr));
  }
  return numbers;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  Eigen::Isometry3d T;
  std::string error;
  if (!parseTransform(text, &T, &error)) {
    fuzzing::require(fuzzing::isOneLineMessage(error), "refusal is a one-line reason", error);
    return 0;
  }
  fuzzing::requireRigid(T);
  const Eigen::Matrix3d R = T.linear();
  const std::vector<double> written = writtenNumbers(text);
  fuzzing::require(written.size() == 16, "accepted text holds 16 numbers");
  Eigen::Matrix4d given;
  for (int i = 0; i < 16; ++i) given(i / 4, i % 4) = written[i];
  // Snapping a block within 1e-3 of orthonormal moves it by about as much.
  fuzzing::require((R - given.topLeftCorner<3, 3>()).norm() < 1e-2,
                   "accepted rotation is the one written");
  fuzzing::require(T.translation() == given.topRightCorner<3, 1>(),
                   "accepted translation is the one written");
  // What was accepted must read back the same (the tools write with formatTransform).
  Eigen::Isometry3d again;
  fuzzing::require(parseTransform(formatTransform(T), &again, &error) && again.isApprox(T),
                   "formatTransform output parses to the same transform", error);
  return 0;
}
