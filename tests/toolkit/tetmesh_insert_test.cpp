// Bowyer–Watson insertion into TetMesh: validity after every insertion on random,
// cospherical and grid inputs; cavity computation without commit; splits.
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "tests/support/tetmesh_fixtures.h"
#include "toolkit/predicates/predicates.h"
#include "toolkit/tetmesh/tet_check.h"
#include "toolkit/tetmesh/tet_insert.h"
#include "toolkit/tetmesh/tet_mesh.h"

namespace delmesh {
namespace {

using test::describe;
using test::random_points;

void expect_valid(const TetMesh& mesh, bool symbolic_delaunay = true) {
  const auto topo = check_topology(mesh);
  ASSERT_TRUE(topo.empty()) << describe(topo);
  const auto del = check_delaunay(mesh, 20, symbolic_delaunay);
  ASSERT_TRUE(del.empty()) << describe(del);
}

// Inserts points one by one (first four must be non-coplanar), checking after each.
TetMesh build_checked(const std::vector<Vec3>& points, std::size_t* duplicates = nullptr) {
  TetMesh mesh;
  for (const auto& p : points) mesh.add_vertex(p);
  make_first_tet(mesh, 1, 2, 3, 4);
  Cavity cavity;
  std::size_t dups = 0;
  for (std::uint32_t v = 5; v < mesh.num_vertices(); ++v) {
    const auto r = insert_vertex(mesh, v, kNone, cavity);
    if (r.duplicate_of != kNone) ++dups;
    expect_valid(mesh);
    if (::testing::Test::HasFatalFailure()) {
      ADD_FAILURE() << "after inserting vertex " << v;
      break;
    }
  }
  if (duplicates) *duplicates = dups;
  return mesh;
}

TEST(TetInsert, FirstTetIsPositiveWithFourHullTets) {
  TetMesh mesh;
  mesh.add_vertex({0, 0, 0});
  mesh.add_vertex({0, 1, 0});  // negative order: make_first_tet must reorder
  mesh.add_vertex({1, 0, 0});
  mesh.add_vertex({0, 0, 1});
  make_first_tet(mesh, 1, 2, 3, 4);
  EXPECT_EQ(mesh.num_live_tets(), 5u);
  EXPECT_EQ(mesh.num_finite_tets(), 1u);
  expect_valid(mesh);
}

TEST(TetInsert, RandomPointsValidAfterEveryInsertion) {
  const auto pts = random_points(300, 7);
  const TetMesh mesh = build_checked(pts);
  EXPECT_GT(mesh.num_finite_tets(), 300u);
}

TEST(TetInsert, SmallGridAllCosphericalValidAfterEveryInsertion) {
  std::vector<Vec3> pts;
  // Non-coplanar start, then a 5x5x5 grid (every unit cube cospherical, many points on
  // faces and edges of existing tets, many coplanar with hull faces).
  pts.emplace_back(0, 0, 0);
  pts.emplace_back(4, 0, 0);
  pts.emplace_back(0, 4, 0);
  pts.emplace_back(0, 0, 4);
  for (int x = 0; x < 5; ++x)
    for (int y = 0; y < 5; ++y)
      for (int z = 0; z < 5; ++z) pts.emplace_back(x, y, z);
  std::size_t dups = 0;
  const TetMesh mesh = build_checked(pts, &dups);
  EXPECT_EQ(dups, 4u);  // the four start points reappear in the grid
  // The grid fills the cube [0,4]^3 of volume 64: 64 cubes, at least 5 tets each.
  EXPECT_GE(mesh.num_finite_tets(), 64u * 5u);
}

TEST(TetInsert, PointsOutsideHullAndOnHullPlanes) {
  std::vector<Vec3> pts{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1},
                        {2, 0, 0}, {0, 2, 0}, {1, 1, 0}, {-1, -1, 0},  // on the hull plane z=0
                        {0.5, 0.5, 0}, {3, 3, 3}, {-2, 0.25, 0.25}, {0.25, 0.25, 0.25}};
  build_checked(pts);
}

TEST(TetInsert, ComputeCavityDoesNotChangeTheMesh) {
  auto pts = random_points(60, 11);
  TetMesh mesh;
  for (const auto& p : pts) mesh.add_vertex(p);
  make_first_tet(mesh, 1, 2, 3, 4);
  Cavity cavity;
  for (std::uint32_t v = 5; v < mesh.num_vertices(); ++v) insert_vertex(mesh, v, kNone, cavity);
  const auto before = mesh.records();
  const Vec3 q(0.1, 0.2, -0.05);
  const Location loc = compute_cavity(mesh, q.data(), mesh.num_vertices(), kNone, cavity);
  EXPECT_EQ(loc.kind, LocationKind::InTet);
  EXPECT_FALSE(cavity.tets.empty());
  // Euler: a ball cavity with F boundary triangles has F = 2V - 4 >= 4 faces.
  EXPECT_GE(cavity.boundary.size(), 4u);
  EXPECT_TRUE(cavity_is_star_shaped(mesh, q.data(), cavity));
  const auto& after = mesh.records();
  ASSERT_EQ(before.size(), after.size());
  for (std::size_t t = 0; t < before.size(); ++t) {
    EXPECT_EQ(before[t].v, after[t].v);
    EXPECT_EQ(before[t].adj, after[t].adj);
  }
  // Committing it is the same as inserting.
  const std::uint32_t v = mesh.add_vertex(q);
  commit_cavity(mesh, v, cavity);
  EXPECT_EQ(cavity.created.size(), cavity.boundary.size());
  expect_valid(mesh);
}

TEST(TetInsert, LargeCavityWithManyBoundaryVertices) {
  // The centre of a sphere is in the circumsphere of every tet of points on that sphere:
  // its cavity is the whole interior, bounded by all 300 points (beyond the 64 boundary
  // vertices of the table-based gluing, so the general path runs).
  std::mt19937_64 rng(17);
  std::normal_distribution<double> g;
  std::vector<Vec3> pts;
  while (pts.size() < 300) {
    const Vec3 q(g(rng), g(rng), g(rng));
    if (q.norm() > 1e-3) pts.push_back(q / q.norm());
  }
  TetMesh mesh;
  for (const auto& p : pts) mesh.add_vertex(p);
  make_first_tet(mesh, 1, 2, 3, 4);
  Cavity cavity;
  for (std::uint32_t v = 5; v < mesh.num_vertices(); ++v) insert_vertex(mesh, v, kNone, cavity);
  expect_valid(mesh);
  const std::uint32_t c = mesh.add_vertex({0, 0, 0});
  const auto r = insert_vertex(mesh, c, kNone, cavity);
  EXPECT_EQ(r.location.kind, LocationKind::InTet);
  EXPECT_GT(cavity.boundary.size(), 500u);
  expect_valid(mesh);
  std::vector<std::uint32_t> star;
  mesh.star(c, star);
  EXPECT_EQ(star.size(), cavity.boundary.size());
}

TEST(TetInsert, DuplicateIsReportedNotInserted) {
  auto pts = random_points(20, 3);
  pts.push_back(pts[7]);
  TetMesh mesh;
  for (const auto& p : pts) mesh.add_vertex(p);
  make_first_tet(mesh, 1, 2, 3, 4);
  Cavity cavity;
  for (std::uint32_t v = 5; v < 21; ++v) insert_vertex(mesh, v, kNone, cavity);
  const auto tets = mesh.num_live_tets();
  const auto r = insert_vertex(mesh, 21, kNone, cavity);
  EXPECT_EQ(r.location.kind, LocationKind::OnVertex);
  EXPECT_EQ(r.duplicate_of, 8u);
  EXPECT_EQ(mesh.num_live_tets(), tets);
  expect_valid(mesh);
}

TEST(TetInsert, SplitTetFaceAndEdgeKeepValidity) {
  TetMesh mesh;
  mesh.add_vertex({0, 0, 0});
  mesh.add_vertex({4, 0, 0});
  mesh.add_vertex({0, 4, 0});
  mesh.add_vertex({0, 0, 4});
  mesh.add_vertex({4, 4, 4});
  make_first_tet(mesh, 1, 2, 3, 4);
  Cavity cavity;
  insert_vertex(mesh, 5, kNone, cavity);
  // Split the interior face (2,3,4) at its centroid-ish point (exact: 4/3 not needed,
  // use a point with exactly representable barycentric coordinates).
  const auto face = mesh.find_face(2, 3, 4);
  ASSERT_TRUE(face.has_value());
  const std::uint32_t f = mesh.add_vertex({2, 1, 1});  // 0.5*(4,0,0) + 0.25*(0,4,0) + 0.25*(0,0,4)
  EXPECT_TRUE(split_face(mesh, *face, f, cavity));
  expect_valid(mesh, false);
  EXPECT_EQ(cavity.created.size(), 6u);
  // Split the hull edge (2,3) at its midpoint (its ring holds infinite tets).
  const std::uint32_t e = mesh.add_vertex({2, 2, 0});
  std::vector<std::uint32_t> ring;
  ASSERT_TRUE(mesh.tets_around_edge(2, 3, ring));
  const std::size_t m = ring.size();
  EXPECT_TRUE(split_edge(mesh, 2, 3, e, cavity));
  EXPECT_EQ(cavity.created.size(), 2 * m);
  EXPECT_FALSE(check_topology(mesh).size());
  // Split the hull face (1, 2, e) (on the plane z = 0) at an interior point: the
  // infinite tet behind it becomes three.
  const auto hull_face = mesh.find_face(1, 2, e);
  ASSERT_TRUE(hull_face.has_value());
  const std::uint32_t h = mesh.add_vertex({2, 0.5, 0});
  const std::uint32_t infinite_before = mesh.num_live_tets() - mesh.num_finite_tets();
  EXPECT_TRUE(split_face(mesh, *hull_face, h, cavity));
  EXPECT_EQ(mesh.num_live_tets() - mesh.num_finite_tets(), infinite_before + 2);
  EXPECT_TRUE(check_topology(mesh).empty()) << describe(check_topology(mesh));
  // Split a tet at an interior point.
  std::uint32_t finite = kNone;
  for (std::uint32_t t = 0; t < mesh.tet_slots() && finite == kNone; ++t) {
    if (!mesh.is_dead(t) && mesh.is_finite(t)) finite = t;
  }
  Vec3 c = Vec3::Zero();
  for (const auto w : mesh.tet(finite).v) c += mesh.point(w);
  const std::uint32_t x = mesh.add_vertex(c / 4);
  EXPECT_TRUE(split_tet(mesh, finite, x, cavity));
  EXPECT_TRUE(check_topology(mesh).empty()) << describe(check_topology(mesh));
  // A point outside the face is refused and nothing changes.
  const auto face2 = mesh.find_face(3, 4, f);
  ASSERT_TRUE(face2.has_value());
  const std::uint32_t bad = mesh.add_vertex({10, 10, 10});
  const auto live = mesh.num_live_tets();
  EXPECT_FALSE(split_face(mesh, *face2, bad, cavity));
  EXPECT_EQ(mesh.num_live_tets(), live);
  EXPECT_TRUE(check_topology(mesh).empty());
}

}  // namespace
}  // namespace delmesh
