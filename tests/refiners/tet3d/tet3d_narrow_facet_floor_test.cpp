// Floors that follow a facet narrower than them between two of its own segments that
// share no vertex (refiners/tet3d/narrow_facet_floor.h):
//   * segment_distance on skew, crossing-above, parallel and degenerate segments;
//   * a unit cube whose top holds a strip 0.002 wide and 1 long: the strip's two long
//     segments are each other's partners and a point on one gets kFloorFactor times its
//     distance to the other; segments that share a vertex are never partners, and a
//     facet's short sides farther apart than their length are not either;
//   * a tetrahedron (triangle facets only) has no partners;
//   * meshed at radius-edge 1.414 the strip leaves no tet above the bound away from small
//     input angles (168 of 14049 tets before this rule, when the floors along the strip
//     grew from 0.00025 at its ends by 1/128 per unit, above its width; 0 of 16044 with it).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "refiners/tet3d/narrow_facet_floor.h"
#include "refiners/tet3d/plc_preparation.h"
#include "test_plcs.h"

namespace delmesh::test {
namespace {

using namespace delmesh::tet3d;

/// A unit cube whose top is three facets: [0, 1] x [0, 0.5], a strip [0, 1] x [0.5, 0.5 + w]
/// and [0, 1] x [0.5 + w, 1] (all at z = 1): no small input angle, but the strip's long
/// segments share no vertex and lie w apart.
Plc cube_with_thin_strip(double w) {
  Plc plc;
  for (int i = 0; i < 8; ++i) plc.points.emplace_back(i & 1 ? 1.0 : 0.0, i & 2 ? 1.0 : 0.0, i & 4 ? 1.0 : 0.0);
  plc.points.emplace_back(0.0, 0.5, 1.0);      // 8
  plc.points.emplace_back(1.0, 0.5, 1.0);      // 9
  plc.points.emplace_back(0.0, 0.5 + w, 1.0);  // 10
  plc.points.emplace_back(1.0, 0.5 + w, 1.0);  // 11
  const std::vector<std::vector<std::uint32_t>> polygons = {
      {0, 2, 6, 10, 8, 4}, {1, 5, 9, 11, 7, 3}, {0, 4, 5, 1}, {2, 3, 7, 6},
      {0, 1, 3, 2},        {4, 5, 9, 8},        {8, 9, 11, 10}, {10, 11, 7, 6}};
  for (std::size_t f = 0; f < polygons.size(); ++f) {
    Plc::Facet facet;
    facet.polygons.push_back(polygons[f]);
    facet.marker = static_cast<int>(f) + 1;
    plc.facets.push_back(facet);
  }
  return plc;
}

std::uint32_t segment_id(const RefineState& state, std::uint32_t a, std::uint32_t b) {
  const auto it = state.subsegments.find(edge_key(a, b));
  return it == state.subsegments.end() ? kNone : it->second;
}

bool has_partner(const RefineState& state, std::uint32_t s, std::uint32_t q) {
  const auto partners = state.narrow_partners.find(s);
  if (partners == state.narrow_partners.end()) return false;
  const auto& p = partners->second;
  return std::find(p.begin(), p.end(), q) != p.end();
}

TEST(Tet3dNarrowFacetFloor, SegmentDistance) {
  // Skew: x axis from 0 to 1 and a segment along y at x = 0.5, z = 0.3.
  EXPECT_NEAR(segment_distance(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0.5, -1, 0.3), Vec3(0.5, 1, 0.3)), 0.3, 1e-15);
  // The closest points at ends: the second segment lies beyond the first's end.
  EXPECT_NEAR(segment_distance(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(2, 0, 1), Vec3(3, 0, 1)), std::sqrt(2.0), 1e-15);
  // Parallel, overlapping in x: their distance.
  EXPECT_NEAR(segment_distance(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0.5, 0.002, 0), Vec3(1.5, 0.002, 0)), 0.002, 1e-15);
  // A degenerate segment is a point.
  EXPECT_NEAR(segment_distance(Vec3(0.5, 1, 0), Vec3(0.5, 1, 0), Vec3(0, 0, 0), Vec3(1, 0, 0)), 1.0, 1e-15);
}

