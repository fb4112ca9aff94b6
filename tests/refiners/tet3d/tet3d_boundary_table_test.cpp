// BoundaryTable (the subsegment and subfacet lookups of 3D refinement) against std::map:
// insertions through several rehashes, backward-shift erasures, the vertex filter,
// iteration over exactly the stored keys in an order fixed by the operations.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <random>
#include <vector>

#include "refiners/tet3d/boundary_table.h"

namespace delmesh::tet3d {
namespace {

FaceKeyTraits::Key random_face(std::mt19937_64& rng, std::uint32_t vertices) {
  std::uniform_int_distribution<std::uint32_t> u(1, vertices);
  std::uint32_t a = u(rng), b = u(rng), c = u(rng);
  while (b == a) b = u(rng);
  while (c == a || c == b) c = u(rng);
  if (a > b) std::swap(a, b);
  if (b > c) std::swap(b, c);
  if (a > b) std::swap(a, b);
  return {a, b, c};
}

TEST(BoundaryTable, AgreesWithAMapThroughRehashesAndErasures) {
  SubfaceTable table;
  std::map<FaceKeyTraits::Key, std::uint32_t> reference;
  std::mt19937_64 rng(5);
  // Few vertices: many keys share their smallest vertex, so probe runs are long.
  for (std::uint32_t i = 0; i < 20000; ++i) {
    const auto key = random_face(rng, 300);
    const bool fresh = table.emplace(key, i).second;
    EXPECT_EQ(fresh, reference.emplace(key, i).second);
  }
  ASSERT_EQ(table.size(), reference.size());
  std::vector<FaceKeyTraits::Key> keys;
  for (const auto& [key, id] : reference) keys.push_back(key);
  std::shuffle(keys.begin(), keys.end(), rng);
  for (std::size_t k = 0; k < keys.size() / 2; ++k) {
    EXPECT_EQ(table.erase(keys[k]), 1u);
    EXPECT_EQ(table.erase(keys[k]), 0u);
    reference.erase(keys[k]);
  }
  EXPECT_EQ(table.size(), reference.size());
  for (const auto& [key, id] : reference) {
    const std::uint32_t* found = table.lookup(key);
    ASSERT_NE(found, nullptr);
    EXPECT_EQ(*found, id);
  }
  for (std::size_t k = 0; k < keys.size() / 2; ++k) EXPECT_EQ(table.lookup(keys[k]), nullptr);
  std::size_t seen = 0;
  for (const auto& [key, id] : table) {
    ASSERT_TRUE(reference.count(key));
    EXPECT_EQ(reference.at(key), id);
    ++seen;
  }
  EXPECT_EQ(seen, reference.size());
}

TEST(BoundaryTable, VertexFilterAndUpdates) {
  SubsegmentTable table;
  EXPECT_FALSE(table.may_hold(3));
  table.emplace((std::uint64_t{3} << 32) | 9, 1);
  EXPECT_TRUE(table.may_hold(3));
  EXPECT_TRUE(table.may_hold(9));
  EXPECT_FALSE(table.may_hold(4));
  EXPECT_FALSE(table.may_hold(1u << 30));  // beyond every flagged id
  table[(std::uint64_t{3} << 32) | 9] = 7;
  EXPECT_EQ(table.at((std::uint64_t{3} << 32) | 9), 7u);
  const auto version = table.version();
  table.erase((std::uint64_t{3} << 32) | 9);
  EXPECT_NE(table.version(), version);
  EXPECT_TRUE(table.empty());
  EXPECT_TRUE(table.may_hold(3));  // flags are never cleared
}

TEST(BoundaryTable, IterationOrderDependsOnlyOnTheOperations) {
  auto run = [] {
    SubfaceTable table;
    std::mt19937_64 rng(8);
    for (std::uint32_t i = 0; i < 5000; ++i) table.emplace(random_face(rng, 2000), i);
    std::vector<std::uint32_t> ids;
    for (const auto& [key, id] : table) ids.push_back(id);
    return ids;
  };
  EXPECT_EQ(run(), run());
}

}  // namespace
}  // namespace delmesh::tet3d
