// check_mesh on hand-built meshes: the six Kuhn tetrahedra of the unit cube (valid), the
// cube with a split edge (valid, a segment made of two edges), a triangular bipyramid as
// two tets (not Delaunay) and as three tets around its axis (valid); then corrupted
// variants, each of which must be reported with the right kind and entity ids.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <map>
#include <string>
#include <vector>

#include "toolkit/check/check_mesh.h"
#include "toolkit/predicates/predicates.h"

namespace delmesh {
namespace {

struct Case {
  Plc plc;
  TetraMesh mesh;
  std::vector<std::uint32_t> facets;  ///< facet of each boundary face
};

/// Orients every tet positively and lists the faces of exactly one tet, outward, each
/// with the PLC facet whose plane holds it (exact orient3d) and that facet's marker.
void finish(Case& c) {
  auto& m = c.mesh;
  for (auto& t : m.tets) {
    if (predicates::orient3d(m.points[t[0]].data(), m.points[t[1]].data(), m.points[t[2]].data(),
                             m.points[t[3]].data()) == Sign::Negative) {
      std::swap(t[1], t[2]);
    }
  }
  std::map<FaceKey, std::pair<std::array<std::uint32_t, 3>, int>> count;
  for (const auto& t : m.tets) {
    const std::array<std::array<std::uint32_t, 3>, 4> outward{
        {{t[1], t[2], t[3]}, {t[0], t[3], t[2]}, {t[0], t[1], t[3]}, {t[0], t[2], t[1]}}};
    for (const auto& f : outward) {
      auto& entry = count[face_key(f[0], f[1], f[2])];
      entry.first = f;
      ++entry.second;
    }
  }
  m.boundary_faces.clear();
  m.boundary_markers.clear();
  c.facets.clear();
  for (const auto& [key, entry] : count) {
    if (entry.second != 1) continue;
    const auto& f = entry.first;
    std::uint32_t facet = 0;
    for (; facet < c.plc.facets.size(); ++facet) {
      const auto& poly = c.plc.facets[facet].polygons[0];
      const auto& p = c.plc.points;
      const bool in_plane = std::all_of(f.begin(), f.end(), [&](std::uint32_t v) {
        return predicates::orient3d(p[poly[0]].data(), p[poly[1]].data(), p[poly[2]].data(), m.points[v].data()) ==
               Sign::Zero;
      });
      if (in_plane) break;
    }
    ASSERT_LT(facet, c.plc.facets.size());
    m.boundary_faces.push_back(f);
    m.boundary_markers.push_back(c.plc.facets[facet].marker);
    c.facets.push_back(facet);
  }
}

/// Unit cube, vertices by bits (x = bit 0, y = bit 1, z = bit 2); facets x=0, x=1, y=0,
/// y=1, z=0, z=1 with markers 1..6; six tets around the diagonal 0-7.
Case kuhn_cube() {
  Case c;
  for (int i = 0; i < 8; ++i) c.plc.points.emplace_back(i & 1, (i >> 1) & 1, (i >> 2) & 1);
  const std::vector<Plc::Polygon> sides{{0, 2, 6, 4}, {1, 3, 7, 5}, {0, 1, 5, 4},
                                        {2, 3, 7, 6}, {0, 1, 3, 2}, {4, 5, 7, 6}};
  for (std::size_t s = 0; s < sides.size(); ++s) {
    Plc::Facet facet;
    facet.polygons = {sides[s]};
    facet.marker = static_cast<int>(s) + 1;
    c.plc.facets.push_back(facet);
  }
  c.mesh.points = c.plc.points;
  const int axes[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  for (const auto& a : axes) {
    const std::uint32_t v1 = 1u << a[0], v2 = v1 | (1u << a[1]);
    c.mesh.tets.push_back({0, v1, v2, 7});
  }
  c.mesh.tet_regions = {1, 1, 1, 2, 2, 2};
  finish(c);
  return c;
}

/// The cube with edge 0-1 split at its midpoint (vertex 8): each tet on the edge becomes two.
Case split_cube() {
  Case c = kuhn_cube();
  c.mesh.points.emplace_back(0.5, 0.0, 0.0);
  std::vector<std::array<std::uint32_t, 4>> tets;
  for (const auto& t : c.mesh.tets) {
    const bool has0 = std::count(t.begin(), t.end(), 0u) > 0, has1 = std::count(t.begin(), t.end(), 1u) > 0;
    if (!(has0 && has1)) {
      tets.push_back(t);
      continue;
    }
    auto a = t, b = t;
    std::replace(a.begin(), a.end(), 1u, 8u);
    std::replace(b.begin(), b.end(), 0u, 8u);
    tets.push_back(a);
    tets.push_back(b);
  }
  c.mesh.tets = tets;
  c.mesh.tet_regions.clear();
  finish(c);
  return c;
}

/// Triangle a b c in z = 0 with apexes d (z = 0.2) and e (z = -0.2); six triangular facets.
Plc bipyramid() {
  Plc plc;
  plc.points = {{1, 0, 0}, {-0.5, 0.875, 0}, {-0.5, -0.875, 0}, {0, 0, 0.2}, {0, 0, -0.2}};
  const std::vector<Plc::Polygon> faces{{0, 1, 3}, {1, 2, 3}, {2, 0, 3}, {0, 2, 4}, {2, 1, 4}, {1, 0, 4}};
  for (std::size_t f = 0; f < faces.size(); ++f) {
    Plc::Facet facet;
    facet.polygons = {faces[f]};
    facet.marker = 10 + static_cast<int>(f);
    plc.facets.push_back(facet);
  }
  return plc;
}

std::vector<MeshCheckIssue> check(const Case& c, const CheckMeshOptions& options = {}) {
  return check_mesh(c.mesh, c.plc, c.facets, options);
}

bool has(const std::vector<MeshCheckIssue>& issues, MeshCheckKind kind, const std::vector<std::uint32_t>& ids) {
  return std::any_of(issues.begin(), issues.end(),
                     [&](const MeshCheckIssue& i) { return i.kind == kind && i.ids == ids; });
}

std::string dump(const std::vector<MeshCheckIssue>& issues) {
  std::string text;
  for (const auto& i : issues) text += std::string(to_string(i.kind)) + ": " + i.message + "\n";
  return text;
}

TEST(CheckMesh, KuhnCubeIsValid) {
  const Case c = kuhn_cube();
  ASSERT_EQ(c.mesh.boundary_faces.size(), 12u);
  const auto issues = check(c);
  EXPECT_TRUE(issues.empty()) << dump(issues);
}

TEST(CheckMesh, SplitEdgeIsAChainOfTwoEdges) {
  const Case c = split_cube();
  ASSERT_EQ(c.mesh.tets.size(), 8u);  // two of the six tets hold edge 0-1
  ASSERT_EQ(c.mesh.boundary_faces.size(), 14u);
  // The midpoint lies inside the cube's circumsphere, so the split tets are not Delaunay
  // (the checker says so: two faces); everything else holds.
  const auto all = check(c);
  ASSERT_EQ(all.size(), 2u) << dump(all);
  EXPECT_EQ(all[0].kind, MeshCheckKind::NotDelaunay);
  CheckMeshOptions options;
  options.check_delaunay = false;
  const auto issues = check(c, options);
  EXPECT_TRUE(issues.empty()) << dump(issues);
}

TEST(CheckMesh, InvertedTet) {
  Case c = kuhn_cube();
  std::swap(c.mesh.tets[2][0], c.mesh.tets[2][1]);
  const auto issues = check(c);
  EXPECT_TRUE(has(issues, MeshCheckKind::InvertedTet, {2})) << dump(issues);
}

TEST(CheckMesh, FlatTet) {
  Case c = kuhn_cube();
  c.mesh.points.emplace_back(0.5, 0.5, 0.0);  // on the z = 0 side, coplanar with 0 1 3
  c.mesh.tets.push_back({0, 1, 3, 8});
  c.mesh.tet_regions.push_back(3);
  const auto issues = check(c);
  EXPECT_TRUE(has(issues, MeshCheckKind::FlatTet, {6})) << dump(issues);
}

TEST(CheckMesh, OverlappingTetsHaveFacesInTheSameOrientation) {
  Case c = kuhn_cube();
  c.mesh.tets.push_back(c.mesh.tets[4]);
  c.mesh.tet_regions.push_back(2);
  const auto issues = check(c);
  EXPECT_TRUE(has(issues, MeshCheckKind::FaceOrientation, {4, 6})) << dump(issues);
}

TEST(CheckMesh, FaceOfThreeTetsIsNonManifold) {
  Case c = kuhn_cube();
  // Tets {0 1 3 7} and {0 1 5 7} share the face (0 1 7); a third tet on it, outside the
  // cube, makes the face non-manifold (its three slots are consecutive in the face array).
  c.mesh.points.emplace_back(2.0, -1.0, 0.5);
  c.mesh.tets.push_back({0, 1, 7, 8});
  c.mesh.tet_regions.push_back(3);
  const auto issues = check(c);
  EXPECT_TRUE(has(issues, MeshCheckKind::NonManifoldFace, {0, 1, 7})) << dump(issues);
}

TEST(CheckMesh, MissingBoundaryFaceIsAnUnlistedFreeFaceAndUncoveredFacet) {
  Case c = kuhn_cube();
  const auto face = c.mesh.boundary_faces[5];
  const std::uint32_t facet = c.facets[5];
  c.mesh.boundary_faces.erase(c.mesh.boundary_faces.begin() + 5);
  c.mesh.boundary_markers.erase(c.mesh.boundary_markers.begin() + 5);
  c.facets.erase(c.facets.begin() + 5);
  const auto issues = check(c);
  const FaceKey key = face_key(face[0], face[1], face[2]);
  std::uint32_t owner = 0;
  for (; owner < c.mesh.tets.size(); ++owner) {
    const auto& t = c.mesh.tets[owner];
    if (std::all_of(key.begin(), key.end(), [&](std::uint32_t v) { return std::count(t.begin(), t.end(), v) > 0; }))
      break;
  }
  EXPECT_TRUE(has(issues, MeshCheckKind::UnlistedBoundaryFace, {owner, key[0], key[1], key[2]})) << dump(issues);
  EXPECT_TRUE(has(issues, MeshCheckKind::FacetNotCovered, {facet})) << dump(issues);
}

TEST(CheckMesh, GapLeftByARemovedTet) {
  Case c = kuhn_cube();
  c.mesh.tets.erase(c.mesh.tets.begin() + 3);
  c.mesh.tet_regions.erase(c.mesh.tet_regions.begin() + 3);
  const auto issues = check(c);
  EXPECT_TRUE(std::any_of(issues.begin(), issues.end(),
                          [](const auto& i) { return i.kind == MeshCheckKind::VolumeMismatch; }))
      << dump(issues);
  // Its two outer faces are still listed but no tet has them; its two inner faces are free.
  const auto count = [&](MeshCheckKind kind) {
    return std::count_if(issues.begin(), issues.end(), [&](const auto& i) { return i.kind == kind; });
  };
  EXPECT_EQ(count(MeshCheckKind::MissingBoundaryFace), 2) << dump(issues);
  EXPECT_EQ(count(MeshCheckKind::UnlistedBoundaryFace), 2) << dump(issues);
}

TEST(CheckMesh, WrongMarker) {
  Case c = kuhn_cube();
  c.mesh.boundary_markers[7] = 42;
  const auto issues = check(c);
  ASSERT_EQ(issues.size(), 1u) << dump(issues);
  EXPECT_TRUE(has(issues, MeshCheckKind::WrongMarker, {7, c.facets[7]})) << dump(issues);
}

TEST(CheckMesh, FaceAssignedToTheWrongFacet) {
  Case c = kuhn_cube();
  const std::uint32_t other = (c.facets[3] + 1) % 6;
  c.facets[3] = other;
  c.mesh.boundary_markers[3] = c.plc.facets[other].marker;
  const auto issues = check(c);
  EXPECT_TRUE(has(issues, MeshCheckKind::FaceOffFacet, {3, other})) << dump(issues);
  EXPECT_TRUE(has(issues, MeshCheckKind::FacetNotCovered, {other})) << dump(issues);
}

TEST(CheckMesh, FaceInThePlaneButOutsideAFacetWithAHole) {
  Case c = kuhn_cube();
  // Facet z=0 (index 4) gets a hole: the corner square [0.5,1]x[0,0.5], loop 8-1-9-10.
  for (const auto& p : {Vec3(0.5, 0.0, 0.0), Vec3(1.0, 0.5, 0.0), Vec3(0.5, 0.5, 0.0)}) c.plc.points.push_back(p);
  c.plc.facets[4].polygons.push_back({8, 1, 9, 10});
  c.plc.facets[4].holes.emplace_back(0.75, 0.25, 0.0);
  c.mesh.points = c.plc.points;
  const auto issues = check(c);
  // The facet's area is now 0.75 while its two faces still cover 1, and the face 0-1-3
  // has its centroid (2/3, 1/3, 0) in the hole.
  EXPECT_TRUE(has(issues, MeshCheckKind::FacetNotCovered, {4})) << dump(issues);
  std::uint32_t corner = 0;
  for (; corner < c.mesh.boundary_faces.size(); ++corner) {
    const auto& v = c.mesh.boundary_faces[corner];
    if (face_key(v[0], v[1], v[2]) == FaceKey{0, 1, 3}) break;
  }
  EXPECT_TRUE(has(issues, MeshCheckKind::FaceOffFacet, {corner, 4})) << dump(issues);
  EXPECT_TRUE(has(issues, MeshCheckKind::MissingSegment, {8, 10})) << dump(issues);
}

TEST(CheckMesh, SegmentNotPresent) {
  Case c = kuhn_cube();
  c.plc.segments.push_back({1, 6, 0});  // the diagonal 1-6 crosses the tets
  c.plc.segments.push_back({0, 7, 0});  // the diagonal 0-7 is an edge of every tet
  const auto issues = check(c);
  ASSERT_EQ(issues.size(), 1u) << dump(issues);
  EXPECT_TRUE(has(issues, MeshCheckKind::MissingSegment, {1, 6})) << dump(issues);
}

TEST(CheckMesh, SplitEdgeWithoutItsSecondHalfIsMissing) {
  Case c = split_cube();
  // Move the midpoint off the segment: the chain 0-8-1 no longer follows segment 0-1.
  c.mesh.points[8] = Vec3(0.5, 0.0, 1e-3);
  CheckMeshOptions options;
  options.check_volume = false;
  const auto issues = check(c, options);
  EXPECT_TRUE(has(issues, MeshCheckKind::MissingSegment, {0, 1})) << dump(issues);
}

TEST(CheckMesh, NonDelaunayInteriorFace) {
  Case two;
  two.plc = bipyramid();
  two.mesh.points = two.plc.points;
  two.mesh.tets = {{0, 1, 2, 3}, {0, 2, 1, 4}};
  finish(two);
  ASSERT_EQ(two.mesh.boundary_faces.size(), 6u);
  const auto issues = check(two);
  ASSERT_EQ(issues.size(), 1u) << dump(issues);
  EXPECT_TRUE(has(issues, MeshCheckKind::NotDelaunay, {0, 1})) << dump(issues);

  // With the middle triangle as a facet the face is constrained: no issue.
  Case constrained = two;
  Plc::Facet middle;
  middle.polygons = {{0, 1, 2}};
  middle.marker = 99;
  constrained.plc.facets.push_back(middle);
  constrained.mesh.boundary_faces.push_back({0, 1, 2});
  constrained.mesh.boundary_markers.push_back(99);
  constrained.facets.push_back(6);
  const auto constrained_issues = check(constrained);
  EXPECT_TRUE(constrained_issues.empty()) << dump(constrained_issues);

  Case three;
  three.plc = bipyramid();
  three.mesh.points = three.plc.points;
  three.mesh.tets = {{3, 4, 0, 1}, {3, 4, 1, 2}, {3, 4, 2, 0}};
  finish(three);
  const auto three_issues = check(three);
  EXPECT_TRUE(three_issues.empty()) << dump(three_issues);
}

TEST(CheckMesh, RoundedSteinerPointOnATiltedSegmentIsAcceptedWithinRoundoff) {
  // Bipyramid as three tets around its axis 3-4; edge 0-3 (a segment shared by the tilted
  // facets 0 and 2) split at p = a + (d - a) / 3, rounded to doubles as a mesher would.
  Case c;
  c.plc = bipyramid();
  c.mesh.points = c.plc.points;
  const Vec3 &a = c.plc.points[0], &d = c.plc.points[3];
  const Vec3 p = a + (d - a) / 3.0;
  ASSERT_NE(predicates::orient2d_projected(a.data(), d.data(), p.data(), Axis::Y), Sign::Zero)
      << "the rounded point happens to be exactly on the segment";
  c.mesh.points.push_back(p);  // vertex 5
  for (const std::array<std::uint32_t, 4>& t :
       std::vector<std::array<std::uint32_t, 4>>{{3, 4, 0, 1}, {3, 4, 1, 2}, {3, 4, 2, 0}}) {
    if (std::count(t.begin(), t.end(), 0u) == 0) {
      c.mesh.tets.push_back(t);
      continue;
    }
    auto lower = t, upper = t;
    std::replace(lower.begin(), lower.end(), 3u, 5u);
    std::replace(upper.begin(), upper.end(), 0u, 5u);
    c.mesh.tets.push_back(lower);
    c.mesh.tets.push_back(upper);
  }
  for (auto& t : c.mesh.tets) {
    const auto& m = c.mesh.points;
    if (predicates::orient3d(m[t[0]].data(), m[t[1]].data(), m[t[2]].data(), m[t[3]].data()) == Sign::Negative)
      std::swap(t[1], t[2]);
  }
  // Free faces, outward; the facet is the one whose polygon holds the face's input
  // vertices (and the segment 0-3 for faces at p).
  std::map<FaceKey, std::pair<std::array<std::uint32_t, 3>, int>> count;
  for (const auto& t : c.mesh.tets) {
    for (const auto& f : std::array<std::array<std::uint32_t, 3>, 4>{
             {{t[1], t[2], t[3]}, {t[0], t[3], t[2]}, {t[0], t[1], t[3]}, {t[0], t[2], t[1]}}}) {
      auto& entry = count[face_key(f[0], f[1], f[2])];
      entry.first = f;
      ++entry.second;
    }
  }
  for (const auto& [key, entry] : count) {
    if (entry.second != 1) continue;
    std::vector<std::uint32_t> needed;
    for (std::uint32_t v : key) {
      if (v == 5) {
        needed.push_back(0);
        needed.push_back(3);
      } else {
        needed.push_back(v);
      }
    }
    std::uint32_t facet = 0;
    for (; facet < c.plc.facets.size(); ++facet) {
      const auto& poly = c.plc.facets[facet].polygons[0];
      if (std::all_of(needed.begin(), needed.end(),
                      [&](std::uint32_t v) { return std::count(poly.begin(), poly.end(), v) > 0; }))
        break;
    }
    ASSERT_LT(facet, c.plc.facets.size());
    c.mesh.boundary_faces.push_back(entry.first);
    c.mesh.boundary_markers.push_back(c.plc.facets[facet].marker);
    c.facets.push_back(facet);
  }
  ASSERT_EQ(c.mesh.boundary_faces.size(), 8u);
  CheckMeshOptions options;
  options.check_delaunay = false;
  const auto issues = check(c, options);
  EXPECT_TRUE(issues.empty()) << dump(issues);

  options.roundoff_tolerance = 0.0;  // purely exact: p is off the line and off the planes
  const auto exact = check(c, options);
  EXPECT_TRUE(has(exact, MeshCheckKind::MissingSegment, {0, 3})) << dump(exact);
  EXPECT_TRUE(std::any_of(exact.begin(), exact.end(),
                          [](const auto& i) { return i.kind == MeshCheckKind::FaceOffFacet; }))
      << dump(exact);
}

TEST(CheckMesh, DuplicateAndUnknownBoundaryFaces) {
  Case c = kuhn_cube();
  c.mesh.boundary_faces.push_back(c.mesh.boundary_faces[0]);
  c.mesh.boundary_markers.push_back(c.mesh.boundary_markers[0]);
  c.facets.push_back(c.facets[0]);
  c.mesh.boundary_faces.push_back({1, 2, 4});  // not a face of the Kuhn tets
  c.mesh.boundary_markers.push_back(1);
  c.facets.push_back(0);
  const auto issues = check(c);
  EXPECT_TRUE(has(issues, MeshCheckKind::DuplicateBoundaryFace, {0, 12})) << dump(issues);
  EXPECT_TRUE(has(issues, MeshCheckKind::MissingBoundaryFace, {13})) << dump(issues);
}

TEST(CheckMesh, InwardBoundaryFace) {
  Case c = kuhn_cube();
  std::swap(c.mesh.boundary_faces[2][0], c.mesh.boundary_faces[2][1]);
  const auto issues = check(c);
  EXPECT_TRUE(has(issues, MeshCheckKind::FaceOrientation, {2})) << dump(issues);
}

TEST(CheckMesh, BadIndicesStopTheCheck) {
  Case c = kuhn_cube();
  c.mesh.tets[1][3] = 99;
  c.facets[0] = 17;
  const auto issues = check(c);
  EXPECT_TRUE(has(issues, MeshCheckKind::BadIndex, {1})) << dump(issues);
  EXPECT_TRUE(has(issues, MeshCheckKind::BadIndex, {0, 17})) << dump(issues);
}

TEST(CheckMesh, HullTetsOfRegionMinusOneNeedNoBoundaryFaces) {
  // The bipyramid's upper half is the domain (upper facets and the middle triangle); its
  // lower half is a kept hull tet of region -1 whose free faces are nobody's boundary.
  Case c;
  c.plc = bipyramid();
  c.plc.facets.resize(3);
  Plc::Facet middle;
  middle.polygons = {{0, 1, 2}};
  middle.marker = 7;
  c.plc.facets.push_back(middle);
  c.mesh.points = c.plc.points;
  c.mesh.tets = {{0, 1, 2, 3}, {0, 2, 1, 4}};
  c.mesh.tet_regions = {0, -1};
  c.mesh.boundary_faces = {{0, 1, 3}, {1, 2, 3}, {0, 3, 2}, {0, 2, 1}};  // outward from tet 0
  c.mesh.boundary_markers = {10, 11, 12, 7};
  c.facets = {0, 1, 2, 3};
  const auto issues = check(c);
  EXPECT_TRUE(issues.empty()) << dump(issues);

  // Without region -1 the hull tet's free faces must be listed.
  c.mesh.tet_regions = {0, 0};
  const auto unlisted = check(c);
  EXPECT_TRUE(has(unlisted, MeshCheckKind::UnlistedBoundaryFace, {1, 0, 1, 4})) << dump(unlisted);
}

TEST(CheckMesh, FacetOutsideTheDomainNeedsNoBoundaryFacesButOneInsideDoes) {
  // A facet of the lower half, which is a hull tet of region -1 (like a facet between a
  // hole and the exterior): no tet of the domain reaches it, so it has no boundary faces.
  Case c;
  c.plc = bipyramid();
  c.plc.facets.resize(3);
  Plc::Facet middle;
  middle.polygons = {{0, 1, 2}};
  middle.marker = 7;
  c.plc.facets.push_back(middle);
  Plc::Facet lower;
  lower.polygons = {{0, 2, 4}};
  lower.marker = 8;
  c.plc.facets.push_back(lower);
  c.mesh.points = c.plc.points;
  c.mesh.tets = {{0, 1, 2, 3}, {0, 2, 1, 4}};
  c.mesh.tet_regions = {0, -1};
  c.mesh.boundary_faces = {{0, 1, 3}, {1, 2, 3}, {0, 3, 2}, {0, 2, 1}};
  c.mesh.boundary_markers = {10, 11, 12, 7};
  c.facets = {0, 1, 2, 3};
  const auto issues = check(c);
  EXPECT_TRUE(issues.empty()) << dump(issues);
  // With the lower tet in the domain the facet is on its boundary and must be covered.
  c.mesh.tet_regions = {0, 0};
  EXPECT_TRUE(has(check(c), MeshCheckKind::FacetNotCovered, {4})) << dump(check(c));

  // A facet through the interior of the domain (the Kuhn cube's diagonal triangle 0 3 7,
  // shared by two tets) without boundary faces is reported.
  Case cube = kuhn_cube();
  Plc::Facet diagonal;
  diagonal.polygons = {{0, 3, 7}};
  diagonal.marker = 9;
  cube.plc.facets.push_back(diagonal);
  const auto inside = check(cube);
  EXPECT_TRUE(has(inside, MeshCheckKind::FacetNotCovered, {6})) << dump(inside);
}

TEST(CheckMesh, StopsAtMaxIssues) {
  Case c = kuhn_cube();
  for (auto& t : c.mesh.tets) std::swap(t[0], t[1]);
  CheckMeshOptions options;
  options.max_issues = 3;
  EXPECT_EQ(check(c, options).size(), 3u);
}

}  // namespace
}  // namespace delmesh