TEST(Tet3dNarrowFacetFloor, PartnersOfAStrip) {
  constexpr double kWidth = 0.002;
  const Plc plc = cube_with_thin_strip(kWidth);
  MeshOptions options;
  RefineState state(plc, options);
  ASSERT_TRUE(prepare_plc(state).has_value());
  // Tet mesh id = input index + 1.
  const std::uint32_t lower = segment_id(state, 9, 10), upper = segment_id(state, 11, 12);
  const std::uint32_t left_end = segment_id(state, 9, 11), right_end = segment_id(state, 10, 12);
  ASSERT_NE(lower, kNone);
  ASSERT_NE(upper, kNone);
  ASSERT_NE(left_end, kNone);
  ASSERT_NE(right_end, kNone);
  EXPECT_TRUE(has_partner(state, lower, upper));
  EXPECT_TRUE(has_partner(state, upper, lower));
  // The strip's ends are 1 apart, farther than their length (0.002).
  EXPECT_FALSE(has_partner(state, left_end, right_end));
  EXPECT_FALSE(has_partner(state, right_end, left_end));
  for (const auto& [s, partners] : state.narrow_partners) {
    const SegmentData& seg = state.segments[s];
    for (const std::uint32_t q : partners) {
      const SegmentData& other = state.segments[q];
      EXPECT_TRUE(seg.a != other.a && seg.a != other.b && seg.b != other.a && seg.b != other.b)
          << "segments " << s << " and " << q << " share a vertex";
    }
  }
  // A point in the middle of the lower long segment: the floor is kFloorFactor * width.
  EXPECT_NEAR(narrow_facet_floor(state, lower, Vec3(0.5, 0.5, 1.0)), kFloorFactor * kWidth, 1e-15);
  // Before the rule, the field floors there grew from the strip's ends by 1/128 per unit:
  // the input floor at each end is kFloorFactor times its local feature size (the width).
  EXPECT_NEAR(state.vertices[9].field_floor, kFloorFactor * kWidth, 1e-15);
  EXPECT_GT(state.vertices[9].field_floor + 0.5 / 128.0, 2.0 * kWidth);
}

TEST(Tet3dNarrowFacetFloor, TrianglesHaveNoPartners) {
  Plc plc;
  plc.points = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
  const std::uint32_t faces[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};
  for (const auto& f : faces) {
    Plc::Facet facet;
    facet.polygons.push_back({f[0], f[1], f[2]});
    plc.facets.push_back(facet);
  }
  MeshOptions options;
  RefineState state(plc, options);
  ASSERT_TRUE(prepare_plc(state).has_value());
  EXPECT_TRUE(state.narrow_partners.empty());
  for (std::uint32_t s = 0; s < state.segments.size(); ++s) {
    EXPECT_TRUE(std::isinf(narrow_facet_floor(state, s, Vec3(0.1, 0.1, 0.1)))) << s;
  }
}

TEST(Tet3dNarrowFacetFloor, StripMeetsTheBound) {
  constexpr double kWidth = 0.002;
  MeshOptions options;
  options.max_radius_edge = 1.414;
  auto r = mesh_plc(cube_with_thin_strip(kWidth), options);
  ASSERT_TRUE(r.has_value()) << r.error().message;
  const TetraMesh& mesh = r->mesh;
  ASSERT_EQ(r->tet_at_small_angle.size(), mesh.tets.size());
  std::size_t above = 0, above_elsewhere = 0;
  for (std::size_t t = 0; t < mesh.tets.size(); ++t) {
    const auto& v = mesh.tets[t];
    if (radius_edge_ratio(mesh.points[v[0]], mesh.points[v[1]], mesh.points[v[2]], mesh.points[v[3]]) <= 1.414)
      continue;
    ++above;
    if (r->tet_at_small_angle[t] == 0) ++above_elsewhere;
  }
  EXPECT_EQ(above_elsewhere, 0u) << above << " tets above the bound of " << mesh.tets.size();
  EXPECT_EQ(r->stats.unmet_tets, r->stats.unmet_tets_at_small_angles);
  // The strip is resolved: some vertex lies on its long segments away from its ends.
  bool inside = false;
  for (const Vec3& p : mesh.points)
    inside = inside || (p.z() == 1.0 && (p.y() == 0.5 || p.y() == 0.5 + kWidth) && p.x() > 0.25 && p.x() < 0.75);
  EXPECT_TRUE(inside);
}

}  // namespace
}  // namespace delmesh::test
