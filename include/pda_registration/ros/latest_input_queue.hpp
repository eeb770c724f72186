#pragma once
// A one-slot mailbox per input kind for the worker thread: a newer input replaces a pending
// older one (which is counted as dropped), so the worker always aligns the newest data and a
// slow registration never builds a backlog. ROS-free so it can be tested without a roscore.

#include <condition_variable>
#include <mutex>

namespace pda_registration {

template <class Dense, class Sparse>
class LatestInputQueue {
 public:
  /// Returns true when this replaced a pending dense input.
  bool putDense(Dense dense) { return put(&dense_, std::move(dense)); }
  /// Returns true when this replaced a pending sparse input.
  bool putSparse(Sparse sparse) { return put(&sparse_, std::move(sparse)); }

  /// Blocks until an input is pending or stop() was called. Takes everything pending; a dense
  /// input comes with the sparse one so the new map is in place before the next alignment.
  /// Returns false once stopped.
  bool waitAndTake(Dense* dense, bool* has_dense, Sparse* sparse, bool* has_sparse) {
    std::unique_lock<std::mutex> lock(mutex_);
    wake_.wait(lock, [this] { return stopped_ || dense_.pending || sparse_.pending; });
    if (stopped_) return false;
    *has_dense = take(&dense_, dense);
    *has_sparse = take(&sparse_, sparse);
    return true;
  }

  /// True when a dense input waits (the keeper's background work gives way to it).
  bool denseWaiting() {
    std::lock_guard<std::mutex> lock(mutex_);
    return dense_.pending;
  }

  void stop() {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      stopped_ = true;
    }
    wake_.notify_all();
  }

 private:
  template <class T>
  struct Slot {
    T value{};
    bool pending = false;
  };

  template <class T>
  bool put(Slot<T>* slot, T value) {
    bool replaced;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      replaced = slot->pending;
      slot->value = std::move(value);
      slot->pending = true;
    }
    wake_.notify_one();
    return replaced;
  }

  template <class T>
  static bool take(Slot<T>* slot, T* out) {
    if (!slot->pending) return false;
    *out = std::move(slot->value);
    slot->value = T{};
    slot->pending = false;
    return true;
  }

  std::mutex mutex_;
  std::condition_variable wake_;
  Slot<Dense> dense_;
  Slot<Sparse> sparse_;
  bool stopped_ = false;
};

}  // namespace pda_registration
