#pragma once
// How many cores the rest of the machine leaves idle, for the alignment's thread count. An OpenMP
// team waits at every barrier for its slowest thread, and a thread that shares its core with
// another busy process is descheduled for whole scheduler slices: on 2 cores with one neighbour
// busy, 2 threads took an alignment from ~130 ms (1 thread) to 260-550 ms, several times slower
// (docs/benchmark.md, "Nodelet latency"). The nodelet therefore uses at most as many threads as
// there are cores free of other processes' work (its own threads, the keeper's included, do not
// count against it).

#include <cstdint>
#include <mutex>

namespace pda_registration {

class IdleCores {
 public:
  /// Starts the first window now (the nodelet: at start-up, well before its first alignment).
  IdleCores() { sample(); }
  /// Cores not busy with other processes' work, averaged since the last sample that started a
  /// new window; windows shorter than `min_window` seconds keep the last value. Sampled every
  /// second (the nodelet's diagnostics timer), the value covers the last one to two seconds. Before
  /// the first full window (or where /proc is unreadable) this is the number of cores.
  double sample(double min_window = 1.0);
  /// At most `wanted`, at least 1: the whole idle cores (a team member on a shared core stalls
  /// every barrier; 0.75 of a core counts as one).
  int threadsFor(int wanted, double min_window = 1.0);

 private:
  double sampleLocked(double min_window);

  std::mutex mutex_;  // a timer samples, the alignment thread asks
  bool have_start_ = false;
  uint64_t start_total_ = 0, start_idle_ = 0;  // /proc/stat, all cores [jiffies]
  uint64_t start_own_ = 0;                     // this process [jiffies]
  double idle_cores_ = -1.0;                   // < 0: none measured yet
};

}  // namespace pda_registration
