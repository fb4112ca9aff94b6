// Constrained Bowyer–Watson cavities (toolkit/tetmesh/tet_insert.h,
// compute_constrained_cavity and shrink_cavity_to_star; notes §2.1.7): the search never
// crosses a blocked face, so a face between the tet holding the point and a conflict
// tet beyond survives the insertion, and the committed mesh is valid.
#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "tests/support/tetmesh_fixtures.h"
#include "toolkit/tetmesh/tet_check.h"
#include "toolkit/tetmesh/tet_insert.h"
#include "toolkit/tetmesh/tet_mesh.h"

namespace delmesh {
namespace {

using test::describe;
using test::random_points;

TetMesh delaunay_of(const std::vector<Vec3>& points) {
  TetMesh mesh;
  for (const auto& p : points) mesh.add_vertex(p);
  make_first_tet(mesh, 1, 2, 3, 4);
  Cavity cavity;
  for (std::uint32_t v = 5; v < mesh.num_vertices(); ++v) insert_vertex(mesh, v, kNone, cavity);
  return mesh;
}

bool holds(const std::vector<std::uint32_t>& tets, std::uint32_t t) {
  return std::find(tets.begin(), tets.end(), t) != tets.end();
}

TEST(ConstrainedCavity, NeverCrossesABlockedFace) {
  // Several points, each with an unconstrained cavity that crosses a face of the tet
  // holding it: that face is blocked and must survive the constrained insertion.
  std::size_t tested = 0;
  for (unsigned seed = 1; seed <= 20; ++seed) {
    TetMesh mesh = delaunay_of(random_points(200, seed));
    const Vec3 p = random_points(1, 1000 + seed).front() * 0.5 + Vec3(0.25, 0.25, 0.25);
    Cavity free_cavity;
    const Location loc = compute_cavity(mesh, p.data(), mesh.num_vertices(), kNone, free_cavity);
    ASSERT_NE(loc.kind, LocationKind::OnVertex);
    // A finite face of the holding tet whose far tet the free cavity deletes.
    int blocked_face = -1;
    for (int f = 0; f < 4 && blocked_face < 0; ++f) {
      const std::uint32_t n = mesh.neighbor(loc.tet, f);
      if (!mesh.is_infinite(n) && holds(free_cavity.tets, n)) blocked_face = f;
    }
    if (blocked_face < 0) continue;
    const auto face = mesh.face_vertices({loc.tet, static_cast<std::uint8_t>(blocked_face)});
    auto key = [](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
      std::uint32_t k[3] = {a, b, c};
      std::sort(k, k + 3);
      return std::vector<std::uint32_t>(k, k + 3);
    };
    const std::vector<std::uint32_t> blocked_key = key(face[0], face[1], face[2]);
    const CavityBlocker blocked = [&](std::uint32_t t, int f) {
      const auto v = mesh.face_vertices({t, static_cast<std::uint8_t>(f)});
      return key(v[0], v[1], v[2]) == blocked_key;
    };
    Cavity cavity;
    compute_constrained_cavity(mesh, p.data(), mesh.num_vertices(), loc.tet, blocked, cavity);
    // Every tet of the constrained cavity is in the free one; the far tet is not in it
    // unless reached around the face.
    for (const std::uint32_t t : cavity.tets) EXPECT_TRUE(holds(free_cavity.tets, t));
    bool shrunk = false;
    ASSERT_TRUE(shrink_cavity_to_star(mesh, p.data(), cavity.location.tet, cavity, shrunk));
    EXPECT_LT(cavity.tets.size(), free_cavity.tets.size());
    ASSERT_TRUE(cavity_is_star_shaped(mesh, p.data(), cavity));
    const std::uint32_t v = mesh.add_vertex(p);
    commit_cavity(mesh, v, cavity);
    const auto topo = check_topology(mesh);
    ASSERT_TRUE(topo.empty()) << describe(topo);
    EXPECT_TRUE(mesh.find_face(face[0], face[1], face[2]).has_value()) << "seed " << seed;
    ++tested;
  }
  EXPECT_GE(tested, 10u);
}

TEST(ConstrainedCavity, WithoutBlocksEqualsTheFreeCavity) {
  TetMesh mesh = delaunay_of(random_points(300, 3));
  const Vec3 p(0.41, 0.53, 0.47);
  Cavity free_cavity, cavity;
  compute_cavity(mesh, p.data(), mesh.num_vertices(), kNone, free_cavity);
  const CavityBlocker none = [](std::uint32_t, int) { return false; };
  compute_constrained_cavity(mesh, p.data(), mesh.num_vertices(), kNone, none, cavity);
  std::vector<std::uint32_t> a = free_cavity.tets, b = cavity.tets;
  std::sort(a.begin(), a.end());
  std::sort(b.begin(), b.end());
  EXPECT_EQ(a, b);
  bool shrunk = false;
  EXPECT_TRUE(shrink_cavity_to_star(mesh, p.data(), cavity.location.tet, cavity, shrunk));
  EXPECT_FALSE(shrunk);  // a Delaunay cavity is a star of its point already
}

}  // namespace
}  // namespace delmesh
