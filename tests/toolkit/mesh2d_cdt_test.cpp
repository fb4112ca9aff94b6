// Constrained Delaunay triangulation: segment recovery by flips, vertices on segments,
// crossing segments split at their intersection, holes, concavities and regions.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "toolkit/mesh2d/cdt.h"
#include "toolkit/mesh2d/triangulation.h"
#include "toolkit/mesh2d/validate.h"
#include "toolkit/predicates/predicates.h"

namespace delmesh::mesh2d {
namespace {

struct Built {
  Triangulation tri;
  SubsegmentOwners owners;
  CdtStats stats;
};

void build(Built& b, const std::vector<Point2>& pts,
           const std::vector<std::array<std::uint32_t, 2>>& segs) {
  ASSERT_TRUE(b.tri.build_delaunay(pts).has_value());
  ASSERT_TRUE(insert_segments(b.tri, segs, b.owners, b.stats).has_value());
  const auto topo = check_topology(b.tri);
  ASSERT_TRUE(topo.empty()) << topo.front();
  const auto del = check_delaunay(b.tri);
  ASSERT_TRUE(del.empty()) << del.front();
}

double domain_area(const Triangulation& tri) {
  double area = 0;
  for (std::uint32_t t = 0; t < tri.num_slots(); ++t) {
    if (!tri.in_domain(t)) continue;
    const auto& a = tri.points[tri.tv[3 * t]];
    const auto& b = tri.points[tri.tv[3 * t + 1]];
    const auto& c = tri.points[tri.tv[3 * t + 2]];
    area += 0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]));
  }
  return area;
}

// Edge a-b exists and is a subsegment.
bool has_subsegment(const Triangulation& tri, std::uint32_t a, std::uint32_t b) {
  const std::uint32_t e = tri.find_edge(a, b);
  return e != kNone && tri.subseg(e / 3, e % 3);
}

TEST(Mesh2dCdt, SegmentsThroughRandomPointsAreRecovered) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Point2> pts = {{0, 0}, {1, 0}, {1, 1}, {0, 1}, {0.05, 0.5}, {0.95, 0.52}};
  for (int i = 0; i < 2000; ++i) pts.push_back({u(rng), u(rng)});
  Built b;
  build(b, pts, {{4, 5}, {0, 2}, {1, 3}});
  // 0-2 and 1-3 cross at (0.5, 0.5); 4-5 crosses both.
  EXPECT_GE(b.stats.crossings, 2u);
  EXPECT_GT(b.tri.points.size(), pts.size());
  // Every piece of every segment is a subsegment: walk each chain.
  std::size_t marked = 0;
  for (std::uint32_t t = 0; t < b.tri.num_slots(); ++t)
    if (b.tri.alive(t))
      for (std::uint32_t i = 0; i < 3; ++i) marked += b.tri.subseg(t, i);
  EXPECT_EQ(marked / 2, b.owners.size());
}

TEST(Mesh2dCdt, VertexOnSegmentSplitsIt) {
  std::vector<Point2> pts = {{0, 0}, {4, 0}, {4, 4}, {0, 4}, {1, 1}, {2, 2}, {3, 3}, {3, 1}};
  Built b;
  build(b, pts, {{0, 2}});
  EXPECT_EQ(b.stats.vertices_on_segments, 3u);
  EXPECT_TRUE(has_subsegment(b.tri, 0, 4));
  EXPECT_TRUE(has_subsegment(b.tri, 4, 5));
  EXPECT_TRUE(has_subsegment(b.tri, 5, 6));
  EXPECT_TRUE(has_subsegment(b.tri, 6, 2));
  EXPECT_EQ(b.owners.get(5, 6), 0u);
}

TEST(Mesh2dCdt, CrossingSegmentsOnAGridAreSplitExactly) {
  // Integer grid (all cocircular) with the two diagonals: they cross at a grid point, so
  // the crossing vertex is an existing vertex found exactly.
  std::vector<Point2> pts;
  for (int i = 0; i <= 10; ++i)
    for (int j = 0; j <= 10; ++j) pts.push_back({double(i), double(j)});
  Built b;
  build(b, pts, {{0, 120}, {10, 110}, {5, 115}, {55, 65}});
  EXPECT_EQ(b.stats.crossings, 0u);
  EXPECT_GT(b.stats.vertices_on_segments, 0u);
  EXPECT_EQ(b.tri.points.size(), pts.size());
}

