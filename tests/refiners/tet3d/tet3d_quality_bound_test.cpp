// The termination rule of quality refinement (refiners/tet3d/quality_refinement.h): the
// floor field of termination_floor.h and the automatic bound of quality_bound.h, the last
// resort that ends the quality stage on any input.
#include <algorithm>
#include <cmath>
#include <limits>

#include "refiners/tet3d/boundary_recovery.h"
#include "refiners/tet3d/domain_marking.h"
#include "refiners/tet3d/plc_preparation.h"
#include "refiners/tet3d/quality_bound.h"
#include "refiners/tet3d/quality_refinement.h"
#include "test_plcs.h"
#include "toolkit/check/check_mesh.h"
#include "toolkit/tetmesh/tet_check.h"

namespace delmesh::test {
namespace {

using namespace delmesh::tet3d;

/// Runs the stages before quality refinement on `state` (as mesh_plc does).
void recover_and_mark(RefineState& state) {
  ASSERT_TRUE(prepare_plc(state).has_value());
  ASSERT_TRUE(restore_conformity(state, true).has_value());
  for (const auto& [key, facet] : state.subfaces) state.subface_queue.push_back({key});
  ASSERT_TRUE(restore_conformity(state, false).has_value());
  mark_domain(state);
}

/// A sizing field that asks for ever smaller tets toward a point c inside the unit cube:
/// volume |p - c|^6 at circumcenter p. Near c a tet of edge h meets it only where
/// h^3 < |p - c|^6, so the points needed in the shell at distance d grow like d^-3 and
/// refinement toward c never ends on its own (a too-big tet needs no floor): without the
/// automatic bound the quality stage runs until the vertex cap of 30 million vertices.
double shrinking_sizing(const Vec3& p) { return std::pow((p - Vec3(0.37, 0.41, 0.46)).squaredNorm(), 3.0); }

TEST(Tet3dQualityBound, StopsRefinementThatWouldNotEnd) {
  const TestPlc input = unit_cube();
  MeshOptions options;
  options.max_volume_at = shrinking_sizing;
  RefineState state(input.plc, options);
  recover_and_mark(state);
  const std::size_t bound = quality_steiner_bound(state);
  // The bound of the documented rule: 8 (V + D) + 20000 for the recovered cube.
  const double vertices = static_cast<double>(state.mesh.num_vertices() - 1);
  EXPECT_EQ(bound, static_cast<std::size_t>(kBoundPerVertex * (vertices + volume_bound_demand(state)) + kBoundBase));
  EXPECT_GT(volume_bound_demand(state), 0.0);
  const std::size_t before = state.stage_steiner;
  auto outcome = refine_quality(state, input.plc.points.size());
  ASSERT_TRUE(outcome.has_value());
  EXPECT_TRUE(outcome->bound_reached);
  EXPECT_TRUE(outcome->budget_exhausted);
  const std::size_t inserted = state.stage_steiner - before;
  EXPECT_GE(inserted, bound);
  // The last insertion's conformity repairs may overshoot by a few points only.
  EXPECT_LE(inserted, bound + 64);
  EXPECT_TRUE(check_topology(state.mesh).empty());
}

TEST(Tet3dQualityBound, MeshPlcEndsPartialAndValidAtTheBound) {
  const TestPlc input = unit_cube();
  MeshOptions options;
  options.max_volume_at = shrinking_sizing;
  options.improve = false;  // refinement alone: a constrained Delaunay mesh
  auto r = mesh_plc(input.plc, options);
  ASSERT_TRUE(r.has_value());
  expect_valid_mesh(input, *r);
  EXPECT_TRUE(check_mesh(r->mesh, input.plc, r->boundary_face_facets).empty());
  EXPECT_EQ(r->status, MeshStatus::Partial);
  EXPECT_TRUE(r->stats.quality_bound_reached);
  EXPECT_TRUE(r->stats.budget_exhausted);
  // The tets still above the sizing field are counted.
  EXPECT_GT(r->stats.unmet_tets, 0u);
  ASSERT_GE(r->stats.stages.size(), 5u);
  EXPECT_EQ(r->stats.stages[4].name, "quality");
  EXPECT_GE(r->stats.stages[4].steiner_points, static_cast<std::size_t>(kBoundBase));
}

TEST(Tet3dQualityBound, NotReachedWhereRefinementEnds) {
  // A finite sizing field: the demand term lets the stage place its points.
  MeshOptions sized;
  sized.max_volume_at = [](const Vec3& p) { return p.x() < 0.5 ? 1e-4 : 1e-3; };
  auto r = mesh_plc(unit_cube().plc, sized);
  ASSERT_TRUE(r.has_value());
  EXPECT_FALSE(r->stats.quality_bound_reached);
  EXPECT_FALSE(r->stats.budget_exhausted);
  EXPECT_GT(r->mesh.tets.size(), 5000u);
  for (const TestPlc& input : all_test_plcs()) {
    MeshOptions options;
    options.max_radius_edge = 1.1;
    auto q = mesh_plc(input.plc, options);
    ASSERT_TRUE(q.has_value()) << input.name;
    EXPECT_FALSE(q->stats.quality_bound_reached) << input.name;
    EXPECT_FALSE(q->stats.budget_exhausted) << input.name;
  }
}

TEST(Tet3dQualityBound, VolumeDemandSumsVolumeOverBound) {
  const TestPlc input = two_boxes();
  MeshOptions options;
  options.max_volume = 0.01;
  RefineState state(input.plc, options);
  recover_and_mark(state);
  // Uniform bound: the demand is the domain volume over the bound.
  EXPECT_NEAR(volume_bound_demand(state), 2.0 / 0.01, 1e-9);
  MeshOptions none;
  RefineState plain(input.plc, none);
  recover_and_mark(plain);
  EXPECT_EQ(volume_bound_demand(plain), 0.0);
}

// The quality stage's floors form a field that grows away from small input features
// (termination_floor.h): between the smallest and the largest input floor, and more
// than a quarter of the Steiner vertices of the sharp wedge, which lie away from its
// sharp end, carry a floor above the smallest (by more than 10%: the field grows by
// kFloorSlope = 1/128 per unit of distance; with the smallest floor of the element alone
// every vertex descended from the sharp end would carry it). The recovery floors are those of
// the element.
TEST(Tet3dQualityBound, FloorsGrowAwayFromSmallFeatures) {
  const TestPlc input = sharp_wedge();
  MeshOptions options;
  options.max_radius_edge = 1.1;
  RefineState state(input.plc, options);
  recover_and_mark(state);
  ASSERT_TRUE(refine_quality(state, input.plc.points.size()).has_value());
  const std::uint32_t inputs = static_cast<std::uint32_t>(input.plc.points.size());
  double smallest = std::numeric_limits<double>::infinity(), largest = 0.0;
  for (std::uint32_t u = 1; u <= inputs; ++u) {
    // The quality stage's input floors come from the local feature size, at most the
    // nearest vertex distance that sets the recovery floors (feature_size.h).
    EXPECT_LE(state.vertices[u].field_floor, state.vertices[u].floor);
    smallest = std::min(smallest, state.vertices[u].field_floor);
    largest = std::max(largest, state.vertices[u].field_floor);
  }
  ASSERT_GT(smallest, 0.0);
  ASSERT_GT(largest, 4.0 * smallest);
  std::size_t steiner = 0, above_smallest = 0;
  for (std::uint32_t v = inputs + 1; v < state.mesh.num_vertices(); ++v) {
    const double floor = state.vertices[v].field_floor;
    EXPECT_GE(floor, smallest) << "vertex " << v;
    EXPECT_LE(floor, largest) << "vertex " << v;
    ++steiner;
    if (floor > 1.1 * smallest) ++above_smallest;
  }
  EXPECT_GT(steiner, 100u);
  EXPECT_GT(above_smallest, steiner / 4);
}

}  // namespace
}  // namespace delmesh::test
