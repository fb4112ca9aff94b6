// Split points of segment recovery (refiners/tet3d/concentric_shells.h, split_choice.h;
// notes §3.8, §4.2.1): shells with a unit per apex, and the choice among the midpoint and
// shell points that keeps a split from encroaching the segments around it. A small fan of
// thin triangles, where recovery with the global power-of-two shells and the usual split
// point cascaded, pins the counts; after the stage no subsegment is missing or has a
// vertex inside or on its diametral sphere.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

#include "refiners/tet3d/boundary_recovery.h"
#include "refiners/tet3d/boundary_split.h"
#include "refiners/tet3d/concentric_shells.h"
#include "refiners/tet3d/plc_preparation.h"
#include "refiners/tet3d/split_choice.h"
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

TEST(Tet3dSplitChoice, ShellDistanceIsTheUnitTimesThePowerOfTwoNearestHalfTheLength) {
  EXPECT_EQ(shell_split_distance(1.0, 3.0), 2.0);   // 1.5 -> 2^1
  EXPECT_EQ(shell_split_distance(1.0, 1.0), 0.5);   // the midpoint
  EXPECT_EQ(shell_split_distance(1.0, 5.0), 2.0);   // 2.5 -> 2^1 (log2 2.5 = 1.32)
  EXPECT_EQ(shell_split_distance(0.3, 1.2), 0.6);   // 2 units
  EXPECT_EQ(shell_split_distance(0.3, 2.9), 1.2);   // 4.83 units -> 4
  EXPECT_EQ(shell_split_distance(1.0, 0.0), 0.0);
  EXPECT_EQ(shell_split_distance(0.0, 1.0), 0.0);
}

TEST(Tet3dSplitChoice, ShellUnitIsTheShortestSegmentAtTheApex) {
  const Plc plc = thin_fan();
  MeshOptions options;
  RefineState state(plc, options);
  ASSERT_TRUE(prepare_plc(state).has_value());
  std::vector<double> shortest(state.mesh.num_vertices(), std::numeric_limits<double>::infinity());
  for (const SegmentData& s : state.segments) {
    const double l = (state.mesh.point(s.a) - state.mesh.point(s.b)).norm();
    shortest[s.a] = std::min(shortest[s.a], l);
    shortest[s.b] = std::min(shortest[s.b], l);
  }
  ASSERT_EQ(state.segments.size(), 9u);
  for (const SegmentData& s : state.segments) {
    EXPECT_TRUE(s.shell_a && s.shell_b);
    EXPECT_EQ(s.shell_unit_a, shortest[s.a]);
    EXPECT_EQ(s.shell_unit_b, shortest[s.b]);
  }
  // Input vertex 0 (tet mesh id 1) is the apex; its shortest segment is the unit rim edge.
  EXPECT_DOUBLE_EQ(shortest[1], 1.0);
}

TEST(Tet3dSplitChoice, ChosenPointIsAMidpointOrAShellPoint) {
  const Plc plc = thin_fan();
  MeshOptions options;
  RefineState state(plc, options);
  ASSERT_TRUE(prepare_plc(state).has_value());
  for (const SegmentData& s : state.segments) {
    const Vec3 c = choose_subsegment_split(state, s.a, s.b, kNone);
    const Vec3& pa = state.mesh.point(s.a);
    const Vec3& pb = state.mesh.point(s.b);
    const double length = (pb - pa).norm();
    // On the segment, strictly inside, pieces at least a quarter of it.
    EXPECT_NEAR(((c - pa).norm() + (pb - c).norm()) / length, 1.0, 1e-12);
    EXPECT_GE((c - pa).norm(), 0.25 * length * (1 - 1e-12));
    EXPECT_GE((pb - c).norm(), 0.25 * length * (1 - 1e-12));
    auto on_shell = [](double d, double unit) {
      const double k = std::log2(d / unit);
      return std::abs(k - std::round(k)) < 1e-9;
    };
    const bool midpoint = c == 0.5 * (pa + pb);
    EXPECT_TRUE(midpoint || on_shell((c - pa).norm(), s.shell_unit_a) || on_shell((pb - c).norm(), s.shell_unit_b));
  }
}

TEST(Tet3dSplitChoice, ThinFanRecoversWithoutTheCascade) {
  const Plc plc = thin_fan();
  MeshOptions options;
  RefineState state(plc, options);
  ASSERT_TRUE(prepare_plc(state).has_value());
  ASSERT_TRUE(restore_conformity(state, true).has_value());
  // With global power-of-two shells and the usual split point this stage made 29 splits,
  // 20 of them for subsegments encroached by another split point (7 missing, 2 by an
  // input vertex).
  const SegmentSplitStats& splits = state.stage_segment_splits;
  EXPECT_EQ(state.stage_steiner, 12u);
  EXPECT_EQ(splits.missing, 2u);
  EXPECT_EQ(splits.encroached_by_input, 3u);
  EXPECT_EQ(splits.encroached_by_segment_vertex, 7u);
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

TEST(Tet3dSplitChoice, ThinFanMeshesValid) {
  // A pyramid over the fan's outline: base area times height over three.
  const double s20 = std::sin(20.0 * std::numbers::pi / 180.0);
  TestPlc input{"thin_fan", thin_fan(), (0.5 * 1.0 * 3.0 * s20 + 0.5 * 3.0 * 1.7 * s20) * 1.5 / 3.0, {}, true};
  MeshOptions options;
  options.max_radius_edge = 1.414;
  const auto r = mesh_plc(input.plc, options);
  ASSERT_TRUE(r.has_value()) << r.error().message;
  EXPECT_EQ(r->stats.stages[1].name, "segments");
  EXPECT_EQ(r->stats.stages[1].steiner_points, 12u);
  expect_valid_mesh(input, *r);
}

}  // namespace
}  // namespace delmesh::test
