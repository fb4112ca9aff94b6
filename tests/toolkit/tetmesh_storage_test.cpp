// TetMesh storage: construction from a point array taken by move, the stamp array that
// compact() and release_stamps() release and new_stamp() brings back, and handing
// perturbation ids back.
#include <gtest/gtest.h>

#include <random>
#include <utility>
#include <vector>

#include "tests/support/tetmesh_fixtures.h"
#include "toolkit/tetmesh/delaunay.h"
#include "toolkit/tetmesh/tet_check.h"
#include "toolkit/tetmesh/tet_flips.h"
#include "toolkit/tetmesh/tet_insert.h"
#include "toolkit/tetmesh/tet_mesh.h"

namespace delmesh {
namespace {

using test::describe;
using test::random_points;

TEST(TetMeshStorage, ConstructionFromPointsTakesTheArray) {
  const auto pts = random_points(100, 3);
  std::vector<Vec3> moved = pts;
  moved.shrink_to_fit();  // no room for the infinite vertex: the array must grow once
  TetMesh mesh(std::move(moved));
  ASSERT_EQ(mesh.num_vertices(), 101u);
  for (std::uint32_t i = 0; i < 100; ++i) {
    EXPECT_EQ(mesh.point(i + 1), pts[i]) << "point " << i;
    EXPECT_EQ(mesh.vertex_tet(i + 1), kNone);
  }
  EXPECT_EQ(mesh.vertex_tet(kInfiniteVertex), kNone);
  EXPECT_EQ(mesh.tet_slots(), 0u);
  EXPECT_EQ(mesh.perturbation_id(7), 7u);
  // The mesh is usable like one filled by add_vertex.
  make_first_tet(mesh, 1, 2, 3, 4);
  Cavity cavity;
  for (std::uint32_t v = 5; v <= 100; ++v) insert_vertex(mesh, v, kNone, cavity);
  EXPECT_TRUE(check_topology(mesh).empty()) << describe(check_topology(mesh));
  EXPECT_TRUE(check_delaunay(mesh, 20, true).empty());
}

TEST(TetMeshStorage, TakePerturbationIdsRestoresOwnIds) {
  TetMesh mesh;
  for (int k = 0; k < 3; ++k) mesh.add_vertex({double(k), 0, 0});
  mesh.set_perturbation_ids({0, 3, 1, 2});
  EXPECT_EQ(mesh.perturbation_id(1), 3u);
  const auto ids = mesh.take_perturbation_ids();
  EXPECT_EQ(ids, (std::vector<std::uint32_t>{0, 3, 1, 2}));
  for (std::uint32_t v = 0; v < 4; ++v) EXPECT_EQ(mesh.perturbation_id(v), v);
  EXPECT_TRUE(mesh.take_perturbation_ids().empty());
}

// A 2-3 flip followed by the inverse 3-2 flip leaves one dead slot; compact() must
// squeeze it out, hand back a correct id map in the released stamp buffer, and leave a
// mesh on which marking operations (star, insertion, flips) work again.
TEST(TetMeshStorage, CompactThenMarkAgain) {
  auto r = delaunay_tetrahedralize(random_points(300, 5));
  ASSERT_TRUE(r.has_value()) << r.error().describe();
  TetMesh& mesh = r->mesh;
  bool flipped = false;
  for (std::uint32_t t = 0; t < mesh.tet_slots() && !flipped; ++t) {
    if (mesh.is_infinite(t)) continue;
    for (std::uint8_t f = 0; f < 4 && !flipped; ++f) {
      if (mesh.is_infinite(mesh.neighbor(t, f))) continue;
      const std::uint32_t d = mesh.vertex(t, f);
      const std::uint32_t e = mesh.opposite_vertex({t, f});
      if (!flip23(mesh, {t, f})) continue;
      ASSERT_TRUE(flip32(mesh, d, e));
      flipped = true;
    }
  }
  ASSERT_TRUE(flipped);
  const std::uint32_t slots = mesh.tet_slots();
  const std::uint32_t live = mesh.num_live_tets();
  ASSERT_EQ(slots, live + 1);
  std::vector<TetRecord> before;
  for (std::uint32_t t = 0; t < slots; ++t) {
    if (!mesh.is_dead(t)) before.push_back(mesh.tet(t));
  }
  const auto remap = mesh.compact();
  ASSERT_EQ(remap.size(), slots);
  EXPECT_EQ(mesh.tet_slots(), live);
  EXPECT_EQ(mesh.num_live_tets(), live);
  std::uint32_t next = 0, dead = 0;
  for (std::uint32_t t = 0; t < slots; ++t) {
    if (remap[t] == kNone) {
      ++dead;
      continue;
    }
    EXPECT_EQ(remap[t], next++);
  }
  EXPECT_EQ(dead, 1u);
  for (std::uint32_t t = 0; t < live; ++t) EXPECT_EQ(mesh.tet(t).v, before[t].v);
  ASSERT_TRUE(check_topology(mesh).empty()) << describe(check_topology(mesh));

  // star() marks tets: it must see exactly the tets holding the vertex.
  std::vector<std::uint32_t> star;
  mesh.star(10, star);
  std::uint32_t holding = 0;
  for (std::uint32_t t = 0; t < mesh.tet_slots(); ++t) holding += mesh.local_index(t, 10) >= 0;
  EXPECT_EQ(star.size(), holding);
  // Insertion marks its cavity with stamps, including on tets it creates afterwards.
  Cavity cavity;
  for (const Vec3& p : random_points(50, 6)) {
    const std::uint32_t v = mesh.add_vertex(p * 0.5);
    insert_vertex(mesh, v, kNone, cavity);
  }
  EXPECT_TRUE(check_topology(mesh).empty()) << describe(check_topology(mesh));
  EXPECT_TRUE(check_delaunay(mesh).empty());
}

// release_stamps() frees the stamp array of a mesh in use; the next marking operation
// (insertion) brings it back at full size and the mesh stays a valid Delaunay mesh.
TEST(TetMeshStorage, ReleaseStampsThenMarkAgain) {
  auto r = delaunay_tetrahedralize(random_points(300, 7));
  ASSERT_TRUE(r.has_value()) << r.error().describe();
  TetMesh& mesh = r->mesh;
  const std::uint32_t s = mesh.new_stamp();
  ASSERT_EQ(mesh.stamps().size(), mesh.tet_slots());
  for (std::uint32_t t = 0; t < mesh.tet_slots(); ++t) mesh.set_stamp(t, s);
  mesh.release_stamps();
  EXPECT_TRUE(mesh.stamps().empty());
  EXPECT_EQ(mesh.stamps().capacity(), 0u);
  // Fresh stamps: no tet carries the new value, whatever it carried before.
  const std::uint32_t fresh = mesh.new_stamp();
  ASSERT_EQ(mesh.stamps().size(), mesh.tet_slots());
  for (std::uint32_t t = 0; t < mesh.tet_slots(); ++t) EXPECT_NE(mesh.stamp(t), fresh) << "tet " << t;
  mesh.release_stamps();
  Cavity cavity;
  for (const Vec3& p : random_points(50, 8)) {
    const std::uint32_t v = mesh.add_vertex(p * 0.5);
    insert_vertex(mesh, v, kNone, cavity);
  }
  EXPECT_EQ(mesh.stamps().size(), mesh.tet_slots());
  EXPECT_TRUE(check_topology(mesh).empty()) << describe(check_topology(mesh));
  EXPECT_TRUE(check_delaunay(mesh).empty());
}

}  // namespace
}  // namespace delmesh
