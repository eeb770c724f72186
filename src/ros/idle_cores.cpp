#include "pda_registration/ros/idle_cores.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

namespace pda_registration {
namespace {

int onlineCores() { return static_cast<int>(std::max(1L, sysconf(_SC_NPROCESSORS_ONLN))); }

// The "cpu" line of /proc/stat: all time and idle time (idle + iowait) over all cores.
bool readMachine(uint64_t* total, uint64_t* idle) {
  std::ifstream in("/proc/stat");
  std::string label;
  if (!(in >> label) || label != "cpu") return false;
  uint64_t value = 0, sum = 0, idle_sum = 0;
  for (int field = 0; field < 8 && (in >> value); ++field) {  // user ... steal
    sum += value;
    if (field == 3 || field == 4) idle_sum += value;  // idle, iowait
  }
  *total = sum;
  *idle = idle_sum;
  return sum > 0;
}

// utime + stime of this process (all its threads), fields 14 and 15 of /proc/self/stat.
bool readOwn(uint64_t* jiffies) {
  std::ifstream in("/proc/self/stat");
  std::string line;
  if (!std::getline(in, line)) return false;
  const size_t end_of_name = line.rfind(')');  // the name may hold spaces
  if (end_of_name == std::string::npos) return false;
  std::istringstream fields(line.substr(end_of_name + 2));
  std::string field;
  uint64_t utime = 0, stime = 0;
  for (int i = 3; i <= 15 && (fields >> field); ++i) {
    if (i == 14) utime = std::stoull(field);
    if (i == 15) stime = std::stoull(field);
  }
  *jiffies = utime + stime;
  return true;
}

}  // namespace

double IdleCores::sample(double min_window) {
  std::lock_guard<std::mutex> lock(mutex_);
  return sampleLocked(min_window);
}

double IdleCores::sampleLocked(double min_window) {
  const int cores = onlineCores();
  uint64_t total = 0, idle = 0, own = 0;
  if (!readMachine(&total, &idle) || !readOwn(&own)) return cores;
  if (!have_start_) {
    have_start_ = true;
    start_total_ = total;
    start_idle_ = idle;
    start_own_ = own;
    return idle_cores_ < 0.0 ? cores : idle_cores_;
  }
  const double elapsed_all = static_cast<double>(total - start_total_);  // summed over cores
  const double per_core = elapsed_all / cores;
  const double hz = static_cast<double>(sysconf(_SC_CLK_TCK));
  if (per_core < min_window * hz || per_core <= 0.0) {
    return idle_cores_ < 0.0 ? cores : idle_cores_;
  }
  const double busy = elapsed_all - static_cast<double>(idle - start_idle_);
  const double others = std::max(0.0, busy - static_cast<double>(own - start_own_));
  idle_cores_ = std::clamp(cores - others / per_core, 0.0, static_cast<double>(cores));
  start_total_ = total;
  start_idle_ = idle;
  start_own_ = own;
  return idle_cores_;
}

int IdleCores::threadsFor(int wanted, double min_window) {
  const double idle = sample(min_window);  // locks
  return std::clamp(static_cast<int>(std::floor(idle + 0.25)), 1, std::max(wanted, 1));
}

}  // namespace pda_registration
