// Open-addressing hash map from an unordered body pair to a contact index. Linear probing with
// backward-shift deletion (no tombstones), so lookups stay short however long the world runs.
// Grows by doubling only when more than half full: no allocation in a steady state.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace haif {

class PairMap {
 public:
  static constexpr uint32_t kNotFound = 0xffffffffu;

  static uint64_t key(uint32_t a, uint32_t b) {
    return a < b ? (uint64_t(a) << 32) | b : (uint64_t(b) << 32) | a;
  }

  uint32_t find(uint64_t k) const {
    if (slots_.empty()) return kNotFound;
    for (size_t i = home(k);; i = (i + 1) & mask_) {
      if (slots_[i].key == kEmpty) return kNotFound;
      if (slots_[i].key == k) return slots_[i].value;
    }
  }

  /// Inserts or overwrites.
  void set(uint64_t k, uint32_t value) {
    if ((count_ + 1) * 2 > slots_.size()) grow();
    for (size_t i = home(k);; i = (i + 1) & mask_) {
      if (slots_[i].key == kEmpty) {
        slots_[i] = {k, value};
        ++count_;
        return;
      }
      if (slots_[i].key == k) {
        slots_[i].value = value;
        return;
      }
    }
  }

  void erase(uint64_t k) {
    if (slots_.empty()) return;
    size_t i = home(k);
    while (slots_[i].key != k) {
      if (slots_[i].key == kEmpty) return;
      i = (i + 1) & mask_;
    }
    // Shift later members of the probe run back so no lookup ever meets a hole early.
    size_t j = i;
    for (;;) {
      j = (j + 1) & mask_;
      if (slots_[j].key == kEmpty) break;
      const size_t h = home(slots_[j].key);
      const bool between = i <= j ? (i < h && h <= j) : (i < h || h <= j);
      if (between) continue;
      slots_[i] = slots_[j];
      i = j;
    }
    slots_[i].key = kEmpty;
    --count_;
  }

  size_t size() const { return count_; }

 private:
  static constexpr uint64_t kEmpty = ~uint64_t(0);
  struct Slot {
    uint64_t key = kEmpty;
    uint32_t value = 0;
  };
  size_t home(uint64_t k) const {
    k ^= k >> 33;
    k *= 0xff51afd7ed558ccdull;
    k ^= k >> 33;
    return size_t(k) & mask_;
  }
  void grow() {
    std::vector<Slot> old = std::move(slots_);
    slots_.assign(old.empty() ? 1024 : old.size() * 2, Slot{});
    mask_ = slots_.size() - 1;
    count_ = 0;
    for (const Slot& s : old)
      if (s.key != kEmpty) set(s.key, s.value);
  }

  std::vector<Slot> slots_;
  size_t mask_ = 0;
  size_t count_ = 0;
};

}  // namespace haif
