// SegmentFacetList (the facets of a segment, two in place and more on the heap) against
// std::vector: appends across the move to the heap, copies and moves of inline and heap
// lists, and a segment record that no longer needs an allocation for two facets.
#include <gtest/gtest.h>

#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "refiners/tet3d/refine_state.h"
#include "refiners/tet3d/segment_facet_list.h"

namespace delmesh::tet3d {
namespace {

std::vector<std::uint32_t> contents(const SegmentFacetList& list) { return {list.begin(), list.end()}; }

SegmentFacetList list_of(std::uint32_t count) {
  SegmentFacetList list;
  for (std::uint32_t i = 0; i < count; ++i) list.push_back(100 + 7 * i);
  return list;
}

TEST(SegmentFacetList, AgreesWithAVectorAcrossTheMoveToTheHeap) {
  SegmentFacetList list;
  std::vector<std::uint32_t> reference;
  EXPECT_TRUE(list.empty());
  for (std::uint32_t i = 0; i < 9; ++i) {
    list.push_back(3 * i + 1);
    reference.push_back(3 * i + 1);
    ASSERT_EQ(list.size(), reference.size());
    EXPECT_EQ(contents(list), reference);
    EXPECT_EQ(list.front(), reference.front());
    EXPECT_EQ(list[i], reference[i]);
    const std::span<const std::uint32_t> span = list;
    EXPECT_EQ(span.size(), reference.size());
  }
  list.clear();
  EXPECT_TRUE(list.empty());
  list.push_back(42);
  EXPECT_EQ(contents(list), std::vector<std::uint32_t>{42});
}

TEST(SegmentFacetList, CopiesAndMovesKeepTheFacets) {
  for (const std::uint32_t count : {0u, 1u, 2u, 3u, 5u}) {
    const SegmentFacetList original = list_of(count);
    const std::vector<std::uint32_t> expected = contents(original);
    ASSERT_EQ(expected.size(), count);

    SegmentFacetList copy(original);
    EXPECT_EQ(contents(copy), expected) << count;
    SegmentFacetList assigned = list_of(4);
    assigned = original;
    EXPECT_EQ(contents(assigned), expected) << count;
    SegmentFacetList smaller = list_of(1);
    smaller = original;
    EXPECT_EQ(contents(smaller), expected) << count;

    SegmentFacetList moved(std::move(copy));
    EXPECT_EQ(contents(moved), expected) << count;
    EXPECT_TRUE(copy.empty());  // NOLINT(bugprone-use-after-move): a moved-from list is empty
    SegmentFacetList move_assigned = list_of(6);
    move_assigned = std::move(moved);
    EXPECT_EQ(contents(move_assigned), expected) << count;
    copy.push_back(9);
    EXPECT_EQ(contents(copy), std::vector<std::uint32_t>{9});
  }
}

TEST(SegmentFacetList, SegmentRecordsKeepTheirFacetsThroughVectorGrowth) {
  static_assert(sizeof(SegmentData) == 56);
  std::vector<SegmentData> segments;
  for (std::uint32_t s = 0; s < 1000; ++s) {
    SegmentData seg;
    seg.a = s;
    for (std::uint32_t k = 0; k <= s % 4; ++k) seg.facets.push_back(s + k);
    segments.push_back(std::move(seg));
  }
  for (std::uint32_t s = 0; s < segments.size(); ++s) {
    ASSERT_EQ(segments[s].facets.size(), s % 4 + 1);
    for (std::uint32_t k = 0; k < segments[s].facets.size(); ++k) EXPECT_EQ(segments[s].facets[k], s + k);
  }
}

}  // namespace
}  // namespace delmesh::tet3d
