// MappedArray: growth across the mapping threshold keeps every element, copies and moves
// are deep / stealing, resize fills, push_back of an own element survives growth, assign
// fills in place when the capacity suffices, shrink_to_fit / shrink_capacity keep the
// elements and give back the storage beyond them.
#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <utility>

#include "toolkit/core/mapped_array.h"

namespace delmesh {
namespace {

struct Record {
  std::array<std::uint32_t, 4> v;
  std::array<std::uint32_t, 4> adj;
};

Record record(std::uint32_t i) { return {{i, i + 1, i + 2, i + 3}, {~i, i * 7, i ^ 0x55u, i / 3}}; }
bool same(const Record& x, const Record& y) { return x.v == y.v && x.adj == y.adj; }

TEST(MappedArray, GrowsPastTheMappingThresholdKeepingEveryElement) {
  MappedArray<Record> a;
  EXPECT_TRUE(a.empty());
  const std::uint32_t n = 3 * MappedArray<Record>::kMapBytes / sizeof(Record);
  bool was_small = false;
  for (std::uint32_t i = 0; i < n; ++i) {
    a.push_back(record(i));
    if (i == 100) was_small = !a.mapped();
  }
  EXPECT_TRUE(was_small);
#if defined(__linux__)
  EXPECT_TRUE(a.mapped());
#endif
  ASSERT_EQ(a.size(), n);
  EXPECT_GE(a.capacity(), n);
  for (std::uint32_t i = 0; i < n; ++i) ASSERT_TRUE(same(a[i], record(i))) << i;
  std::uint64_t sum = 0;
  for (const Record& r : a) sum += r.v[0];
  EXPECT_EQ(sum, std::uint64_t{n} * (n - 1) / 2);
  EXPECT_TRUE(same(a.back(), record(n - 1)));
  a.pop_back();
  EXPECT_EQ(a.size(), n - 1);
}

TEST(MappedArray, ShrinkToFitKeepsTheElementsAndLowersTheCapacity) {
  MappedArray<Record> a;
  const std::uint32_t n = 4 * MappedArray<Record>::kMapBytes / sizeof(Record);
  for (std::uint32_t i = 0; i < n; ++i) a.push_back(record(i));
  // Still mapped after shrinking: shortened in place.
  const std::uint32_t mid = 2 * MappedArray<Record>::kMapBytes / sizeof(Record) + 5;
  a.resize(mid);
  a.shrink_to_fit();
  ASSERT_EQ(a.size(), mid);
  EXPECT_LT(a.capacity(), n);
  EXPECT_GE(a.capacity(), mid);
  for (std::uint32_t i = 0; i < mid; ++i) ASSERT_TRUE(same(a[i], record(i))) << i;
  // shrink_capacity keeps the requested room, never less than the size.
  a.resize(1000);
  a.shrink_capacity(1500);
  EXPECT_EQ(a.capacity(), 1500u);
  a.shrink_capacity(10);
  EXPECT_EQ(a.capacity(), 1000u);
  for (std::uint32_t i = 0; i < 1000; ++i) ASSERT_TRUE(same(a[i], record(i))) << i;
  // Below the mapping threshold: back to malloc, exact size.
  a.resize(100);
  a.shrink_to_fit();
  EXPECT_FALSE(a.mapped());
  EXPECT_EQ(a.capacity(), 100u);
  for (std::uint32_t i = 0; i < 100; ++i) ASSERT_TRUE(same(a[i], record(i))) << i;
  a.push_back(record(100));
  EXPECT_TRUE(same(a.back(), record(100)));
  a.clear();
  a.shrink_to_fit();
  EXPECT_EQ(a.capacity(), 0u);
  a.push_back(record(7));
  EXPECT_TRUE(same(a[0], record(7)));
}

TEST(MappedArray, MapsFromTheThresholdItIsGiven) {
  MappedArray<std::uint32_t, 4096> a;
  a.resize(1000, 5u);  // 4000 bytes
  EXPECT_FALSE(a.mapped());
  a.resize(1100, 6u);
#if defined(__linux__)
  EXPECT_TRUE(a.mapped());
#endif
  for (std::size_t i = 0; i < 1000; ++i) ASSERT_EQ(a[i], 5u) << i;
  for (std::size_t i = 1000; i < 1100; ++i) ASSERT_EQ(a[i], 6u) << i;
  a.resize(10);
  a.shrink_to_fit();
  EXPECT_FALSE(a.mapped());
  EXPECT_EQ(a.capacity(), 10u);
  for (std::size_t i = 0; i < 10; ++i) ASSERT_EQ(a[i], 5u) << i;
}

TEST(MappedArray, ResizeFillsAndShrinksWithoutReleasing) {
  MappedArray<std::uint32_t> a;
  a.resize(5, 7u);
  a.resize(8);
  ASSERT_EQ(a.size(), 8u);
  for (std::size_t i = 0; i < 5; ++i) EXPECT_EQ(a[i], 7u);
  for (std::size_t i = 5; i < 8; ++i) EXPECT_EQ(a[i], 0u);
  const std::size_t capacity = a.capacity();
  a.resize(2);
  EXPECT_EQ(a.size(), 2u);
  EXPECT_EQ(a.capacity(), capacity);
  a.resize(1'000'000, 3u);  // beyond the threshold: into a mapping
  EXPECT_EQ(a[0], 7u);
  EXPECT_EQ(a[1], 7u);
  EXPECT_EQ(a[2], 3u);
  EXPECT_EQ(a[999'999], 3u);
  a.release();
  EXPECT_EQ(a.size(), 0u);
  EXPECT_EQ(a.capacity(), 0u);
  EXPECT_FALSE(a.mapped());
  a.push_back(4u);  // usable again
  EXPECT_EQ(a[0], 4u);
}

TEST(MappedArray, CopiesAreDeepMovesSteal) {
  for (const std::size_t n : {std::size_t{10}, std::size_t{200'000}}) {
    MappedArray<Record> a;
    for (std::uint32_t i = 0; i < n; ++i) a.push_back(record(i));
    MappedArray<Record> b = a;
    EXPECT_TRUE(a == b);
    b[0].v[0] = 99;
    EXPECT_FALSE(a == b);
    EXPECT_EQ(a[0].v[0], 0u);
    MappedArray<Record> c = std::move(b);
    EXPECT_TRUE(b.empty());
    EXPECT_EQ(c.size(), n);
    EXPECT_EQ(c[0].v[0], 99u);
    c = a;
    EXPECT_TRUE(c == a);
    MappedArray<Record> d;
    d = std::move(c);
    EXPECT_TRUE(d == a);
    EXPECT_TRUE(c.empty());
  }
}

TEST(MappedArray, PushBackOfAnOwnElementSurvivesGrowth) {
  MappedArray<Record> a;
  a.push_back(record(5));
  while (a.size() < a.capacity()) a.push_back(record(1));
  const std::size_t full = a.size();
  a.push_back(a[0]);  // the reference dies when the storage moves
  ASSERT_EQ(a.size(), full + 1);
  EXPECT_TRUE(same(a.back(), record(5)));
}

TEST(MappedArray, AssignFillsInPlaceWhenTheCapacitySuffices) {
  MappedArray<std::uint32_t> a;
  a.assign(10, 7u);
  ASSERT_EQ(a.size(), 10u);
  for (const std::uint32_t x : a) EXPECT_EQ(x, 7u);
  // Past the mapping threshold: a mapped array, every element set.
  const std::size_t n = 2 * MappedArray<std::uint32_t>::kMapBytes / sizeof(std::uint32_t);
  a.assign(n, 3u);
  ASSERT_EQ(a.size(), n);
#if defined(__linux__)
  EXPECT_TRUE(a.mapped());
#endif
  for (std::size_t i = 0; i < n; ++i) ASSERT_EQ(a[i], 3u) << i;
  // Smaller: the same storage, refilled, the capacity kept.
  const std::uint32_t* storage = a.data();
  const std::size_t capacity = a.capacity();
  a.assign(n / 2, 9u);
  EXPECT_EQ(a.data(), storage);
  EXPECT_EQ(a.capacity(), capacity);
  ASSERT_EQ(a.size(), n / 2);
  for (std::size_t i = 0; i < n / 2; ++i) ASSERT_EQ(a[i], 9u) << i;
}

}  // namespace
}  // namespace delmesh
