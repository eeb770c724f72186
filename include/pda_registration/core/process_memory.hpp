#pragma once
// This process's memory, for the tools' reports and the nodelet's diagnostics (Linux: read from
// /proc/self/status; zeros elsewhere).

namespace pda_registration {

struct ProcessMemory {
  double resident_mb = 0.0;  ///< VmRSS: resident now
  double peak_mb = 0.0;      ///< VmHWM: the most ever resident
};

ProcessMemory processMemory();

}  // namespace pda_registration
