// The sleeping islands: each a set of bodies that fell asleep together and wake together (a body
// touched wakes its whole set). Set ids are reused, and so are their lists.
#pragma once

#include <cstdint>
#include <vector>

namespace haif {

class SleepSets {
 public:
  /// A new, empty set; its id stays valid until close().
  int32_t open() {
    if (!free_.empty()) {
      const int32_t set = free_.back();
      free_.pop_back();
      return set;
    }
    sets_.emplace_back();
    return int32_t(sets_.size()) - 1;
  }
  void add(int32_t set, uint32_t body) { sets_[size_t(set)].push_back(body); }
  const std::vector<uint32_t>& members(int32_t set) const { return sets_[size_t(set)]; }
  /// Empties a set (its bodies woke) and frees its id.
  void close(int32_t set) {
    sets_[size_t(set)].clear();
    free_.push_back(set);
  }

 private:
  std::vector<std::vector<uint32_t>> sets_;
  std::vector<int32_t> free_;
};

}  // namespace haif
