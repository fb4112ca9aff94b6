// BoxGrid reports every overlapping pair exactly once, and every box overlapping a query
// once: compared with brute force on random boxes of mixed sizes (including flat and
// degenerate ones).
#include <gtest/gtest.h>

#include <random>
#include <set>
#include <utility>

#include "toolkit/plc/box_grid.h"

namespace delmesh {
namespace {

using Pair = std::pair<std::uint32_t, std::uint32_t>;

std::vector<Box3> random_boxes(std::size_t n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> pos(-10, 10), size(0, 1), big(0, 15);
  std::vector<Box3> boxes;
  for (std::size_t i = 0; i < n; ++i) {
    Box3 b;
    const Vec3 lo(pos(rng), pos(rng), i % 7 == 0 ? 0.0 : pos(rng));  // some share a plane
    b.extend(lo);
    Vec3 hi = lo + Vec3(size(rng), size(rng), i % 7 == 0 ? 0.0 : size(rng));
    if (i % 50 == 0) hi += Vec3(big(rng), big(rng), big(rng));  // a few large ones
    b.extend(hi);
    boxes.push_back(b);
  }
  return boxes;
}

TEST(BoxGrid, PairsMatchBruteForceExactlyOnce) {
  const auto boxes = random_boxes(600, 7);
  std::set<Pair> expected;
  for (std::uint32_t i = 0; i < boxes.size(); ++i)
    for (std::uint32_t j = i + 1; j < boxes.size(); ++j)
      if (boxes[i].overlaps(boxes[j])) expected.insert({i, j});
  const BoxGrid grid(boxes);
  std::multiset<Pair> found;
  grid.for_each_overlapping_pair([&](std::uint32_t i, std::uint32_t j) { found.insert({i, j}); });
  EXPECT_EQ(found.size(), expected.size());
  const std::set<Pair> distinct(found.begin(), found.end());
  EXPECT_EQ(distinct, expected);
}

TEST(BoxGrid, QueriesMatchBruteForceExactlyOnce) {
  const auto boxes = random_boxes(400, 11);
  const auto queries = random_boxes(50, 13);
  const BoxGrid grid(boxes);
  for (const Box3& q : queries) {
    std::multiset<std::uint32_t> found;
    grid.for_each_overlapping(q, [&](std::uint32_t i) { found.insert(i); });
    std::multiset<std::uint32_t> expected;
    for (std::uint32_t i = 0; i < boxes.size(); ++i)
      if (boxes[i].overlaps(q)) expected.insert(i);
    EXPECT_EQ(found, expected);
  }
}

TEST(BoxGrid, AllBoxesInOnePoint) {
  std::vector<Box3> boxes(5);
  for (auto& b : boxes) b.extend(Vec3(1, 2, 3));
  const BoxGrid grid(boxes);
  int pairs = 0;
  grid.for_each_overlapping_pair([&](std::uint32_t, std::uint32_t) { ++pairs; });
  EXPECT_EQ(pairs, 10);
}

}  // namespace
}  // namespace delmesh
