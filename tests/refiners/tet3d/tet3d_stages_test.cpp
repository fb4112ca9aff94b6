// The refinement stages on their internal state: after segment and facet recovery every
// subsegment is an edge and every subfacet a face of a valid tetrahedralization; domain
// marking; determinism and volume bounds of mesh_plc.
#include "refiners/tet3d/boundary_recovery.h"
#include "refiners/tet3d/domain_marking.h"
#include "refiners/tet3d/plc_preparation.h"
#include "refiners/tet3d/quality_refinement.h"
#include "test_plcs.h"
#include "toolkit/tetmesh/tet_check.h"

namespace delmesh::test {
namespace {

using namespace delmesh::tet3d;

void expect_conforming(RefineState& state, const std::string& name) {
  EXPECT_TRUE(check_topology(state.mesh).empty()) << name;
  EXPECT_TRUE(check_delaunay(state.mesh, 20, true).empty()) << name;
  for (const auto& [key, seg] : state.subsegments) {
    const auto a = static_cast<std::uint32_t>(key >> 32), b = static_cast<std::uint32_t>(key);
    EXPECT_TRUE(state.mesh.find_edge(a, b).has_value()) << name << ": subsegment missing";
  }
  for (const auto& [key, facet] : state.subfaces)
    EXPECT_TRUE(state.mesh.find_face(key[0], key[1], key[2]).has_value()) << name << ": subfacet missing";
  for (std::size_t f = 0; f < state.facets.size(); ++f) EXPECT_TRUE(state.facets[f].check().empty()) << name;
}

TEST(Tet3dStages, RecoveryGivesAConformingDelaunayTetrahedralization) {
  for (const TestPlc& input : all_test_plcs()) {
    MeshOptions options;
    RefineState state(input.plc, options);
    ASSERT_TRUE(prepare_plc(state).has_value()) << input.name;
    ASSERT_TRUE(restore_conformity(state, true).has_value()) << input.name;
    for (const auto& [key, seg] : state.subsegments) {
      const auto a = static_cast<std::uint32_t>(key >> 32), b = static_cast<std::uint32_t>(key);
      EXPECT_TRUE(state.mesh.find_edge(a, b).has_value()) << input.name << ": segment stage left a subsegment missing";
    }
    for (const auto& [key, facet] : state.subfaces) state.subface_queue.push_back({key});
    ASSERT_TRUE(restore_conformity(state, false).has_value()) << input.name;
    expect_conforming(state, input.name);
    mark_domain(state);
    double volume = 0.0;
    for (std::uint32_t t = 0; t < state.mesh.tet_slots(); ++t) {
      if (state.mesh.is_dead(t) || state.mesh.is_infinite(t) || !in_domain(state.tet_region[t])) continue;
      const auto& v = state.mesh.tet(t).v;
      volume += signed_volume(state.mesh.point(v[0]), state.mesh.point(v[1]), state.mesh.point(v[2]),
                              state.mesh.point(v[3]));
    }
    EXPECT_NEAR(volume, input.volume, 1e-9 * input.volume) << input.name;
    // Quality refinement keeps the boundary conforming and every tet's region exact: the
    // marks it maintained are those a domain marking from scratch gives.
    auto refined = refine_quality(state, input.plc.points.size());
    ASSERT_TRUE(refined.has_value()) << input.name;
    expect_conforming(state, input.name);
    const std::vector<int> maintained(state.tet_region.begin(), state.tet_region.end());
    mark_domain(state);
    std::size_t differ = 0, live = 0;
    for (std::uint32_t t = 0; t < state.mesh.tet_slots(); ++t) {
      if (state.mesh.is_dead(t) || state.mesh.is_infinite(t)) continue;
      ++live;
      differ += maintained[t] != state.tet_region[t];
    }
    EXPECT_EQ(differ, 0u) << input.name << ": " << differ << " of " << live << " tets carried a wrong region";
  }
}

TEST(Tet3dStages, BoxWithHoleMarksHoleAndExterior) {
  const TestPlc input = box_with_hole();
  MeshOptions options;
  auto r = mesh_plc(input.plc, options);
  ASSERT_TRUE(r.has_value());
  expect_valid_mesh(input, *r);
  // Both the outer and the hole boundary are output (12 facets' worth of markers).
  std::set<int> markers(r->mesh.boundary_markers.begin(), r->mesh.boundary_markers.end());
  EXPECT_EQ(markers.size(), 12u);
  // Outer faces point outward: a face with marker 1 (x = 0) has a normal with x < 0.
  for (std::size_t i = 0; i < r->mesh.boundary_faces.size(); ++i) {
    if (r->mesh.boundary_markers[i] != 1) continue;
    const auto& f = r->mesh.boundary_faces[i];
    const Vec3 n = (r->mesh.points[f[1]] - r->mesh.points[f[0]]).cross(r->mesh.points[f[2]] - r->mesh.points[f[0]]);
    EXPECT_LT(n.x(), 0.0);
  }
}

TEST(Tet3dMeshPlc, DeterministicOutput) {
  const TestPlc input = box_with_hole();
  MeshOptions options;
  options.max_radius_edge = 1.2;
  auto a = mesh_plc(input.plc, options);
  auto b = mesh_plc(input.plc, options);
  ASSERT_TRUE(a.has_value() && b.has_value());
  EXPECT_EQ(a->mesh.points, b->mesh.points);
  EXPECT_EQ(a->mesh.tets, b->mesh.tets);
  EXPECT_EQ(a->mesh.boundary_faces, b->mesh.boundary_faces);
}

TEST(Tet3dMeshPlc, VolumeBoundsGlobalRegionalAndSizing) {
  TestPlc input = two_boxes();
  input.plc.regions[1].max_volume = 0.002;
  MeshOptions options;
  options.max_volume = 0.01;
  auto r = mesh_plc(input.plc, options);
  ASSERT_TRUE(r.has_value());
  expect_valid_mesh(input, *r);
  EXPECT_EQ(r->status, MeshStatus::Complete);
  for (std::size_t t = 0; t < r->mesh.tets.size(); ++t) {
    const double bound = r->mesh.region_of(t) == 2 ? 0.002 : 0.01;
    EXPECT_LE(tet_volume(r->mesh, t), bound) << "tet " << t;
  }
  MeshOptions sizing;
  sizing.max_volume_at = [](const Vec3& p) { return p.x() < 1.0 ? 0.001 : -1.0; };
  auto s = mesh_plc(input.plc, sizing);
  ASSERT_TRUE(s.has_value());
  expect_valid_mesh(input, *s);
  std::size_t left = 0, right = 0;
  for (std::size_t t = 0; t < s->mesh.tets.size(); ++t) (s->mesh.region_of(t) == 1 ? left : right)++;
  EXPECT_GT(left, right);
}

TEST(Tet3dMeshPlc, SmallAnglesTerminatePartialWithCounts) {
  const TestPlc input = sharp_wedge();
  MeshOptions options;
  options.max_radius_edge = 1.1;
  auto r = mesh_plc(input.plc, options);
  ASSERT_TRUE(r.has_value());
  expect_valid_mesh(input, *r);
  EXPECT_EQ(r->status, MeshStatus::Partial);
  EXPECT_GT(r->stats.unmet_tets, 0u);
  EXPECT_GT(r->stats.unmet_tets_at_small_angles, 0u);
  EXPECT_LE(r->stats.unmet_tets_at_small_angles, r->stats.unmet_tets);
}

TEST(Tet3dMeshPlc, SteinerBudgetGivesPartialValidMesh) {
  const TestPlc input = box_with_hole();
  MeshOptions options;
  options.max_radius_edge = 1.05;
  options.max_steiner_points = 40;
  auto r = mesh_plc(input.plc, options);
  ASSERT_TRUE(r.has_value());
  expect_valid_mesh(input, *r);
  EXPECT_TRUE(r->stats.budget_exhausted);
  EXPECT_EQ(r->status, MeshStatus::Partial);
}

TEST(Tet3dMeshPlc, BadInputIsAnError) {
  Plc plc = unit_cube().plc;
  plc.facets[0].polygons[0][2] = 99;
  auto r = mesh_plc(plc, MeshOptions{});
  ASSERT_FALSE(r.has_value());
  EXPECT_NE(r.error().message.find("facet 0"), std::string::npos);
  Plc dup = unit_cube().plc;
  dup.points.push_back(dup.points[3]);
  dup.facets[0].polygons.push_back({8});
  auto d = mesh_plc(dup, MeshOptions{});
  ASSERT_FALSE(d.has_value());
  EXPECT_EQ(d.error().code, ErrorCode::DuplicateVertex);
}

}  // namespace
}  // namespace delmesh::test
