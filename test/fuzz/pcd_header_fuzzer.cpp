// checkPcdHeader: the guard in front of PCL's PCD reader (which crashes on some malformed files).
// The input is the whole file. Whatever it holds, the check returns, and a refusal is a one-line
// reason.
#include <cstddef>
#include <cstdint>
#include <sstream>
#include <string>

#include "fuzz_invariant.hpp"
#include "pda_registration/tools/pcd_header.hpp"

using namespace pda_registration;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::istringstream file(std::string(reinterpret_cast<const char*>(data), size), std::ios::binary);
  std::string error;
  if (!checkPcdHeader(file, &error)) {
    fuzzing::require(fuzzing::isOneLineMessage(error), "refusal is a one-line reason", error);
  }
  return 0;
}
