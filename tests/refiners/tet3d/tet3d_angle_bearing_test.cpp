// Tets bearing a small input angle (refiners/tet3d/angle_bearing.h, notes §3.8): a unit
// cube whose bottom facet holds an extra segment from the corner (0,0,0) at `degrees` to
// the cube edge along x. Both subsegments at the corner are split at the same distance
// from it (as concentric shells do); the tets with the corner and the two split points,
// whose shortest edge joins the split points, bear the angle exactly when
// 2 B sin(angle) < kBearingMargin: below 25.1 degrees at B = 1.414, below 17.4 at B = 2;
// no tet without the corner bears it.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <optional>

#include "refiners/tet3d/angle_bearing.h"
#include "refiners/tet3d/boundary_recovery.h"
#include "refiners/tet3d/boundary_split.h"
#include "refiners/tet3d/plc_preparation.h"
#include "test_plcs.h"

namespace delmesh::test {
namespace {

using namespace delmesh::tet3d;

constexpr std::uint32_t kCorner = 1;  // tet mesh id of input point 0, (0,0,0)

Plc cube_with_corner_segment(double degrees) {
  Plc plc = unit_cube().plc;
  const double a = degrees * std::numbers::pi / 180.0;
  const auto tip = static_cast<std::uint32_t>(plc.points.size());
  plc.points.emplace_back(0.8 * std::cos(a), 0.8 * std::sin(a), 0.0);
  // Facet 4 of add_box is the bottom (z = 0); a two-point polygon is a segment in it.
  plc.facets[4].polygons.push_back({0, tip});
  return plc;
}

/// The subsegment of segment `seg` at the corner (its other end).
std::optional<std::uint32_t> corner_subsegment_end(const RefineState& state, std::uint32_t seg) {
  for (const auto& [key, s] : state.subsegments) {
    if (s != seg) continue;
    const auto a = static_cast<std::uint32_t>(key >> 32), b = static_cast<std::uint32_t>(key);
    if (a == kCorner) return b;
    if (b == kCorner) return a;
  }
  return std::nullopt;
}

struct Bearing {
  std::size_t tets = 0;     ///< tets with the corner whose shortest edge joins the split points
  std::size_t bearing = 0;  ///< of those, the ones bears_small_angle reports
  std::size_t others_bearing = 0;  ///< tets without the corner that it reports (none may)
};

Bearing bearing_at(double degrees, double radius_edge) {
  const Plc plc = cube_with_corner_segment(degrees);
  MeshOptions options;
  RefineState state(plc, options);
  Bearing out;
  EXPECT_TRUE(prepare_plc(state).has_value());
  EXPECT_TRUE(restore_conformity(state, true).has_value());
  // The segments at the corner: the cube edge to (1,0,0) (input 1) and the new one.
  // (tet mesh ids: the corner 1, (1,0,0) 2, the new segment's tip 9).
  auto segment_of = [&](std::uint32_t a, std::uint32_t b) {
    for (std::uint32_t s = 0; s < state.segments.size(); ++s)
      if ((state.segments[s].a == a && state.segments[s].b == b) || (state.segments[s].a == b && state.segments[s].b == a))
        return s;
    return kNone;
  };
  const std::uint32_t edge_seg = segment_of(kCorner, 2), new_seg = segment_of(kCorner, 9);
  EXPECT_NE(edge_seg, kNone);
  EXPECT_NE(new_seg, kNone);
  if (edge_seg == kNone || new_seg == kNone) return out;
  const auto e1 = corner_subsegment_end(state, edge_seg), e2 = corner_subsegment_end(state, new_seg);
  EXPECT_TRUE(e1 && e2);
  if (!e1 || !e2) return out;
  const Vec3 corner = state.mesh.point(kCorner);
  const Vec3 u1 = state.mesh.point(*e1) - corner, u2 = state.mesh.point(*e2) - corner;
  const double d = 0.5 * std::min(u1.norm(), u2.norm());
  const std::uint32_t v1 = split_subsegment(state, kCorner, *e1, corner + d * u1.normalized(), 0.0);
  const std::uint32_t v2 = split_subsegment(state, kCorner, *e2, corner + d * u2.normalized(), 0.0);
  EXPECT_NE(v1, kNone);
  EXPECT_NE(v2, kNone);
  for (std::uint32_t t = 0; t < state.mesh.tet_slots(); ++t) {
    if (state.mesh.is_dead(t) || state.mesh.is_infinite(t)) continue;
    if (state.mesh.local_index(t, kCorner) < 0) {
      out.others_bearing += bears_small_angle(state, t, radius_edge);
      continue;
    }
    if (state.mesh.local_index(t, v1) < 0 || state.mesh.local_index(t, v2) < 0) continue;
    const auto& v = state.mesh.tet(t).v;
    double shortest = 1e300;
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j)
        shortest = std::min(shortest, (state.mesh.point(v[i]) - state.mesh.point(v[j])).norm());
    if (shortest < (state.mesh.point(v1) - state.mesh.point(v2)).norm()) continue;
    ++out.tets;
    out.bearing += bears_small_angle(state, t, radius_edge);
  }
  return out;
}

TEST(Tet3dAngleBearing, SmallAngleAtTheCornerDependsOnTheBound) {
  struct Case {
    double degrees, radius_edge;
    bool bears;
  };
  const Case cases[] = {{15.0, 1.414, true}, {22.0, 1.414, true},  {24.5, 1.414, true}, {26.0, 1.414, false},
                        {35.0, 1.414, false}, {15.0, 2.0, true},   {22.0, 2.0, false},  {50.0, 2.0, false}};
  for (const Case& c : cases) {
    const Bearing b = bearing_at(c.degrees, c.radius_edge);
    ASSERT_GT(b.tets, 0u) << c.degrees << " degrees: no tet with the corner and both split points";
    EXPECT_EQ(b.bearing, c.bears ? b.tets : 0u) << c.degrees << " degrees at B = " << c.radius_edge;
    EXPECT_EQ(b.others_bearing, 0u) << c.degrees << " degrees: a tet without the corner bears the angle";
  }
}

// The tessellation bound asked of CAD models: above the bearing threshold of the radius-edge
// bound, never below the importer's default 20 degrees, never above 30.
TEST(Tet3dAngleBearing, TessellationMinAngleClearsTheBearingThreshold) {
  EXPECT_EQ(tessellation_min_angle_deg(1.414), 26.0);
  EXPECT_EQ(tessellation_min_angle_deg(2.0), 20.0);
  EXPECT_EQ(tessellation_min_angle_deg(1.8), 20.0);
  EXPECT_EQ(tessellation_min_angle_deg(1.75), 21.0);
  EXPECT_EQ(tessellation_min_angle_deg(1.2), 30.0);
  EXPECT_EQ(tessellation_min_angle_deg(0.0), 20.0);
  for (const double bound : {1.3, 1.414, 1.6, 2.0, 3.0}) {
    const double alpha = tessellation_min_angle_deg(bound) * std::numbers::pi / 180.0;
    EXPECT_GE(2.0 * bound * std::sin(alpha), kBearingMargin) << bound;
  }
}

}  // namespace
}  // namespace delmesh::test
