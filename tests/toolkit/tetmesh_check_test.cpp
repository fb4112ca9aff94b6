// The validators must catch what they claim to: broken gluing, inverted tets, stale
// vertex_tet, non-Delaunay faces.
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "toolkit/tetmesh/delaunay.h"
#include "toolkit/tetmesh/tet_check.h"
#include "toolkit/tetmesh/tet_flips.h"

namespace delmesh {
namespace {

TetMesh random_mesh(std::size_t n, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Vec3> pts;
  for (std::size_t i = 0; i < n; ++i) pts.emplace_back(u(rng), u(rng), u(rng));
  auto r = delaunay_tetrahedralize(pts);
  EXPECT_TRUE(r.has_value());
  return std::move(r->mesh);
}

std::uint32_t first_finite(const TetMesh& mesh) {
  for (std::uint32_t t = 0; t < mesh.tet_slots(); ++t) {
    if (!mesh.is_dead(t) && mesh.is_finite(t)) return t;
  }
  return kNone;
}

TEST(TetCheck, ValidMeshHasNoIssues) {
  const TetMesh mesh = random_mesh(500, 1);
  EXPECT_TRUE(check_topology(mesh).empty());
  EXPECT_TRUE(check_delaunay(mesh).empty());
  EXPECT_TRUE(check_delaunay(mesh, 20, true).empty());
}

TEST(TetCheck, DetectsBrokenGluing) {
  TetMesh mesh = random_mesh(100, 2);
  const std::uint32_t t = first_finite(mesh);
  mesh.tet(t).adj[0] = mesh.tet(t).adj[1];
  EXPECT_FALSE(check_topology(mesh).empty());
}

TEST(TetCheck, DetectsInvertedTet) {
  TetMesh mesh = random_mesh(100, 3);
  const std::uint32_t t = first_finite(mesh);
  auto& r = mesh.tet(t);
  std::swap(r.v[0], r.v[1]);
  const auto issues = check_topology(mesh);
  ASSERT_FALSE(issues.empty());
  bool orientation = false;
  for (const auto& i : issues) orientation |= i.message.find("oriented") != std::string::npos;
  EXPECT_TRUE(orientation);
}

TEST(TetCheck, DetectsStaleVertexTet) {
  TetMesh mesh = random_mesh(100, 4);
  const std::uint32_t v = 7;
  for (std::uint32_t t = 0; t < mesh.tet_slots(); ++t) {
    if (mesh.local_index(t, v) < 0) {
      mesh.set_vertex_tet(v, t);
      break;
    }
  }
  const auto issues = check_topology(mesh);
  ASSERT_EQ(issues.size(), 1u);
  EXPECT_EQ(issues[0].vertex, v);
}

TEST(TetCheck, DetectsNonDelaunayFaceAfterAFlip) {
  TetMesh mesh = random_mesh(300, 5);
  // A 2-3 flip of a strictly Delaunay face of random points makes a non-Delaunay mesh
  // that is still a valid triangulation.
  for (std::uint32_t t = 0; t < mesh.tet_slots(); ++t) {
    if (mesh.is_dead(t) || mesh.is_infinite(t)) continue;
    for (std::uint8_t f = 0; f < 4; ++f) {
      if (!flip23(mesh, {t, f})) continue;
      EXPECT_TRUE(check_topology(mesh).empty());
      EXPECT_FALSE(check_delaunay(mesh).empty());
      return;
    }
  }
  FAIL() << "no flippable face";
}

}  // namespace
}  // namespace delmesh
