// Facet triangulations (OpenMesh) in a tilted plane: assignment, Delaunay flips, vertex
// insertion with off-plane (rounded) Steiner points, segment splits, holes, change lists;
// several facets in one FacetMeshPool sharing global vertices; lone triangles kept out of
// the pool until changed.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <set>

#include "toolkit/facet/facet_triangulation.h"

namespace delmesh {
namespace {

// The plane z = x + 2y; normal (-1, -2, 1), dominant axis Y.
Vec3 on_plane(double x, double y) { return {x, y, x + 2 * y}; }
const Vec3 kNormal(-1, -2, 1);

std::set<Subface> as_set(const std::vector<Subface>& faces) {
  std::set<Subface> out;
  for (auto f : faces) {
    std::sort(f.begin(), f.end());
    out.insert(f);
  }
  return out;
}

double facet_area(const FacetTriangulation& facet, const std::vector<Vec3>& points) {
  double area = 0;
  for (const auto& f : facet.subfaces()) area += 0.5 * (points[f[1]] - points[f[0]]).cross(points[f[2]] - points[f[0]]).norm();
  return area;
}

class FacetTriangulationTest : public ::testing::Test {
 protected:
  void add(FacetTriangulation& facet, const Vec3& p) {
    points.push_back(p);
    facet.add_vertex(static_cast<std::uint32_t>(points.size() - 1));
  }
  /// Square [0,4]^2 lifted to the plane (a parallelogram in the plane), two triangles
  /// with diagonal 0-2, not yet made Delaunay.
  FacetTriangulation raw_square() {
    FacetTriangulation facet(pool, kNormal);
    for (auto [x, y] : {std::pair{0, 0}, {4, 0}, {4, 4}, {0, 4}}) add(facet, on_plane(x, y));
    const std::vector<Subface> tris{{0, 1, 2}, {0, 2, 3}};
    const std::vector<std::array<std::uint32_t, 2>> segs{{0, 1}, {1, 2}, {2, 3}, {3, 0}};
    EXPECT_TRUE(facet.assign(tris, segs));
    return facet;
  }
  FacetTriangulation square() {
    FacetTriangulation facet = raw_square();
    facet.make_delaunay();
    return facet;
  }
  std::uint32_t next_id() const { return static_cast<std::uint32_t>(points.size()); }
  std::vector<Vec3> points;
  FacetMeshPool pool{points};
  std::mt19937_64 rng{7};
};

TEST_F(FacetTriangulationTest, AssignThenFlipToTheInPlaneDelaunayDiagonal) {
  FacetTriangulation facet = raw_square();
  EXPECT_EQ(facet.axis(), Axis::Y);
  EXPECT_EQ(facet.subface_count(), 2u);
  EXPECT_TRUE(facet.has_subface(0, 1, 2));
  EXPECT_TRUE(facet.has_subface(2, 0, 3));
  // In its plane the square is a parallelogram whose short diagonal is 1-3 (|1-3|^2 = 48
  // against |0-2|^2 = 176): the Delaunay triangulation uses it.
  EXPECT_EQ(facet.check().size(), 1u);
  SubfaceChange change;
  EXPECT_EQ(facet.make_delaunay(&change), 1u);
  EXPECT_TRUE(facet.check().empty());
  EXPECT_TRUE(facet.has_subface(0, 1, 3));
  EXPECT_TRUE(facet.has_subface(1, 2, 3));
  EXPECT_EQ(change.removed.size(), 2u);
  EXPECT_EQ(change.added.size(), 2u);
  EXPECT_TRUE(facet.is_segment(0, 1));
  EXPECT_FALSE(facet.is_segment(1, 3));
  EXPECT_EQ(facet.make_delaunay(), 0u);
}

TEST_F(FacetTriangulationTest, RandomInsertionsKeepAValidConstrainedDelaunayFacet) {
  FacetTriangulation facet = square();
  const double area = facet_area(facet, points);
  std::uniform_real_distribution<double> u(0.01, 3.99);
  for (int i = 0; i < 300; ++i) {
    const auto before = as_set(facet.subfaces());
    const std::uint32_t id = next_id();
    points.push_back(on_plane(u(rng), u(rng)));  // z rounded: off the plane by roundoff
    auto change = facet.insert_vertex(id, points.back());
    ASSERT_TRUE(change) << change.error().describe();
    // after = before - removed + added
    auto expected = before;
    for (const auto& f : change->removed) ASSERT_EQ(expected.erase(f), 1u);
    for (const auto& f : change->added) ASSERT_TRUE(expected.insert(f).second);
    ASSERT_EQ(expected, as_set(facet.subfaces()));
    ASSERT_TRUE(facet.check().empty()) << facet.check().front();
  }
  EXPECT_EQ(facet.subface_count(), 2u + 2u * 300u);
  EXPECT_EQ(facet.segments().size(), 4u);
  EXPECT_NEAR(facet_area(facet, points), area, 1e-9 * area);
}

TEST_F(FacetTriangulationTest, WalkStartNearAVertexGivesTheSameInsertions) {
  // Two copies of the square in one pool; the same points go into both, into one with the
  // walk started at a random vertex of the facet. Quarter-grid points lie exactly on the
  // plane and often exactly on edges (midpoints of diagonals), where the walk could stop
  // in either triangle of the edge: the changes must be the same, in the same order.
  FacetTriangulation plain = square();
  FacetTriangulation hinted(pool, kNormal);
  for (std::uint32_t v = 0; v < 4; ++v) hinted.add_vertex(v);
  const std::vector<Subface> tris{{0, 1, 2}, {0, 2, 3}};
  const std::vector<std::array<std::uint32_t, 2>> segs{{0, 1}, {1, 2}, {2, 3}, {3, 0}};
  ASSERT_TRUE(hinted.assign(tris, segs));
  hinted.make_delaunay();
  std::vector<std::pair<int, int>> grid;
  for (int x = 1; x < 16; ++x)
    for (int y = 1; y < 16; ++y) grid.emplace_back(x, y);
  std::shuffle(grid.begin(), grid.end(), rng);
  std::vector<std::uint32_t> ids{0, 1, 2, 3};
  for (const auto& [x, y] : grid) {
    const std::uint32_t id = next_id();
    points.push_back(on_plane(x / 4.0, y / 4.0));
    const std::uint32_t near = ids[std::uniform_int_distribution<std::size_t>(0, ids.size() - 1)(rng)];
    auto a = plain.insert_vertex(id, points.back());
    auto b = hinted.insert_vertex(id, points.back(), near);
    ASSERT_TRUE(a) << a.error().describe();
    ASSERT_TRUE(b) << b.error().describe();
    ASSERT_EQ(a->removed, b->removed) << "point " << x << " " << y;
    ASSERT_EQ(a->added, b->added) << "point " << x << " " << y;
    ids.push_back(id);
  }
  EXPECT_EQ(as_set(plain.subfaces()), as_set(hinted.subfaces()));
  EXPECT_TRUE(hinted.check().empty());
}

TEST_F(FacetTriangulationTest, SegmentSplitsKeepTheBoundaryAsAChain) {
  FacetTriangulation facet = square();
  const std::uint32_t m = next_id();
  points.push_back(on_plane(2, 0));
  auto change = facet.split_segment(0, 1, m, points.back());
  ASSERT_TRUE(change) << change.error().describe();
  EXPECT_TRUE(facet.is_segment(0, m));
  EXPECT_TRUE(facet.is_segment(m, 1));
  EXPECT_FALSE(facet.is_segment(0, 1));
  EXPECT_FALSE(facet.is_segment(m, 2));  // the new spoke is not a segment
  EXPECT_EQ(facet.subface_count(), 3u);
  EXPECT_TRUE(facet.check().empty());
  // a vertex exactly on a segment inserted as a free vertex splits the segment too
  const std::uint32_t q = next_id();
  points.push_back(on_plane(4, 1));
  ASSERT_TRUE(facet.insert_vertex(q, points.back()));
  EXPECT_TRUE(facet.is_segment(1, q));
  EXPECT_TRUE(facet.is_segment(q, 2));
  EXPECT_EQ(facet.segments().size(), 6u);
  EXPECT_FALSE(facet.split_segment(0, 2, next_id(), on_plane(2, 2)));  // not a segment
}

TEST_F(FacetTriangulationTest, PointsOutsideOrOnVerticesAreRefused) {
  FacetTriangulation facet = square();
  auto outside = facet.insert_vertex(next_id(), on_plane(5, 1));
  ASSERT_FALSE(outside);
  EXPECT_EQ(outside.error().code, ErrorCode::InvalidInput);
  auto duplicate = facet.insert_vertex(next_id() + 1, on_plane(4, 4));
  ASSERT_FALSE(duplicate);
  EXPECT_EQ(duplicate.error().code, ErrorCode::DuplicateVertex);
  EXPECT_EQ(facet.subface_count(), 2u);
  EXPECT_TRUE(facet.check().empty());
}

TEST_F(FacetTriangulationTest, FacetWithAHoleRejectsPointsInTheHole) {
  FacetTriangulation facet(pool, kNormal);
  // outer square 0..3 (side 6), inner square 4..7 (2..4)
  for (auto [x, y] : {std::pair{0, 0}, {6, 0}, {6, 6}, {0, 6}, {2, 2}, {4, 2}, {4, 4}, {2, 4}}) add(facet, on_plane(x, y));
  const std::vector<Subface> ring{{0, 1, 5}, {0, 5, 4}, {1, 2, 6}, {1, 6, 5}, {2, 3, 7}, {2, 7, 6}, {3, 0, 4}, {3, 4, 7}};
  ASSERT_TRUE(facet.assign(ring, std::vector<std::array<std::uint32_t, 2>>{}));
  EXPECT_EQ(facet.segments().size(), 8u);  // both boundaries are segments
  facet.make_delaunay();
  EXPECT_TRUE(facet.check().empty());
  auto in_hole = facet.insert_vertex(next_id(), on_plane(3, 3));
  ASSERT_FALSE(in_hole);
  std::uniform_real_distribution<double> u(0.01, 5.99);
  int inserted = 0;
  while (inserted < 100) {
    const double x = u(rng), y = u(rng);
    if (x > 1.99 && x < 4.01 && y > 1.99 && y < 4.01) continue;
    const std::uint32_t id = next_id();
    points.push_back(on_plane(x, y));
    ASSERT_TRUE(facet.insert_vertex(id, points.back()));
    ++inserted;
  }
  EXPECT_TRUE(facet.check().empty());
  EXPECT_NEAR(facet_area(facet, points), 32.0 * std::sqrt(6.0), 1e-9);  // (36 - 4) * |n|
}

TEST_F(FacetTriangulationTest, InsertionIsDeterministic) {
  auto build = [&]() {
    points.clear();
    FacetTriangulation facet = square();
    std::mt19937_64 local(99);
    std::uniform_real_distribution<double> u(0.01, 3.99);
    for (int i = 0; i < 100; ++i) {
      const std::uint32_t id = next_id();
      points.push_back(on_plane(u(local), u(local)));
      EXPECT_TRUE(facet.insert_vertex(id, points.back()));
    }
    return facet.subfaces();
  };
  EXPECT_EQ(build(), build());
}

TEST_F(FacetTriangulationTest, BadAssignmentsAreErrors) {
  FacetTriangulation facet(pool, kNormal);
  for (auto [x, y] : {std::pair{0, 0}, {1, 0}, {2, 0}}) add(facet, on_plane(x, y));
  const std::vector<Subface> flat{{0, 1, 2}};
  auto degenerate = facet.assign(flat, std::vector<std::array<std::uint32_t, 2>>{});
  ASSERT_FALSE(degenerate);
  EXPECT_EQ(degenerate.error().code, ErrorCode::DegenerateInput);
  FacetTriangulation other(pool, kNormal);
  const std::vector<Subface> missing{{0, 1, 9}};
  EXPECT_FALSE(other.assign(missing, std::vector<std::array<std::uint32_t, 2>>{}));
}

}  // namespace
}  // namespace delmesh

