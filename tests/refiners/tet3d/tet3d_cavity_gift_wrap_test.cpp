// Constrained gift-wrapping of a cavity (refiners/tet3d/cavity_gift_wrap.h): it fills
// cavities whose faces the Delaunay tetrahedralization of their vertices lacks, the fill
// covers the cavity exactly once (positive tets, every face glued once on each side,
// volume), it is deterministic, and it refuses Schönhardt's polyhedron, which has no
// tetrahedralization without Steiner points.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>

#include "refiners/tet3d/cavity_gift_wrap.h"
#include "toolkit/predicates/predicates.h"
#include "toolkit/tetmesh/delaunay.h"

namespace delmesh::test {
namespace {

using Face = std::array<std::uint32_t, 3>;
using Tet = std::array<std::uint32_t, 4>;

struct Cavity {
  std::vector<Vec3> points;  ///< vertex i + 1 of the mesh
  std::vector<Face> faces;   ///< 1-based ids, oriented below
};

/// Orients every face with the point `inside` on its positive side (the cavities here
/// are star-shaped from it).
void orient_towards(Cavity& c, const Vec3& inside) {
  for (Face& f : c.faces) {
    const Sign s = predicates::orient3d(c.points[f[0] - 1].data(), c.points[f[1] - 1].data(),
                                        c.points[f[2] - 1].data(), inside.data());
    ASSERT_NE(s, Sign::Zero);
    if (s == Sign::Negative) std::swap(f[1], f[2]);
  }
}

double signed_volume(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  return (b - a).dot((c - a).cross(d - a)) / 6.0;
}

/// The volume the faces enclose (divergence theorem; faces oriented inwards).
double enclosed_volume(const Cavity& c) {
  double v = 0.0;
  const Vec3 o(0, 0, 0);
  for (const Face& f : c.faces) v -= signed_volume(o, c.points[f[0] - 1], c.points[f[1] - 1], c.points[f[2] - 1]);
  return v;
}

/// Every tet positive, every cavity face covered by exactly one tet on its positive side,
/// every other face by two tets of opposite orientations, volumes summing to the
/// cavity's.
void expect_exact_cover(const TetMesh& mesh, const Cavity& c, const std::vector<Tet>& tets) {
  std::map<std::array<std::uint32_t, 3>, std::vector<Face>> uses;
  double volume = 0.0;
  for (const Tet& t : tets) {
    EXPECT_EQ(predicates::orient3d(mesh.coords(t[0]), mesh.coords(t[1]), mesh.coords(t[2]), mesh.coords(t[3])),
              Sign::Positive);
    volume += signed_volume(mesh.point(t[0]), mesh.point(t[1]), mesh.point(t[2]), mesh.point(t[3]));
    for (const auto& fv : kFaceVertex) {
      const Face f = {t[fv[0]], t[fv[1]], t[fv[2]]};
      Face k = f;
      std::sort(k.begin(), k.end());
      uses[k].push_back(f);
    }
  }
  std::map<std::array<std::uint32_t, 3>, Face> walls;
  for (const Face& f : c.faces) {
    Face k = f;
    std::sort(k.begin(), k.end());
    walls.emplace(k, f);
  }
  auto cyclic_equal = [](const Face& f, const Face& g) {
    for (int r = 0; r < 3; ++r)
      if (f[0] == g[r] && f[1] == g[(r + 1) % 3] && f[2] == g[(r + 2) % 3]) return true;
    return false;
  };
  for (const auto& [k, list] : uses) {
    const auto w = walls.find(k);
    if (w != walls.end()) {
      ASSERT_EQ(list.size(), 1u);
      EXPECT_TRUE(cyclic_equal(list[0], w->second)) << "a wall covered from outside";
    } else {
      ASSERT_EQ(list.size(), 2u);
      EXPECT_FALSE(cyclic_equal(list[0], list[1])) << "two tets on one side of a face";
    }
  }
  for (const auto& [k, f] : walls) EXPECT_TRUE(uses.count(k)) << "a wall left open";
  EXPECT_NEAR(volume, enclosed_volume(c), 1e-12 * std::abs(enclosed_volume(c)));
}

/// A pyramid over a rhombus whose base is cut by its long diagonal, which is not
/// Delaunay: the short diagonal's end is inside the circle of each base triangle.
Cavity rhombus_pyramid() {
  Cavity c;
  c.points = {Vec3(-2, 0, 0), Vec3(0, -1, 0), Vec3(2, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
  c.faces = {{1, 2, 3}, {1, 3, 4}, {1, 2, 5}, {2, 3, 5}, {3, 4, 5}, {4, 1, 5}};
  orient_towards(c, Vec3(0, 0, 0.3));
  return c;
}

/// A triangular prism whose side on the hypotenuse is dented inwards by a vertex at its
/// middle pushed towards the right-angle edge: a non-convex cavity.
Cavity dented_prism() {
  Cavity c;
  c.points = {Vec3(0, 0, 0), Vec3(4, 0, 0), Vec3(0, 4, 0), Vec3(0, 0, 2),
              Vec3(4, 0, 2), Vec3(0, 4, 2), Vec3(1.5, 1.5, 1)};
  c.faces = {{1, 2, 3}, {4, 5, 6},             // bottom, top
             {1, 2, 5}, {1, 5, 4},             // side y = 0
             {1, 3, 6}, {1, 6, 4},             // side x = 0
             {2, 3, 7}, {3, 6, 7}, {6, 5, 7}, {5, 2, 7}};  // the dented side
  orient_towards(c, Vec3(0.3, 0.3, 1.0));
  return c;
}

/// Schönhardt's polyhedron: a triangular prism with its top turned by 30 degrees, each
/// side quad cut by the diagonal that makes its edge reflex.
Cavity schonhardt() {
  Cavity c;
  const double tw = 30.0 * std::numbers::pi / 180.0;
  for (int i = 0; i < 3; ++i) {
    const double a = 2.0 * std::numbers::pi * i / 3.0;
    c.points.emplace_back(std::cos(a), std::sin(a), 0.0);
  }
  for (int i = 0; i < 3; ++i) {
    const double a = 2.0 * std::numbers::pi * i / 3.0 + tw;
    c.points.emplace_back(std::cos(a), std::sin(a), 1.5);
  }
  c.faces = {{1, 3, 2}, {4, 5, 6}};
  for (std::uint32_t i = 0; i < 3; ++i) {
    const std::uint32_t j = (i + 1) % 3;
    c.faces.push_back({1 + i, 1 + j, 4 + j});
    c.faces.push_back({1 + i, 4 + j, 4 + i});
  }
  orient_towards(c, Vec3(0, 0, 0.75));
  return c;
}

TEST(Tet3dCavityGiftWrap, FillsACavityWhoseFaceTheDelaunayTetrahedralizationLacks) {
  const Cavity c = rhombus_pyramid();
  // The Delaunay tetrahedralization of the five vertices uses the short diagonal, so the
  // base triangles are not among its faces (what makes the Delaunay fill of
  // ccdt_facet_recovery fail).
  auto dt = delaunay_tetrahedralize(std::span<const Vec3>(c.points));
  ASSERT_TRUE(dt.has_value());
  EXPECT_FALSE(dt->mesh.find_face(1, 2, 3).has_value());
  EXPECT_TRUE(dt->mesh.find_edge(2, 4).has_value());
  const TetMesh mesh(c.points);
  std::vector<Tet> tets;
  ASSERT_TRUE(tet3d::gift_wrap_cavity(mesh, c.faces, 64, tets));
  EXPECT_EQ(tets.size(), 2u);
  expect_exact_cover(mesh, c, tets);
}

TEST(Tet3dCavityGiftWrap, FillsANonConvexCavityExactlyOnceAndDeterministically) {
  const Cavity c = dented_prism();
  const TetMesh mesh(c.points);
  std::vector<Tet> tets;
  ASSERT_TRUE(tet3d::gift_wrap_cavity(mesh, c.faces, 64, tets));
  expect_exact_cover(mesh, c, tets);
  std::vector<Tet> again;
  ASSERT_TRUE(tet3d::gift_wrap_cavity(mesh, c.faces, 64, again));
  EXPECT_EQ(again, tets);
}

TEST(Tet3dCavityGiftWrap, RefusesSchonhardtsPolyhedronAndTheTetBound) {
  const Cavity s = schonhardt();
  const TetMesh mesh(s.points);
  std::vector<Tet> tets = {{1, 2, 3, 4}};
  EXPECT_FALSE(tet3d::gift_wrap_cavity(mesh, s.faces, 64, tets));
  EXPECT_EQ(tets.size(), 1u) << "output changed on failure";
  const Cavity c = rhombus_pyramid();
  const TetMesh pyramid(c.points);
  std::vector<Tet> none;
  EXPECT_FALSE(tet3d::gift_wrap_cavity(pyramid, c.faces, 1, none));
  EXPECT_TRUE(none.empty());
}

}  // namespace
}  // namespace delmesh::test
