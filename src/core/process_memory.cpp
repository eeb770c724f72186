#include "pda_registration/core/process_memory.hpp"

#include <fstream>
#include <sstream>
#include <string>

namespace pda_registration {

ProcessMemory processMemory() {
  ProcessMemory memory;
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line)) {
    std::istringstream words(line);
    std::string key;
    double kilobytes = 0.0;
    if (!(words >> key >> kilobytes)) continue;
    if (key == "VmRSS:") memory.resident_mb = kilobytes / 1024.0;
    if (key == "VmHWM:") memory.peak_mb = kilobytes / 1024.0;
  }
  return memory;
}

}  // namespace pda_registration
