// Constrained Bowyer–Watson cavities (toolkit/tetmesh/tet_insert.h,
// compute_constrained_cavity and shrink_cavity_to_star; notes §2.1.7): the search never
// crosses a blocked face, so a face between the tet holding the point and a conflict
// tet beyond survives the insertion, and the committed mesh is valid.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
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

TEST(ConstrainedCavity, BlockedFacesBetweenCavityTetsBoundIt) {
  // A blocker that answers alike from both sides of a face (by its sorted vertices) and
  // blocks about a third of them, so that some blocked faces lie between two cavity tets,
  // reached around them. The cavity must be the conflict tets reachable from the tet
  // holding p through unblocked faces, and its boundary every face of a cavity tet that
  // is blocked or leads out of the cavity, each once: the search may skip asking about
  // the face it entered a tet through, and no other.
  std::size_t blocked_inside = 0;
  for (unsigned seed = 1; seed <= 12; ++seed) {
    TetMesh mesh = delaunay_of(random_points(250, 40 + seed));
    const auto blocked_face = [&](std::uint32_t t, int f) {
      std::array<std::uint32_t, 3> v{};
      for (int k = 0; k < 3; ++k) v[static_cast<std::size_t>(k)] = mesh.tet(t).v[kFaceVertex[f][k]];
      std::sort(v.begin(), v.end());
      return (v[0] * 73856093u ^ v[1] * 19349663u ^ v[2] * 83492791u) % 3u == 0;
    };
    const CavityBlocker blocked = blocked_face;
    for (unsigned q = 0; q < 6; ++q) {
      const Vec3 p = random_points(1, 500 + 10 * seed + q).front() * 0.5 + Vec3(0.25, 0.25, 0.25);
      Cavity cavity;
      const Location loc = compute_constrained_cavity(mesh, p.data(), mesh.num_vertices(), kNone, blocked, cavity);
      ASSERT_NE(loc.kind, LocationKind::OnVertex);
      // The expected cavity, by a breadth-first search of its own.
      std::vector<std::uint32_t> expected{loc.tet};
      for (std::size_t i = 0; i < expected.size(); ++i) {
        const std::uint32_t t = expected[i];
        for (int f = 0; f < 4; ++f) {
          const std::uint32_t n = mesh.neighbor(t, f);
          if (holds(expected, n) || blocked_face(t, f)) continue;
          if (tet_in_conflict(mesh, n, p.data(), mesh.num_vertices())) expected.push_back(n);
        }
      }
      std::vector<std::uint32_t> got = cavity.tets;
      std::sort(expected.begin(), expected.end());
      std::sort(got.begin(), got.end());
      ASSERT_EQ(got, expected) << "seed " << seed << " point " << q;
      std::vector<std::uint32_t> expected_boundary, got_boundary;
      for (const std::uint32_t t : expected)
        for (int f = 0; f < 4; ++f) {
          const bool inside = holds(expected, mesh.neighbor(t, f));
          if (inside && blocked_face(t, f)) ++blocked_inside;
          if (!inside || blocked_face(t, f)) expected_boundary.push_back(mesh.tet(t).adj[f]);
        }
      for (const CavityFace& face : cavity.boundary) got_boundary.push_back(face.outside);
      std::sort(expected_boundary.begin(), expected_boundary.end());
      std::sort(got_boundary.begin(), got_boundary.end());
      EXPECT_EQ(got_boundary, expected_boundary) << "seed " << seed << " point " << q;
    }
  }
  EXPECT_GT(blocked_inside, 0u);  // the case the skipped question must not miss arose
}

}  // namespace
}  // namespace delmesh