TEST(Mesh2dCdt, ManyRandomCrossingSegments) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Point2> pts;
  std::vector<std::array<std::uint32_t, 2>> segs;
  for (std::uint32_t i = 0; i < 60; ++i) {
    pts.push_back({u(rng), u(rng)});
    pts.push_back({u(rng), u(rng)});
    segs.push_back({2 * i, 2 * i + 1});
  }
  Built b;
  build(b, pts, segs);
  EXPECT_GT(b.stats.crossings, 100u);
}

TEST(Mesh2dCdt, HoleAndConcavityRemoval) {
  // An L-shaped outer boundary (concave) with a square hole: area 3 - 0.25.
  std::vector<Point2> pts = {{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2},
                             {0.25, 0.25}, {0.75, 0.25}, {0.75, 0.75}, {0.25, 0.75}};
  std::vector<std::array<std::uint32_t, 2>> segs = {{0, 1}, {1, 2}, {2, 3}, {3, 4}, {4, 5},
                                                    {5, 0}, {6, 7}, {7, 8}, {8, 9}, {9, 6}};
  Built b;
  build(b, pts, segs);
  auto dom = classify_domain(b.tri, {{0.5, 0.5}}, {}, DomainOptions{});
  ASSERT_TRUE(dom.has_value());
  EXPECT_TRUE(dom->boundary_edges.empty());
  EXPECT_DOUBLE_EQ(domain_area(b.tri), 3.0 - 0.25);
  EXPECT_TRUE(check_topology(b.tri).empty());

  Built kept;
  build(kept, pts, segs);
  DomainOptions keep;
  keep.keep_convex_hull = true;
  auto dom2 = classify_domain(kept.tri, {{0.5, 0.5}}, {}, keep);
  ASSERT_TRUE(dom2.has_value());
  // The convex hull closes the notch with the single edge (2,1)-(1,2).
  EXPECT_DOUBLE_EQ(domain_area(kept.tri), 3.5 - 0.25);
  ASSERT_EQ(dom2->boundary_edges.size(), 1u);
  const auto e = dom2->boundary_edges[0];
  EXPECT_TRUE((e[0] == 2 && e[1] == 4) || (e[0] == 4 && e[1] == 2));
}

TEST(Mesh2dCdt, HoleOutsideIsAnErrorNamingIt) {
  std::vector<Point2> pts = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  Built b;
  build(b, pts, {{0, 1}, {1, 2}, {2, 3}, {3, 0}});
  auto dom = classify_domain(b.tri, {{0.5, 0.5}, {5.0, 5.0}}, {}, DomainOptions{});
  ASSERT_FALSE(dom.has_value());
  EXPECT_EQ(dom.error().code, ErrorCode::InvalidInput);
  EXPECT_NE(dom.error().message.find("hole 1"), std::string::npos);
  ASSERT_EQ(dom.error().entity_ids.size(), 1u);
  EXPECT_EQ(dom.error().entity_ids[0], 1u);
}

TEST(Mesh2dCdt, RegionsAreFloodFilled) {
  // Square split by a vertical segment into two regions.
  std::vector<Point2> pts = {{0, 0}, {1, 0}, {2, 0}, {2, 1}, {1, 1}, {0, 1}};
  Built b;
  build(b, pts, {{0, 1}, {1, 2}, {2, 3}, {3, 4}, {4, 5}, {5, 0}, {1, 4}});
  std::vector<Pslg::Region> regions(2);
  regions[0].point = {0.5, 0.5};
  regions[1].point = {1.5, 0.5};
  DomainOptions opt;
  opt.track_regions = true;
  auto dom = classify_domain(b.tri, {}, regions, opt);
  ASSERT_TRUE(dom.has_value());
  for (std::uint32_t t = 0; t < b.tri.num_slots(); ++t) {
    if (!b.tri.in_domain(t)) continue;
    double cx = 0;
    for (int i = 0; i < 3; ++i) cx += b.tri.points[b.tri.tv[3 * t + i]][0] / 3;
    EXPECT_EQ(b.tri.region[t], cx < 1 ? 1u : 2u);
  }
}

}  // namespace
}  // namespace delmesh::mesh2d
