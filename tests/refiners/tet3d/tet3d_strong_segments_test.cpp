// Strongly Delaunay segment recovery (MeshOptions::segment_recovery, strong_segments.h;
// notes §2.1.4): the local test on the Delaunay tetrahedralization of a cube's corners
// (cospherical: only the cube's edges are strongly Delaunay), and a closed surface whose
// triangles are all facets, so every triangle edge is a segment: recovery that splits only
// subsegments missing or not strongly Delaunay makes fewer Steiner points than stitching
// with closed diametral spheres, and refinement on the CCDT that follows gives a valid
// mesh (check_mesh) that meets the radius-edge bound away from small input angles.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "refiners/tet3d/boundary_recovery.h"
#include "refiners/tet3d/mesh_plc.h"
#include "refiners/tet3d/plc_preparation.h"
#include "refiners/tet3d/strong_segments.h"
#include "test_plcs.h"
#include "toolkit/check/check_mesh.h"

namespace delmesh::test {
namespace {

using namespace delmesh::tet3d;

/// A closed polyhedron inscribed in the ellipsoid with semi-axes 2.5, 1, 0.6 (long
/// triangles with obtuse corners), its south pole pushed in to z = -0.2 (a dimple, where
/// the surface is not convex): two poles and four rings of eight vertices, every other
/// ring turned by half a step; each triangle is its own facet.
Plc ellipsoid_triangles() {
  constexpr int kRings = 4, kPerRing = 8;
  Plc plc;
  plc.points.emplace_back(0.0, 0.0, 0.6);
  for (int k = 1; k <= kRings; ++k) {
    const double theta = std::numbers::pi * k / (kRings + 1);
    for (int j = 0; j < kPerRing; ++j) {
      const double phi = 2.0 * std::numbers::pi * (j + 0.5 * (k % 2)) / kPerRing;
      plc.points.emplace_back(2.5 * std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
                              0.6 * std::cos(theta));
    }
  }
  plc.points.emplace_back(0.0, 0.0, -0.2);
  const std::uint32_t south = static_cast<std::uint32_t>(plc.points.size() - 1);
  auto ring = [&](int k, int j) { return static_cast<std::uint32_t>(1 + (k - 1) * kPerRing + (j % kPerRing)); };
  auto add = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    Plc::Facet f;
    f.polygons.push_back({a, b, c});
    plc.facets.push_back(f);
  };
  for (int j = 0; j < kPerRing; ++j) {
    add(0, ring(1, j), ring(1, j + 1));
    add(south, ring(kRings, j + 1), ring(kRings, j));
    for (int k = 1; k < kRings; ++k) {
      if (k % 2 == 0) {  // ring k + 1 is turned by +half a step from ring k
        add(ring(k, j), ring(k, j + 1), ring(k + 1, j));
        add(ring(k + 1, j), ring(k, j + 1), ring(k + 1, j + 1));
      } else {  // ring k + 1 is turned by -half a step
        add(ring(k, j), ring(k, j + 1), ring(k + 1, j + 1));
        add(ring(k + 1, j), ring(k, j), ring(k + 1, j + 1));
      }
    }
  }
  return plc;
}

MeshOptions options_for(SegmentRecovery recovery) {
  MeshOptions options;
  options.max_radius_edge = 1.414;
  options.segment_recovery = recovery;
  return options;
}

TEST(Tet3dStrongSegments, OnlyTheEdgesOfACubeAreStronglyDelaunayAmongItsCorners) {
  const TestPlc cube = unit_cube();
  const MeshOptions options;
  RefineState state(cube.plc, options);
  ASSERT_TRUE(prepare_plc(state).has_value());
  TetMesh& mesh = state.mesh;
  std::vector<std::uint32_t> tets, ring;
  std::size_t edges = 0, diagonals = 0;
  for (std::uint32_t a = 1; a < mesh.num_vertices(); ++a) {
    for (std::uint32_t b = a + 1; b < mesh.num_vertices(); ++b) {
      const double length = (mesh.point(a) - mesh.point(b)).norm();
      const bool strong = strongly_delaunay_edge(mesh, a, b, tets, ring);
      if (std::abs(length - 1.0) < 1e-12) {
        // A cube edge: a large sphere bulging away from the cube passes through its ends
        // alone.
        EXPECT_TRUE(strong) << a << " " << b;
        ++edges;
      } else {
        // A face or body diagonal: its ends are cocircular with two other corners, so every
        // sphere through them holds or touches another corner (and a missing edge is never
        // strongly Delaunay).
        EXPECT_FALSE(strong) << a << " " << b;
        if (mesh.tets_around_edge(a, b, tets)) ++diagonals;
      }
    }
  }
  EXPECT_EQ(edges, 12u);
  // Each square face holds one diagonal; the tetrahedralization of the corners has at
  // least five tets, so some diagonal crosses the inside too.
  EXPECT_GE(diagonals, 6u);
}

TEST(Tet3dStrongSegments, FewerSplitsThanDiametralStitchingAndEverySubsegmentStronglyDelaunay) {
  const Plc plc = ellipsoid_triangles();
  std::size_t splits[2] = {0, 0};
  for (const SegmentRecovery recovery : {SegmentRecovery::Diametral, SegmentRecovery::StronglyDelaunay}) {
    const MeshOptions options = options_for(recovery);
    RefineState state(plc, options);
    ASSERT_TRUE(prepare_plc(state).has_value());
    ASSERT_EQ(state.segments.size(), 3u * 8u * 4u);  // every triangle edge
    ASSERT_TRUE(restore_conformity(state, true).has_value());
    splits[recovery == SegmentRecovery::StronglyDelaunay] = state.stage_steiner;
    std::vector<std::uint32_t> tets, ring;
    for (const auto& [key, segment] : state.subsegments) {
      const auto a = static_cast<std::uint32_t>(key >> 32), b = static_cast<std::uint32_t>(key);
      EXPECT_TRUE(strongly_delaunay_edge(state.mesh, a, b, tets, ring)) << a << " " << b;
    }
  }
  // Measured: 186 splits with diametral spheres, 5 strongly Delaunay.
  EXPECT_LT(2 * splits[1], splits[0]) << splits[1] << " strongly Delaunay, " << splits[0] << " diametral";
}

TEST(Tet3dStrongSegments, RefinementOnTheCcdtIsValidWithFewerVertices) {
  const Plc plc = ellipsoid_triangles();
  auto diametral = mesh_plc(plc, options_for(SegmentRecovery::Diametral));
  auto strong = mesh_plc(plc, options_for(SegmentRecovery::StronglyDelaunay));
  ASSERT_TRUE(diametral.has_value()) << diametral.error().message;
  ASSERT_TRUE(strong.has_value()) << strong.error().message;
  EXPECT_TRUE(strong->stats.ccdt.used);
  // Tets left above the bound only where the dimple and the flat ellipsoid make small
  // input angles (measured: 15, all there; diametral 32, all there).
  EXPECT_EQ(strong->stats.unmet_tets, strong->stats.unmet_tets_at_small_angles);
  EXPECT_FALSE(strong->stats.strong_segments_fell_back);
  CheckMeshOptions check;
  check.check_delaunay = strong->constrained_delaunay;
  for (const MeshCheckIssue& issue : check_mesh(strong->mesh, plc, strong->boundary_face_facets, check))
    ADD_FAILURE() << issue.message;
  // Measured: 504 vertices strongly Delaunay, 830 diametral.
  EXPECT_LT(strong->mesh.points.size(), diametral->mesh.points.size())
      << strong->mesh.points.size() << " vertices strongly Delaunay, " << diametral->mesh.points.size() << " diametral";
}

TEST(Tet3dStrongSegments, ConformingFacetRecoveryIsRefused) {
  MeshOptions options = options_for(SegmentRecovery::StronglyDelaunay);
  options.facet_recovery = FacetRecovery::Conforming;
  const auto r = mesh_plc(ellipsoid_triangles(), options);
  ASSERT_FALSE(r.has_value());
  EXPECT_EQ(r.error().code, ErrorCode::InvalidOption);
}

}  // namespace
}  // namespace delmesh::test
