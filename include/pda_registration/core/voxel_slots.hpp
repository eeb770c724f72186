#pragma once
// A table from voxel keys (voxel_cell.hpp) to dense slot numbers 0, 1, 2, ... in the order the
// keys first come: open addressing with linear probing (key + 1; 0 = empty), grown at half load.
// A pass over a map of millions of points is its hash lookups; std::unordered_map's node per
// voxel and pointer chase cost more (2M Kinect points: 39-56 -> 28-32 ms, same output). Shared by
// the voxel filter (point_filter.hpp) and the source budget (source_budget.hpp).

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace pda_registration {

class VoxelSlots {
 public:
  VoxelSlots()
      : keys_(kInitialCapacity, 0), slots_(kInitialCapacity), mask_(kInitialCapacity - 1) {}
  /// Room for `expected` keys without growing.
  explicit VoxelSlots(size_t expected) { clear(expected); }

  /// Empties the table, keeping its memory (and growing it to room for `expected` keys): a table
  /// reused pass after pass does not fault in fresh pages each time. Only the part in use is
  /// cleared and probed, so a table once grown for a large map stays as fast for a small one.
  void clear(size_t expected) {
    size_t capacity = kInitialCapacity;
    while (capacity < 2 * expected + 2) capacity *= 2;
    if (keys_.size() < capacity) {
      keys_.resize(capacity);
      slots_.resize(capacity);
    }
    std::fill(keys_.begin(), keys_.begin() + static_cast<std::ptrdiff_t>(capacity), 0);
    mask_ = capacity - 1;
    used_ = 0;
  }

  /// The slot of `key`, or `next` (recorded as the key's slot) when the key is new.
  size_t find(uint64_t key, size_t next, bool* inserted) {
    const uint64_t stored = key + 1;
    size_t i = mix(stored) & mask();
    while (keys_[i] != 0 && keys_[i] != stored) i = (i + 1) & mask();
    *inserted = keys_[i] == 0;
    if (!*inserted) return slots_[i];
    keys_[i] = stored;
    slots_[i] = static_cast<uint32_t>(next);
    if (2 * ++used_ > mask_ + 1) grow();
    return next;
  }

  /// Keys held.
  size_t size() const { return used_; }

 private:
  static constexpr size_t kInitialCapacity = 1024;
  static uint64_t mix(uint64_t k) {  // a 64-bit finaliser (MurmurHash3's)
    k ^= k >> 33;
    k *= 0xff51afd7ed558ccdull;
    k ^= k >> 33;
    return k;
  }
  size_t mask() const { return mask_; }
  void grow() {
    std::vector<uint64_t> keys(2 * (mask_ + 1), 0);
    std::vector<uint32_t> slots(keys.size());
    const size_t mask = keys.size() - 1;
    for (size_t j = 0; j <= mask_; ++j) {
      if (keys_[j] == 0) continue;
      size_t i = mix(keys_[j]) & mask;
      while (keys[i] != 0) i = (i + 1) & mask;
      keys[i] = keys_[j];
      slots[i] = slots_[j];
    }
    keys_.swap(keys);
    slots_.swap(slots);
    mask_ = mask;
  }

  std::vector<uint64_t> keys_;
  std::vector<uint32_t> slots_;  // a map or pool of more than 4G voxels is out of reach anyway
  size_t mask_;
  size_t used_ = 0;
};

}  // namespace pda_registration
