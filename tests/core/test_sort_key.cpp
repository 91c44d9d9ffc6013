// Packed sort keys give the same order as comparing (value, index) pairs.
#include "core/sort_key.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <random>
#include <vector>

namespace haif {
namespace {

std::vector<float> someValues() {
  std::vector<float> v = {0.0f, -0.0f, 1.0f, -1.0f, 1e-30f, -1e-30f, 3.5f, 3.5f, -2.25f, 1e30f, -1e30f, 0.0f};
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> d(-100.0f, 100.0f);
  for (int i = 0; i < 500; ++i) v.push_back(i % 5 == 0 ? float(int(d(rng))) : d(rng));  // with repeats
  return v;
}

// Sorting the keys made by `key` ranks the values exactly as sorting indices with `before` does.
template <class Key, class Before>
void expectKeysSortLike(Key key, Before before) {
  const std::vector<float> v = someValues();
  std::vector<uint32_t> byCompare(v.size());
  std::vector<uint64_t> keys(v.size());
  for (uint32_t i = 0; i < v.size(); ++i) {
    byCompare[i] = i;
    keys[i] = key(v[i], i);
  }
  std::sort(byCompare.begin(), byCompare.end(),
            [&](uint32_t x, uint32_t y) { return before(v[x], v[y]) || (v[x] == v[y] && x < y); });
  std::sort(keys.begin(), keys.end());
  for (size_t r = 0; r < v.size(); ++r) ASSERT_EQ(keyIndex(keys[r]), byCompare[r]) << "rank " << r;
}

TEST(SortKey, AscendingKeysSortAsValueThenIndex) {
  expectKeysSortLike(ascendingKey, [](float a, float b) { return a < b; });
}

TEST(SortKey, DescendingKeysSortAsValueDownThenIndexUp) {
  expectKeysSortLike(descendingKey, [](float a, float b) { return a > b; });
}

TEST(SortKey, SignedZerosTie) {
  EXPECT_EQ(orderedBits(0.0f), orderedBits(-0.0f));
  EXPECT_LT(orderedBits(-1e-30f), orderedBits(0.0f));
  EXPECT_LT(orderedBits(0.0f), orderedBits(1e-30f));
}

// Keys made in index order sort by their values alone, stably: the same order as sorting whole keys.
TEST(SortKey, KeysMadeInIndexOrderSortAsWholeKeys) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> d(-50.0f, 50.0f);
  for (uint32_t n : {0u, 1u, 5u, 63u, 64u, 65u, 300u, 5000u}) {
    for (int kind = 0; kind < 4; ++kind) {
      std::vector<uint64_t> keys(n), scratch(n);
      for (uint32_t i = 0; i < n; ++i) {
        // Spread values, many ties, values sharing their upper digits, and one value for all.
        const float v = kind == 0 ? d(rng) : kind == 1 ? float(int(d(rng)) / 10) : kind == 2 ? 7.0f + 1e-4f * float(rng() % 97) : 3.0f;
        keys[i] = i % 2 ? descendingKey(v, i) : ascendingKey(v, i);
      }
      std::vector<uint64_t> expected = keys;
      std::sort(expected.begin(), expected.end());
      sortKeysMadeInIndexOrder(keys.data(), scratch.data(), n);
      ASSERT_EQ(keys, expected) << n << " keys, kind " << kind;
    }
  }
}

}  // namespace
}  // namespace haif
