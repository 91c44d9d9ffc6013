// PairMap (open addressing, backward-shift deletion) against std::unordered_map under random ops.
#include <cstddef>  // pair_map.h uses size_t without including it

#include "collision/pair_map.h"

#include <gtest/gtest.h>

#include <random>
#include <unordered_map>
#include <vector>

namespace haif {
namespace {

TEST(PairMap, KeyIsOrderIndependent) {
  EXPECT_EQ(PairMap::key(3, 7), PairMap::key(7, 3));
  EXPECT_NE(PairMap::key(3, 7), PairMap::key(3, 8));
  EXPECT_NE(PairMap::key(1, 2), PairMap::key(2, 2));
}

TEST(PairMap, EmptyMapFindsNothing) {
  PairMap m;
  EXPECT_EQ(m.find(PairMap::key(1, 2)), PairMap::kNotFound);
  m.erase(PairMap::key(1, 2));  // erasing from an empty map is harmless
  EXPECT_EQ(m.size(), 0u);
}

void randomOps(uint32_t seed, uint32_t bodies, int ops) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<uint32_t> body(0, bodies - 1);
  std::uniform_int_distribution<int> op(0, 9);
  PairMap m;
  std::unordered_map<uint64_t, uint32_t> ref;
  std::vector<uint64_t> keys;  // keys seen, to probe present and erased ones
  for (int k = 0; k < ops; ++k) {
    const int o = op(rng);
    uint64_t key;
    if (!keys.empty() && o >= 5) key = keys[std::uniform_int_distribution<size_t>(0, keys.size() - 1)(rng)];
    else key = PairMap::key(body(rng), body(rng));
    if (o < 5 || o == 9) {
      const uint32_t v = uint32_t(rng());
      m.set(key, v == PairMap::kNotFound ? 0 : v);
      ref[key] = v == PairMap::kNotFound ? 0 : v;
      keys.push_back(key);
    } else {
      m.erase(key);
      ref.erase(key);
    }
    ASSERT_EQ(m.size(), ref.size()) << "op " << k;
    // Probe the touched key and a few random ones.
    const auto it = ref.find(key);
    ASSERT_EQ(m.find(key), it == ref.end() ? PairMap::kNotFound : it->second) << "op " << k;
    if (k % 1000 == 0) {
      for (const auto& [kk, vv] : ref) ASSERT_EQ(m.find(kk), vv) << "op " << k;
      for (uint64_t kk : keys) {
        if (!ref.count(kk)) {
          ASSERT_EQ(m.find(kk), PairMap::kNotFound) << "op " << k;
        }
      }
    }
  }
  for (const auto& [kk, vv] : ref) EXPECT_EQ(m.find(kk), vv);
}

// Few bodies: dense keys, long probe runs and many deletions inside them.
TEST(PairMap, RandomOpsDenseKeys) { randomOps(1, 40, 60000); }
// Many bodies: the map grows several times.
TEST(PairMap, RandomOpsGrowth) { randomOps(2, 100000, 60000); }

TEST(PairMap, EraseEverythingThenReuse) {
  PairMap m;
  std::vector<uint64_t> keys;
  for (uint32_t i = 0; i < 5000; ++i) {
    keys.push_back(PairMap::key(i, i * 7 + 1));
    m.set(keys.back(), i);
  }
  EXPECT_EQ(m.size(), keys.size());
  for (size_t i = 0; i < keys.size(); i += 2) m.erase(keys[i]);
  for (size_t i = 0; i < keys.size(); ++i)
    EXPECT_EQ(m.find(keys[i]), i % 2 ? uint32_t(i) : PairMap::kNotFound) << i;
  for (size_t i = 1; i < keys.size(); i += 2) m.erase(keys[i]);
  EXPECT_EQ(m.size(), 0u);
  for (uint64_t k : keys) EXPECT_EQ(m.find(k), PairMap::kNotFound);
}

}  // namespace
}  // namespace haif
