// Delaunay triangulation kernel: random points, integer grids (all cocircular), points
// on a circle, duplicates and collinear input, checked with the topology and exact
// Delaunay validators.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "toolkit/mesh2d/spatial_sort.h"
#include "toolkit/mesh2d/triangulation.h"
#include "toolkit/mesh2d/validate.h"
#include "toolkit/predicates/predicates.h"

namespace delmesh::mesh2d {
namespace {

void expect_valid(const Triangulation& tri) {
  const auto topo = check_topology(tri);
  EXPECT_TRUE(topo.empty()) << topo.front();
  const auto del = check_delaunay(tri);
  EXPECT_TRUE(del.empty()) << del.front();
}

// Euler: a triangulation of n points with h on the hull has 2n - 2 - h triangles.
std::size_t hull_size(const Triangulation& tri) {
  std::size_t h = 0;
  for (std::uint32_t t = 0; t < tri.num_slots(); ++t) h += tri.alive(t) && tri.ghost(t);
  return h;
}

TEST(Mesh2dDelaunay, RandomPoints) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Point2> pts(20000);
  for (auto& p : pts) p = {u(rng), u(rng)};
  Triangulation tri;
  ASSERT_TRUE(tri.build_delaunay(pts).has_value());
  expect_valid(tri);
  EXPECT_EQ(tri.num_duplicates, 0u);
  EXPECT_EQ(tri.count_real(), 2 * pts.size() - 2 - hull_size(tri));
}

TEST(Mesh2dDelaunay, IntegerGridAllCocircular) {
  std::vector<Point2> pts;
  for (int i = 0; i < 60; ++i)
    for (int j = 0; j < 50; ++j) pts.push_back({double(i), double(j)});
  Triangulation tri;
  ASSERT_TRUE(tri.build_delaunay(pts).has_value());
  expect_valid(tri);
  // Hull: 2*(60+50) - 4 boundary vertices, all on hull edges (collinear hull points are
  // hull vertices too).
  EXPECT_EQ(hull_size(tri), 2u * (60 + 50) - 4);
  EXPECT_EQ(tri.count_real(), 2 * pts.size() - 2 - hull_size(tri));
}

TEST(Mesh2dDelaunay, PointsOnACircleAndCenter) {
  std::vector<Point2> pts;
  const int n = 64;
  for (int k = 0; k < n; ++k) {
    const double a = 2 * M_PI * k / n;
    pts.push_back({std::cos(a), std::sin(a)});
  }
  pts.push_back({0.0, 0.0});
  // Exactly cocircular points: the four axis points and diagonal-free square corners.
  pts.push_back({3.0, 0.0});
  pts.push_back({-3.0, 0.0});
  pts.push_back({0.0, 3.0});
  pts.push_back({0.0, -3.0});
  Triangulation tri;
  ASSERT_TRUE(tri.build_delaunay(pts).has_value());
  expect_valid(tri);
}

TEST(Mesh2dDelaunay, DuplicatesAreMergedAndCounted) {
  std::vector<Point2> pts = {{0, 0}, {1, 0}, {0, 1}, {1, 1}, {0, 0}, {1, 1}, {0.5, 0.25}, {1, 1}};
  Triangulation tri;
  ASSERT_TRUE(tri.build_delaunay(pts).has_value());
  expect_valid(tri);
  EXPECT_EQ(tri.num_duplicates, 3u);
  std::size_t dup = 0;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    if (tri.duplicate_of[i] == kNone) continue;
    ++dup;
    EXPECT_EQ(pts[tri.duplicate_of[i]], pts[i]);
    EXPECT_EQ(tri.duplicate_of[tri.duplicate_of[i]], kNone);
  }
  EXPECT_EQ(dup, 3u);
  EXPECT_EQ(tri.count_real(), 4u);
}

