#pragma once
// What every fuzzer checks besides the sanitizers: a violated invariant aborts, so libFuzzer
// saves the input as a crash exactly like an AddressSanitizer report.

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

}  // namespace fuzzing
}  // namespace pda_registration
