// delaunay_tetrahedralize: bulk construction on random, grid (all cospherical) and
// sphere inputs, duplicates, degenerate inputs, determinism.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "tests/support/tetmesh_fixtures.h"
#include "toolkit/tetmesh/delaunay.h"
#include "toolkit/tetmesh/tet_check.h"

namespace delmesh {
namespace {

using test::describe;
using test::random_points;

void expect_valid_delaunay(const TetMesh& mesh) {
  const auto topo = check_topology(mesh);
  ASSERT_TRUE(topo.empty()) << describe(topo);
  const auto del = check_delaunay(mesh);
  ASSERT_TRUE(del.empty()) << describe(del);
  const auto sos = check_delaunay(mesh, 20, true);
  ASSERT_TRUE(sos.empty()) << describe(sos);
}

// Every vertex id 1..n (except merged duplicates) appears in some tet.
void expect_all_points_used(const DelaunayResult& r, std::size_t n) {
  std::vector<bool> used(n + 1, false);
  for (std::uint32_t t = 0; t < r.mesh.tet_slots(); ++t) {
    if (r.mesh.is_dead(t)) continue;
    for (const auto v : r.mesh.tet(t).v) used[v] = true;
  }
  for (std::size_t i = 0; i < n; ++i) {
    const bool dup = !r.duplicate_of.empty() && r.duplicate_of[i] != kNone;
    EXPECT_EQ(used[i + 1], !dup) << "point " << i;
  }
}

TEST(Delaunay, RandomPointsBulk) {
  const auto pts = random_points(20000, 1);
  auto r = delaunay_tetrahedralize(pts);
  ASSERT_TRUE(r.has_value()) << r.error().describe();
  EXPECT_EQ(r->num_duplicates, 0u);
  // About 6.5 tets per point for uniform random points.
  EXPECT_GT(r->mesh.num_finite_tets(), 6 * 20000u);
  EXPECT_LT(r->mesh.num_finite_tets(), 7 * 20000u);
  EXPECT_EQ(r->mesh.num_live_tets(), r->mesh.tet_slots());  // compacted
  expect_valid_delaunay(r->mesh);
  expect_all_points_used(*r, pts.size());
}

TEST(Delaunay, InputOrderInsertionGivesTheSameValidMesh) {
  const auto pts = random_points(2000, 2);
  DelaunayOptions plain;
  plain.spatial_sort = false;
  auto a = delaunay_tet_list(pts, plain);
  auto b = delaunay_tet_list(pts);
  ASSERT_TRUE(a.has_value() && b.has_value());
  // Random points are in general position: the Delaunay tetrahedralization is unique.
  auto sorted = [](std::vector<std::array<std::uint32_t, 4>> tets) {
    for (auto& t : tets) std::sort(t.begin(), t.end());
    std::sort(tets.begin(), tets.end());
    return tets;
  };
  EXPECT_EQ(sorted(a->tets), sorted(b->tets));
}

// 6 x signed volume of tet (a, b, c, d) with integer coordinates, exactly.
long long six_volume(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  const long long bx = std::llround(b[0] - a[0]), by = std::llround(b[1] - a[1]), bz = std::llround(b[2] - a[2]);
  const long long cx = std::llround(c[0] - a[0]), cy = std::llround(c[1] - a[1]), cz = std::llround(c[2] - a[2]);
  const long long dx = std::llround(d[0] - a[0]), dy = std::llround(d[1] - a[1]), dz = std::llround(d[2] - a[2]);
  return bx * (cy * dz - cz * dy) - by * (cx * dz - cz * dx) + bz * (cx * dy - cy * dx);
}

TEST(Delaunay, IntegerGrid30AllCospherical) {
  std::vector<Vec3> pts;
  for (int x = 0; x < 30; ++x)
    for (int y = 0; y < 30; ++y)
      for (int z = 0; z < 30; ++z) pts.emplace_back(x, y, z);
  auto r = delaunay_tetrahedralize(pts);
  ASSERT_TRUE(r.has_value()) << r.error().describe();
  expect_valid_delaunay(r->mesh);
  expect_all_points_used(*r, pts.size());
  // The tets tile the cube [0, 29]^3 exactly: their volumes add up to 29^3, and none is
  // flat.
  long long total = 0;
  for (const auto& t : finite_tets_as_input_indices(r->mesh)) {
    const long long v = six_volume(pts[t[0]], pts[t[1]], pts[t[2]], pts[t[3]]);
    ASSERT_GT(v, 0);
    total += v;
  }
  EXPECT_EQ(total, 6LL * 29 * 29 * 29);
}

TEST(Delaunay, PointsOnASphere) {
  std::mt19937_64 rng(3);
  std::normal_distribution<double> g;
  std::vector<Vec3> pts;
  while (pts.size() < 3000) {
    const Vec3 q(g(rng), g(rng), g(rng));
    if (q.norm() > 1e-3) pts.push_back(q / q.norm());
  }
  // Plus the exactly cospherical octahedron and cube corners of a second sphere.
  for (int s = -1; s <= 1; s += 2) {
    pts.emplace_back(3 * s, 0, 0);
    pts.emplace_back(0, 3 * s, 0);
    pts.emplace_back(0, 0, 3 * s);
  }
  auto r = delaunay_tetrahedralize(pts);
  ASSERT_TRUE(r.has_value()) << r.error().describe();
  expect_valid_delaunay(r->mesh);
  expect_all_points_used(*r, pts.size());
}

TEST(Delaunay, DuplicatesAreMergedIntoTheLowestIndex) {
  auto pts = random_points(500, 4);
  pts.push_back(pts[10]);   // 500 -> 10
  pts.push_back(pts[10]);   // 501 -> 10
  pts.insert(pts.begin(), pts[99]);  // new index 0 equals (shifted) index 100
  auto r = delaunay_tetrahedralize(pts);
  ASSERT_TRUE(r.has_value()) << r.error().describe();
  EXPECT_EQ(r->num_duplicates, 3u);
  ASSERT_EQ(r->duplicate_of.size(), pts.size());
  EXPECT_EQ(r->duplicate_of[501], 11u);
  EXPECT_EQ(r->duplicate_of[502], 11u);
  EXPECT_EQ(r->duplicate_of[100], 0u);
  EXPECT_EQ(r->duplicate_of[0], kNone);
  EXPECT_EQ(r->duplicate_of[11], kNone);
  std::size_t listed = 0;
  for (const auto d : r->duplicate_of) listed += d != kNone;
  EXPECT_EQ(listed, 3u);
  expect_valid_delaunay(r->mesh);
  expect_all_points_used(*r, pts.size());
}

TEST(Delaunay, DegenerateInputsAreClearErrors) {
  std::vector<Vec3> coplanar;
  for (int i = 0; i < 50; ++i) coplanar.emplace_back(i % 7, i / 7, 0.0);
  auto r1 = delaunay_tetrahedralize(coplanar);
  ASSERT_FALSE(r1.has_value());
  EXPECT_EQ(r1.error().code, ErrorCode::DegenerateInput);
  EXPECT_NE(r1.error().message.find("coplanar"), std::string::npos);

  // A tilted plane (not axis-aligned) is coplanar too.
  std::vector<Vec3> tilted;
  for (int i = 0; i < 40; ++i) tilted.emplace_back(i % 5, i / 5, (i % 5) + 2.0 * (i / 5));
  auto r2 = delaunay_tetrahedralize(tilted);
  ASSERT_FALSE(r2.has_value());
  EXPECT_NE(r2.error().message.find("coplanar"), std::string::npos);

  std::vector<Vec3> collinear;
  for (int i = 0; i < 20; ++i) collinear.emplace_back(i, 2 * i, -3 * i);
  auto r3 = delaunay_tetrahedralize(collinear);
  ASSERT_FALSE(r3.has_value());
  EXPECT_NE(r3.error().message.find("collinear"), std::string::npos);

  std::vector<Vec3> same(10, Vec3(1, 2, 3));
  auto r4 = delaunay_tetrahedralize(same);
  ASSERT_FALSE(r4.has_value());
  EXPECT_NE(r4.error().message.find("same position"), std::string::npos);

  auto r5 = delaunay_tetrahedralize(std::vector<Vec3>{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
  ASSERT_FALSE(r5.has_value());
  EXPECT_EQ(r5.error().code, ErrorCode::DegenerateInput);

  auto pts = random_points(10, 5);
  pts[6][1] = std::nan("");
  auto r6 = delaunay_tetrahedralize(pts);
  ASSERT_FALSE(r6.has_value());
  EXPECT_EQ(r6.error().code, ErrorCode::InvalidInput);
  ASSERT_EQ(r6.error().entity_ids.size(), 1u);
  EXPECT_EQ(r6.error().entity_ids[0], 6u);
}

// Taking the points by move gives the same mesh as copying them, keeps every point bit
// for bit at vertex i + 1, and leaves the caller's array empty.
TEST(Delaunay, MovedInPointsGiveTheSameMesh) {
  auto pts = random_points(3000, 7);
  for (int k = 0; k < 5; ++k) pts.push_back(pts[100 * k + 3]);  // duplicates too
  auto copied = delaunay_tetrahedralize(pts);
  std::vector<Vec3> handed = pts;
  auto moved = delaunay_tetrahedralize(std::move(handed));
  ASSERT_TRUE(copied.has_value() && moved.has_value());
  EXPECT_TRUE(handed.empty());
  ASSERT_EQ(moved->mesh.num_vertices(), pts.size() + 1);
  for (std::size_t i = 0; i < pts.size(); ++i) {
    EXPECT_EQ(moved->mesh.point(static_cast<std::uint32_t>(i + 1)), pts[i]) << "point " << i;
  }
  ASSERT_EQ(moved->mesh.tet_slots(), copied->mesh.tet_slots());
  for (std::uint32_t t = 0; t < moved->mesh.tet_slots(); ++t) {
    EXPECT_EQ(moved->mesh.tet(t).v, copied->mesh.tet(t).v) << "tet " << t;
    EXPECT_EQ(moved->mesh.tet(t).adj, copied->mesh.tet(t).adj) << "tet " << t;
  }
  EXPECT_EQ(moved->num_duplicates, 5u);
  EXPECT_EQ(moved->duplicate_of, copied->duplicate_of);
  expect_valid_delaunay(moved->mesh);
  expect_all_points_used(*moved, pts.size());
}

TEST(Delaunay, MovedInBadPointIsReportedAndTheArrayIsConsumed) {
  auto pts = random_points(10, 8);
  pts[4][2] = std::numeric_limits<double>::infinity();
  auto r = delaunay_tetrahedralize(std::move(pts));
  ASSERT_FALSE(r.has_value());
  EXPECT_EQ(r.error().code, ErrorCode::InvalidInput);
  ASSERT_EQ(r.error().entity_ids.size(), 1u);
  EXPECT_EQ(r.error().entity_ids[0], 4u);
  EXPECT_TRUE(pts.empty());  // NOLINT(bugprone-use-after-move): the documented state
}

TEST(Delaunay, CoplanarPointsPlusOneApexWork) {
  std::vector<Vec3> pts;
  for (int x = 0; x < 6; ++x)
    for (int y = 0; y < 6; ++y) pts.emplace_back(x, y, 0);
  pts.emplace_back(2.5, 2.5, 1);
  auto r = delaunay_tetrahedralize(pts);
  ASSERT_TRUE(r.has_value()) << r.error().describe();
  expect_valid_delaunay(r->mesh);
  // A pyramid over the 5x5 squares: two triangles per square, one tet per triangle.
  EXPECT_EQ(r->mesh.num_finite_tets(), 50u);
}

TEST(Delaunay, SameInputSameOutput) {
  std::vector<Vec3> pts;
  for (int x = 0; x < 8; ++x)
    for (int y = 0; y < 8; ++y)
      for (int z = 0; z < 8; ++z) pts.emplace_back(x, y, z);
  const auto extra = random_points(300, 6);
  pts.insert(pts.end(), extra.begin(), extra.end());
  auto a = delaunay_tet_list(pts);
  auto b = delaunay_tet_list(pts);
  ASSERT_TRUE(a.has_value() && b.has_value());
  EXPECT_EQ(a->tets, b->tets);
}

}  // namespace
}  // namespace delmesh