TEST(Mesh2dDelaunay, CollinearInputIsAnError) {
  std::vector<Point2> pts;
  for (int i = 0; i < 10; ++i) pts.push_back({0.5 * i, 0.25 * i + 1});  // exact in binary
  pts.push_back(pts[3]);
  Triangulation tri;
  const auto r = tri.build_delaunay(pts);
  ASSERT_FALSE(r.has_value());
  EXPECT_EQ(r.error().code, ErrorCode::DegenerateInput);
}

TEST(Mesh2dDelaunay, CollinearThenOneOff) {
  std::vector<Point2> pts;
  for (int i = 0; i < 50; ++i) pts.push_back({double(i), 2.0 * i});
  pts.push_back({10.0, 0.0});
  Triangulation tri;
  ASSERT_TRUE(tri.build_delaunay(pts).has_value());
  expect_valid(tri);
  EXPECT_EQ(tri.count_real(), 49u);
}

TEST(Mesh2dDelaunay, Deterministic) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-5.0, 5.0);
  std::vector<Point2> pts(3000);
  for (auto& p : pts) p = {std::round(u(rng)), std::round(u(rng) * 100) / 7};
  Triangulation a, b;
  ASSERT_TRUE(a.build_delaunay(pts).has_value());
  ASSERT_TRUE(b.build_delaunay(pts).has_value());
  EXPECT_EQ(a.tv, b.tv);
  EXPECT_EQ(a.tn, b.tn);
  expect_valid(a);
}

TEST(Mesh2dValidate, DetectsBrokenTriangulations) {
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Point2> pts(200);
  for (auto& p : pts) p = {u(rng), u(rng)};
  Triangulation tri;
  ASSERT_TRUE(tri.build_delaunay(pts).has_value());
  ASSERT_TRUE(check_delaunay(tri).empty());
  // Flipping an interior edge of a Delaunay triangulation (whose quadrilateral is
  // convex) makes it non-Delaunay, unless the four points are cocircular.
  bool flipped = false;
  for (std::uint32_t t = 0; t < tri.num_slots() && !flipped; ++t) {
    if (!tri.in_domain(t)) continue;
    for (std::uint32_t i = 0; i < 3 && !flipped; ++i) {
      const std::uint32_t o = tri.tn[3 * t + i];
      if (!tri.in_domain(o / 3)) continue;
      const auto& P = tri.points;
      const std::uint32_t A = tri.vertex(t, i), D = tri.tv[o];
      if (predicates::orient2d(P[A].data(), P[D].data(), P[tri.org(t, i)].data()) ==
          predicates::orient2d(P[A].data(), P[D].data(), P[tri.dest(t, i)].data()))
        continue;  // not convex
      tri.flip(t, i);
      flipped = true;
    }
  }
  ASSERT_TRUE(flipped);
  EXPECT_TRUE(check_topology(tri).empty());
  EXPECT_FALSE(check_delaunay(tri).empty());
  // A one-sided neighbour link is a topology error.
  tri.tn[3 * tri.last_tri] = tri.tn[3 * tri.last_tri + 1];
  EXPECT_FALSE(check_topology(tri).empty());
}

TEST(Mesh2dSpatialSort, IsAPermutation) {
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Point2> pts(5000);
  for (auto& p : pts) p = {u(rng), u(rng)};
  auto order = brio_hilbert_order(pts);
  std::sort(order.begin(), order.end());
  for (std::size_t i = 0; i < order.size(); ++i) ASSERT_EQ(order[i], i);
  // Hilbert curve: consecutive cells are adjacent.
  for (std::uint32_t d = 0; d < 255; ++d) {
    std::uint32_t x0 = 0, y0 = 0, x1 = 0, y1 = 0;
    for (std::uint32_t x = 0; x < 16; ++x)
      for (std::uint32_t y = 0; y < 16; ++y) {
        if (hilbert_index(x, y, 4) == d) x0 = x, y0 = y;
        if (hilbert_index(x, y, 4) == d + 1) x1 = x, y1 = y;
      }
    EXPECT_EQ(std::abs(int(x0) - int(x1)) + std::abs(int(y0) - int(y1)), 1) << d;
  }
}

}  // namespace
}  // namespace delmesh::mesh2d