namespace delmesh {
namespace {

TEST_F(FacetTriangulationTest, LoneTriangleAnswersAsBuiltAndEntersThePoolOnlyWhenChanged) {
  std::uniform_real_distribution<double> coord(-4.0, 4.0);
  for (int trial = 0; trial < 200; ++trial) {
    points.clear();
    for (int k = 0; k < 3; ++k) points.push_back(on_plane(coord(rng), coord(rng)));
    points.push_back(on_plane(coord(rng), coord(rng)));  // a point to insert
    const std::array<std::uint32_t, 3> order{0, 1, 2};
    // Any orientation and rotation of the triangle, as lone_triangle may give it.
    Subface triangle{static_cast<std::uint32_t>(trial % 3), static_cast<std::uint32_t>((trial + 1) % 3),
                     static_cast<std::uint32_t>((trial + 2) % 3)};
    if (trial % 2) std::swap(triangle[1], triangle[2]);
    FacetMeshPool eager_pool(points), lone_pool(points);
    FacetTriangulation eager(eager_pool, kNormal), lone(lone_pool, kNormal);
    for (const std::uint32_t g : order) eager.add_vertex(g);
    const std::vector<std::array<std::uint32_t, 2>> edges{{triangle[0], triangle[1]},
                                                          {triangle[1], triangle[2]},
                                                          {triangle[2], triangle[0]}};
    const auto eager_ok = eager.assign(std::vector<Subface>{triangle}, edges);
    const auto lone_ok = lone.assign_lone_triangle(order, triangle);
    ASSERT_EQ(eager_ok.has_value(), lone_ok.has_value()) << trial;
    if (!eager_ok) continue;  // degenerate in projection: both refuse it
    EXPECT_EQ(eager.make_delaunay(), lone.make_delaunay());
    EXPECT_TRUE(lone.deferred());
    EXPECT_EQ(lone_pool.mesh().n_vertices(), 0u);
    EXPECT_EQ(lone_pool.mesh().n_faces(), 0u);
    EXPECT_EQ(lone.subfaces(), eager.subfaces()) << trial;
    EXPECT_EQ(lone.segments(), eager.segments()) << trial;
    EXPECT_EQ(lone.subface_count(), eager.subface_count());
    EXPECT_EQ(lone.check(), eager.check());
    for (std::uint32_t a = 0; a < 5; ++a) {
      EXPECT_EQ(lone.has_vertex(a), eager.has_vertex(a));
      for (std::uint32_t b = 0; b < 5; ++b) {
        EXPECT_EQ(lone.is_segment(a, b), eager.is_segment(a, b));
        EXPECT_EQ(lone.third_vertex(a, b), eager.third_vertex(a, b));
        for (std::uint32_t c = 0; c < 5; ++c) EXPECT_EQ(lone.has_subface(a, b, c), eager.has_subface(a, b, c));
      }
      const Vec3 moved = on_plane(coord(rng), coord(rng));
      EXPECT_EQ(lone.can_move_vertex(a, moved), eager.can_move_vertex(a, moved));
    }
    for (int k = 0; k < 8; ++k) {
      const Vec3 p = on_plane(coord(rng), coord(rng));
      EXPECT_EQ(lone.locate(p.data(), 0), eager.locate(p.data(), 0));
    }
    // The first change builds the component as add_vertex and assign would have.
    const auto eager_change = eager.insert_vertex(3, points[3]);
    const auto lone_change = lone.insert_vertex(3, points[3]);
    EXPECT_FALSE(lone.deferred());
    EXPECT_EQ(lone_pool.mesh().n_vertices(), eager_pool.mesh().n_vertices());
    ASSERT_EQ(lone_change.has_value(), eager_change.has_value());
    if (eager_change) {
      EXPECT_EQ(lone_change->removed, eager_change->removed);
      EXPECT_EQ(lone_change->added, eager_change->added);
    }
    EXPECT_EQ(lone.subfaces(), eager.subfaces()) << trial;
    EXPECT_EQ(lone.segments(), eager.segments()) << trial;
    EXPECT_TRUE(lone.check().empty());
  }
}

TEST(FacetTriangulationMove, MovesWithinTheTrianglesAroundAndRefusesInversions) {
  // Square (0,0)-(4,4) in the plane z = 0 with a centre vertex 4 fanned to the corners.
  std::vector<Vec3> p{{0, 0, 0}, {4, 0, 0}, {4, 4, 0}, {0, 4, 0}, {2, 2, 0}};
  FacetMeshPool pool(p);
  FacetTriangulation facet(pool, Vec3(0, 0, 1));
  for (std::uint32_t i = 0; i < p.size(); ++i) facet.add_vertex(i);
  const std::vector<Subface> tris{{0, 1, 4}, {1, 2, 4}, {2, 3, 4}, {3, 0, 4}};
  const std::vector<std::array<std::uint32_t, 2>> segs{{0, 1}, {1, 2}, {2, 3}, {3, 0}};
  ASSERT_TRUE(facet.assign(tris, segs));
  EXPECT_TRUE(facet.can_move_vertex(4, Vec3(1, 3, 0)));
  EXPECT_FALSE(facet.can_move_vertex(4, Vec3(5, 2, 0)));  // outside: triangle (1,2,4) inverts
  EXPECT_FALSE(facet.can_move_vertex(4, Vec3(4, 2, 0)));  // on the boundary: flat triangle
  EXPECT_FALSE(facet.can_move_vertex(9, Vec3(1, 1, 0)));  // unknown vertex
  // The facet reads the shared coordinates: moving the point there moves the vertex.
  p[4] = Vec3(1, 3, 0);
  for (const Subface& f : facet.subfaces()) EXPECT_GT((p[f[1]] - p[f[0]]).cross(p[f[2]] - p[f[0]]).z(), 0.0);
  EXPECT_TRUE(facet.can_move_vertex(4, Vec3(3, 1, 0)));
  EXPECT_FALSE(facet.can_move_vertex(4, Vec3(-1, 2, 0)));
  p[4] = Vec3(-1, 2, 0);  // moved without the check: the facet now sees an inverted triangle
  EXPECT_FALSE(facet.check().empty());
  EXPECT_EQ(facet.pool().global_id(facet.vertex_handle(4)), 4u);
}

}  // namespace
}  // namespace delmesh
