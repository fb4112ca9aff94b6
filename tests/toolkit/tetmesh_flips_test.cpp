// Flips and navigation of TetMesh: 2-3 then 3-2 restores the tets, 4-4 on an
// octahedron, edge removal, and the queries find_face / tets_around_edge / star.
#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <random>
#include <set>
#include <vector>

#include "tests/support/tetmesh_fixtures.h"
#include "toolkit/tetmesh/delaunay.h"
#include "toolkit/tetmesh/tet_check.h"
#include "toolkit/tetmesh/tet_flips.h"
#include "toolkit/tetmesh/tet_mesh.h"

namespace delmesh {
namespace {

using test::describe;

using TetSet = std::multiset<std::array<std::uint32_t, 4>>;

TetSet tet_set(const TetMesh& mesh) {
  TetSet s;
  for (std::uint32_t t = 0; t < mesh.tet_slots(); ++t) {
    if (mesh.is_dead(t)) continue;
    auto v = mesh.tet(t).v;
    std::sort(v.begin(), v.end());
    s.insert(v);
  }
  return s;
}

TetMesh random_mesh(std::size_t n, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Vec3> pts;
  for (std::size_t i = 0; i < n; ++i) pts.emplace_back(u(rng), u(rng), u(rng));
  auto r = delaunay_tetrahedralize(pts);
  EXPECT_TRUE(r.has_value());
  return std::move(r->mesh);
}

TEST(TetFlips, Flip23ThenFlip32RestoresTheTets) {
  TetMesh mesh = random_mesh(200, 5);
  const TetSet before = tet_set(mesh);
  int flipped = 0;
  for (std::uint32_t t = 0; t < mesh.tet_slots() && flipped < 10; ++t) {
    if (mesh.is_dead(t) || mesh.is_infinite(t)) continue;
    for (std::uint8_t f = 0; f < 4; ++f) {
      const FaceRef face{t, f};
      const std::uint32_t d = mesh.vertex(t, f);
      const std::uint32_t e = mesh.opposite_vertex(face);
      const TetSet start = tet_set(mesh);
      std::vector<std::uint32_t> created;
      if (!flip23(mesh, face, &created)) continue;
      ASSERT_EQ(created.size(), 3u);
      ASSERT_TRUE(check_topology(mesh).empty()) << describe(check_topology(mesh));
      std::vector<std::uint32_t> around;
      ASSERT_TRUE(mesh.tets_around_edge(d, e, around));
      EXPECT_EQ(around.size(), 3u);
      ASSERT_TRUE(flip32(mesh, d, e, &created));
      ASSERT_EQ(created.size(), 2u);
      ASSERT_TRUE(check_topology(mesh).empty()) << describe(check_topology(mesh));
      EXPECT_EQ(tet_set(mesh), start);
      ++flipped;
      break;
    }
  }
  EXPECT_EQ(flipped, 10);
  EXPECT_EQ(tet_set(mesh), before);
  EXPECT_TRUE(check_delaunay(mesh).empty());
}

TEST(TetFlips, InvalidFlip23IsRefusedAndChangesNothing) {
  TetMesh mesh = random_mesh(200, 9);
  // In a Delaunay mesh of random points, some interior faces are not flippable (the
  // apex edge misses the face): find one and check the refusal leaves the mesh alone.
  int refused = 0;
  for (std::uint32_t t = 0; t < mesh.tet_slots() && refused < 5; ++t) {
    if (mesh.is_dead(t) || mesh.is_infinite(t)) continue;
    for (std::uint8_t f = 0; f < 4; ++f) {
      if (mesh.is_infinite(mesh.neighbor(t, f))) continue;
      const TetSet start = tet_set(mesh);
      const auto slots = mesh.records();
      if (flip23(mesh, {t, f})) {
        // Undo by the inverse flip so the scan continues on the original mesh.
        const std::uint32_t d = slots[t].v[f];
        const std::uint32_t e = slots[slots[t].adj[f] >> 2].v[slots[t].adj[f] & 3u];
        ASSERT_TRUE(flip32(mesh, d, e));
        continue;
      }
      EXPECT_EQ(tet_set(mesh), start);
      ++refused;
    }
  }
  EXPECT_EQ(refused, 5);
  EXPECT_TRUE(check_topology(mesh).empty());
}

TEST(TetFlips, Flip44OnAnOctahedron) {
  // Octahedron around the z axis plus a far cloud so that every octahedron edge is
  // interior. a, b, c0, c2 are coplanar (the plane y = 0): the 4-4 configuration.
  std::vector<Vec3> pts{{0, 0, -1}, {0, 0, 1}, {1, 0, 0}, {0, 1, 0}, {-1, 0, 0}, {0, -1, 0}};
  for (int x = -1; x <= 1; x += 2)
    for (int y = -1; y <= 1; y += 2)
      for (int z = -1; z <= 1; z += 2) pts.emplace_back(5 * x, 5 * y, 5 * z);
  auto r = delaunay_tetrahedralize(pts);
  ASSERT_TRUE(r.has_value());
  TetMesh& mesh = r->mesh;
  // Vertex ids are input index + 1. Exactly one of the three diagonals exists.
  const std::uint32_t diag[3][2] = {{1, 2}, {3, 5}, {4, 6}};
  int which = -1;
  for (int k = 0; k < 3; ++k) {
    if (mesh.find_edge(diag[k][0], diag[k][1])) which = k;
  }
  ASSERT_GE(which, 0);
  for (int step = 0; step < 3; ++step) {
    const int next = (which + 1) % 3;
    std::vector<std::uint32_t> around;
    ASSERT_TRUE(mesh.tets_around_edge(diag[which][0], diag[which][1], around));
    ASSERT_EQ(around.size(), 4u);
    std::vector<std::uint32_t> created;
    ASSERT_TRUE(flip44(mesh, diag[which][0], diag[which][1], diag[next][0], diag[next][1], &created));
    EXPECT_EQ(created.size(), 4u);
    ASSERT_TRUE(check_topology(mesh).empty()) << describe(check_topology(mesh));
    EXPECT_FALSE(mesh.find_edge(diag[which][0], diag[which][1]).has_value());
    EXPECT_TRUE(mesh.find_edge(diag[next][0], diag[next][1]).has_value());
    // Cospherical octahedron: every diagonal is Delaunay (non-strictly).
    EXPECT_TRUE(check_delaunay(mesh).empty());
    which = next;
  }
}

TEST(TetFlips, EdgeRemovalKeepsValidityAndCountsTets) {
  TetMesh mesh = random_mesh(400, 21);
  int removed = 0;
  std::vector<std::uint32_t> around, ring;
  for (std::uint32_t t = 0; t < mesh.tet_slots() && removed < 15; ++t) {
    if (mesh.is_dead(t) || mesh.is_infinite(t)) continue;
    const std::uint32_t a = mesh.vertex(t, 0), b = mesh.vertex(t, 1);
    if (!mesh.tets_around_edge(a, b, around, &ring)) continue;
    const std::size_t m = around.size();
    if (m < 4) continue;
    const std::uint32_t live = mesh.num_live_tets();
    std::vector<std::uint32_t> created;
    if (!remove_edge(mesh, a, b, -std::numeric_limits<double>::infinity(), &created)) continue;
    EXPECT_EQ(created.size(), 2 * (m - 2));
    EXPECT_EQ(mesh.num_live_tets(), live - m + 2 * (m - 2));
    EXPECT_FALSE(mesh.find_edge(a, b).has_value());
    ASSERT_TRUE(check_topology(mesh).empty()) << describe(check_topology(mesh));
    ++removed;
  }
  EXPECT_EQ(removed, 15);
}

TEST(TetFlips, EdgeRemovalRespectsTheQualityThreshold) {
  TetMesh mesh = random_mesh(300, 4);
  std::vector<std::uint32_t> around;
  for (std::uint32_t t = 0; t < mesh.tet_slots(); ++t) {
    if (mesh.is_dead(t) || mesh.is_infinite(t)) continue;
    const std::uint32_t a = mesh.vertex(t, 2), b = mesh.vertex(t, 3);
    if (!mesh.tets_around_edge(a, b, around) || around.size() < 4) continue;
    const TetSet start = tet_set(mesh);
    // No triangulation can beat a perfect quality of 1: refused, nothing changes.
    EXPECT_FALSE(remove_edge(mesh, a, b, 1.0));
    EXPECT_EQ(tet_set(mesh), start);
    return;
  }
  FAIL() << "no interior edge with four or more tets";
}

double worst_shape(const TetMesh& mesh, const std::vector<std::uint32_t>& tets) {
  double worst = std::numeric_limits<double>::infinity();
  for (const std::uint32_t t : tets) {
    const auto& v = mesh.tet(t).v;
    worst = std::min(worst, tet_shape_quality(mesh.point(v[0]), mesh.point(v[1]), mesh.point(v[2]), mesh.point(v[3])));
  }
  return worst;
}

TEST(TetFlips, EdgeRemovalThresholdPrunesWithoutChangingTheChoice) {
  // The dynamic program skips ring triangles that cannot beat the threshold; whenever the
  // best triangulation beats it, the tets made must be those of the unpruned search, and
  // a threshold equal to their worst quality must be refused.
  const TetMesh start = random_mesh(300, 9);
  int compared = 0;
  std::vector<std::uint32_t> around;
  for (std::uint32_t t = 0; t < start.tet_slots() && compared < 20; ++t) {
    if (start.is_dead(t) || start.is_infinite(t)) continue;
    const std::uint32_t a = start.vertex(t, 0), b = start.vertex(t, 3);
    TetMesh free_mesh = start, pruned = start, refused = start;
    if (!free_mesh.tets_around_edge(a, b, around) || around.size() < 5) continue;
    std::vector<std::uint32_t> made, made_pruned;
    if (!remove_edge(free_mesh, a, b, -std::numeric_limits<double>::infinity(), &made)) continue;
    const double worst = worst_shape(free_mesh, made);
    ASSERT_TRUE(remove_edge(pruned, a, b, worst - 1e-9, &made_pruned)) << "edge " << a << "-" << b;
    EXPECT_EQ(tet_set(pruned), tet_set(free_mesh));
    EXPECT_FALSE(remove_edge(refused, a, b, worst));
    EXPECT_EQ(tet_set(refused), tet_set(start));
    ++compared;
  }
  EXPECT_EQ(compared, 20);
}

TEST(TetNavigation, FindFaceEdgeRingAndStarAgreeWithTheTets) {
  TetMesh mesh = random_mesh(150, 8);
  std::vector<std::uint32_t> around, ring, star;
  for (std::uint32_t t = 0; t < mesh.tet_slots(); ++t) {
    if (mesh.is_dead(t)) continue;
    for (std::uint8_t f = 0; f < 4; ++f) {
      const auto fv = mesh.face_vertices({t, f});
      const auto found = mesh.find_face(fv[0], fv[2], fv[1]);
      ASSERT_TRUE(found.has_value());
      auto got = mesh.face_vertices(*found);
      std::sort(got.begin(), got.end());
      auto want = fv;
      std::sort(want.begin(), want.end());
      EXPECT_EQ(got, want);
    }
    const std::uint32_t a = mesh.vertex(t, 0), b = mesh.vertex(t, 3);
    ASSERT_TRUE(mesh.tets_around_edge(a, b, around, &ring));
    ASSERT_EQ(around.size(), ring.size());
    EXPECT_NE(std::find(around.begin(), around.end(), t), around.end());
    for (std::size_t k = 0; k < around.size(); ++k) {
      const std::uint32_t c = ring[k], d = ring[(k + 1) % ring.size()];
      for (const std::uint32_t w : {a, b, c, d}) EXPECT_GE(mesh.local_index(around[k], w), 0);
    }
  }
  for (std::uint32_t v = 1; v < mesh.num_vertices(); ++v) {
    mesh.star(v, star);
    std::size_t holding = 0;
    for (std::uint32_t t = 0; t < mesh.tet_slots(); ++t) {
      if (!mesh.is_dead(t) && mesh.local_index(t, v) >= 0) ++holding;
    }
    EXPECT_EQ(star.size(), holding);
    for (const std::uint32_t t : star) EXPECT_GE(mesh.local_index(t, v), 0);
  }
  EXPECT_FALSE(mesh.find_face(1, 1, 2).has_value());
}

}  // namespace
}  // namespace delmesh
