// GrowingArray (core/growing_array.h): the contacts' array keeps every element through its growth
// from malloc's blocks into pages of its own and their remapping, as std::vector would.
#include "core/growing_array.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

namespace haif {
namespace {

// About a contact's size, so 1 MB is crossed at ~2,900 elements.
struct Item {
  uint32_t id = 0;
  float payload[90] = {};
};

Item itemOf(uint32_t i) {
  Item it;
  it.id = i;
  for (int k = 0; k < 90; ++k) it.payload[k] = float(i) * 0.5f + float(k);
  return it;
}

bool holds(const Item& it, uint32_t i) {
  if (it.id != i) return false;
  for (int k = 0; k < 90; ++k)
    if (it.payload[k] != float(i) * 0.5f + float(k)) return false;
  return true;
}

TEST(GrowingArray, KeepsEveryElementWhileGrowingIntoMappedPagesAndRemappingThem) {
  GrowingArray<Item> a;
  std::vector<uint32_t> model;  // the id each slot should hold
  const uint32_t n = 40000;     // 14.7 MB: malloc's block, then its own mapping, remapped four times
  size_t capacity = 0, growths = 0;
  for (uint32_t i = 0; i < n; ++i) {
    a.push_back(itemOf(i));
    model.push_back(i);
    if (a.capacity() != capacity) capacity = a.capacity(), ++growths;
    // Swap-remove now and then, as the world does with contacts that ended.
    if (i % 7 == 6) {
      const uint32_t gone = i / 2;
      a[gone] = a.back();
      a.pop_back();
      model[gone] = model.back();
      model.pop_back();
    }
  }
  EXPECT_GE(growths, 10u);
  ASSERT_EQ(a.size(), model.size());
  size_t wrong = 0;
  for (size_t k = 0; k < model.size(); ++k) wrong += !holds(a[k], model[k]);
  EXPECT_EQ(wrong, 0u);
}

TEST(GrowingArray, PushingOneOfItsOwnElementsWhenFullCopiesItBeforeGrowing) {
  GrowingArray<Item> a;
  for (uint32_t i = 0; i < 16; ++i) a.push_back(itemOf(i));
  ASSERT_EQ(a.size(), a.capacity()) << "the next push grows the array";
  a.push_back(a[3]);
  EXPECT_TRUE(holds(a.back(), 3));
  // Once mapped too.
  while (a.size() < a.capacity()) a.push_back(itemOf(uint32_t(a.size())));
  const size_t before = a.size();
  a.push_back(a[5]);
  EXPECT_GT(a.capacity(), before);
  EXPECT_TRUE(holds(a.back(), 5));
}

TEST(GrowingArray, CopiesAndMovesAreWhole) {
  GrowingArray<Item> a;
  for (uint32_t i = 0; i < 5000; ++i) a.push_back(itemOf(i));
  GrowingArray<Item> b = a;  // a mapped block copied
  GrowingArray<Item> c = std::move(a);
  EXPECT_TRUE(a.empty());
  ASSERT_EQ(b.size(), 5000u);
  ASSERT_EQ(c.size(), 5000u);
  for (uint32_t i = 0; i < 5000; i += 499) {
    EXPECT_TRUE(holds(b[i], i));
    EXPECT_TRUE(holds(c[i], i));
  }
  b.clear();
  EXPECT_TRUE(b.empty());
  b.push_back(itemOf(9));
  EXPECT_TRUE(holds(b[0], 9));
}

TEST(GrowingArray, ResizeValueInitialisesWhatItAddsAndKeepsTheRest) {
  GrowingArray<Item> a;
  a.resize(3000);  // past malloc's blocks at once
  ASSERT_EQ(a.size(), 3000u);
  for (uint32_t i = 0; i < 3000; ++i) a[i] = itemOf(i);
  a.resize(10);  // the world's rows shrink and grow back from step to step
  a.resize(20000);
  size_t wrong = 0;
  for (uint32_t i = 0; i < 10; ++i) wrong += !holds(a[i], i);
  EXPECT_EQ(wrong, 0u);
  // What resize added holds zeros, not what was there before (ids and payloads up to 2999).
  size_t stale = 0;
  for (uint32_t i = 10; i < 20000; ++i) {
    stale += a[i].id != 0;
    for (float v : a[i].payload) stale += v != 0.0f;
  }
  EXPECT_EQ(stale, 0u);
}

TEST(GrowingArray, CountsThePagesItMapsUntilItLetsThemGo) {
  const size_t before = growingArrayMappedBytes();
  {
    GrowingArray<Item> a;
    a.resize(10);
    EXPECT_EQ(growingArrayMappedBytes(), before) << "a small block is malloc's, counted there";
    a.resize(50000);
    EXPECT_GE(growingArrayMappedBytes(), before + 50000 * sizeof(Item));
    EXPECT_LE(growingArrayMappedBytes(), before + a.capacity() * sizeof(Item) + 4096);
  }
  EXPECT_EQ(growingArrayMappedBytes(), before);
}

}  // namespace
}  // namespace haif
