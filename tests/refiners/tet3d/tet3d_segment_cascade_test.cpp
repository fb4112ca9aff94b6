// The cascade of segment recovery at a small input angle (notes §3.8, §4.2.1): a fan of
// thin triangles whose edges meet at 20 degrees with mismatched lengths. Most splits of
// the segments stage are of subsegments encroached by the split point of another segment
// at their shared input vertex (a point at distance d from the apex on one edge
// encroaches its neighbour of length l at angle t when d <= l cos t). The counts pin the
// cascade as concentric shells and midpoints make it; after the stage no subsegment is
// missing or has a vertex inside or on its diametral sphere.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "refiners/tet3d/boundary_recovery.h"
#include "refiners/tet3d/boundary_split.h"
#include "refiners/tet3d/plc_preparation.h"
#include "test_plcs.h"
#include "toolkit/tetmesh/tet_check.h"

namespace delmesh::test {
namespace {

using namespace delmesh::tet3d;

/// A closed surface: the fan of thin triangles (apex, rim i, rim i+1) in z = 0, with rim
/// points at 0, 20, 40 degrees and distances 1, 3, 1.7 from the apex at the origin,
/// closed by a tent over its outline.
Plc thin_fan() {
  Plc plc;
  plc.points.emplace_back(0.0, 0.0, 0.0);
  const double angles[3] = {0.0, 20.0, 40.0}, lengths[3] = {1.0, 3.0, 1.7};
  for (int i = 0; i < 3; ++i) {
    const double r = angles[i] * std::numbers::pi / 180.0;
    plc.points.emplace_back(lengths[i] * std::cos(r), lengths[i] * std::sin(r), 0.0);
  }
  Vec3 top = Vec3::Zero();
  for (const Vec3& p : plc.points) top += p;
  top /= 4.0;
  top.z() = 1.5;
  plc.points.push_back(top);
  auto add = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    Plc::Facet f;
    f.polygons.push_back({a, b, c});
    plc.facets.push_back(f);
  };
  add(0, 1, 2);
  add(0, 2, 3);
  for (std::uint32_t i = 0; i < 4; ++i) add(i, (i + 1) % 4, 4);
  return plc;
}

TEST(Tet3dSegmentCascade, ThinFanSplitsMostlyForOtherSplitPoints) {
  const Plc plc = thin_fan();
  MeshOptions options;
  RefineState state(plc, options);
  ASSERT_TRUE(prepare_plc(state).has_value());
  ASSERT_EQ(state.segments.size(), 9u);
  ASSERT_TRUE(restore_conformity(state, true).has_value());
  const SegmentSplitStats& splits = state.stage_segment_splits;
  EXPECT_EQ(state.stage_steiner, 29u);
  EXPECT_EQ(splits.missing, 7u);
  EXPECT_EQ(splits.encroached_by_input, 2u);
  EXPECT_EQ(splits.encroached_by_segment_vertex, 20u);
  EXPECT_EQ(splits.total(), state.stage_steiner);
  // The rule of the stage: no subsegment is missing or encroached (inside or on).
  std::size_t checked = 0;
  for (const auto& [key, seg] : state.subsegments) {
    const auto a = static_cast<std::uint32_t>(key >> 32), b = static_cast<std::uint32_t>(key);
    std::uint32_t by = kNone;
    EXPECT_EQ(subsegment_status(state, a, b, by), SubfaceStatus::Present) << a << "-" << b << " by " << by;
    ++checked;
  }
  EXPECT_EQ(checked, 9u + state.stage_steiner);
  EXPECT_TRUE(check_topology(state.mesh).empty());
  EXPECT_TRUE(check_delaunay(state.mesh, 20, true).empty());
}

TEST(Tet3dSegmentCascade, ThinFanMeshesValid) {
  // A pyramid over the fan's outline: base area times height over three.
  const double s20 = std::sin(20.0 * std::numbers::pi / 180.0);
  TestPlc input{"thin_fan", thin_fan(), (0.5 * 1.0 * 3.0 * s20 + 0.5 * 3.0 * 1.7 * s20) * 1.5 / 3.0, {}, true};
  MeshOptions options;
  options.max_radius_edge = 1.414;
  const auto r = mesh_plc(input.plc, options);
  ASSERT_TRUE(r.has_value()) << r.error().message;
  ASSERT_GE(r->stats.stages.size(), 2u);
  EXPECT_EQ(r->stats.stages[1].name, "segments");
  EXPECT_EQ(r->stats.stages[1].steiner_points, 29u);
  expect_valid_mesh(input, *r);
}

}  // namespace
}  // namespace delmesh::test
