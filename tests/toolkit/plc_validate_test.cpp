// validate_plc() on small hand-built PLCs: every issue kind is found, with the right ids,
// and valid inputs produce no issue.
#include <gtest/gtest.h>

#include <algorithm>

#include "toolkit/plc/plc_statistics.h"
#include "toolkit/plc/plc_validate.h"

namespace delmesh {
namespace {

//      7-------6
//     /|      /|      unit cube, vertices 0..7, six quad facets with outward loops
//    4-------5 |
//    | 3-----|-2
//    |/      |/
//    0-------1
Plc unit_cube() {
  Plc plc;
  plc.points = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  const std::vector<Plc::Polygon> quads = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4},
                                           {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
  for (const auto& q : quads) plc.facets.push_back({{q}, {}, 1});
  return plc;
}

std::vector<PlcIssue> of_kind(const std::vector<PlcIssue>& issues, PlcIssueKind kind) {
  std::vector<PlcIssue> out;
  std::copy_if(issues.begin(), issues.end(), std::back_inserter(out),
               [&](const PlcIssue& i) { return i.kind == kind; });
  return out;
}

/// validate_plc() of a PLC that need not be closed (the surface may have borders).
std::vector<PlcIssue> validate_open(const Plc& plc) {
  PlcValidationOptions options;
  options.require_closed = false;
  return validate_plc(plc, options);
}

bool has(const std::vector<std::uint32_t>& ids, std::uint32_t id) {
  return std::find(ids.begin(), ids.end(), id) != ids.end();
}

TEST(PlcValidate, CubeIsValid) {
  const Plc cube = unit_cube();
  EXPECT_TRUE(validate_plc(cube).empty());
}

TEST(PlcValidate, NonPlanarFacetNamesFacetAndVertex) {
  Plc cube = unit_cube();
  cube.points[6] += Vec3(1, 1, 1) * 0x1p-50;  // moves one corner off all three of its quads
  const auto issues = of_kind(validate_plc(cube), PlcIssueKind::NonPlanarFacet);
  // Vertex 6 is on the top (1), right (3) and back (4) quads; each is reported.
  ASSERT_EQ(issues.size(), 3u);
  EXPECT_EQ(issues[0].facets, (std::vector<std::uint32_t>{1}));
  EXPECT_EQ(issues[1].facets, (std::vector<std::uint32_t>{3}));
  EXPECT_EQ(issues[2].facets, (std::vector<std::uint32_t>{4}));
  EXPECT_TRUE(has(issues[0].vertices, 7));  // the plane is taken through vertices 4, 5, 6
}

TEST(PlcValidate, OpenBoundaryListsEveryOpenEdge) {
  Plc cube = unit_cube();
  cube.facets.erase(cube.facets.begin() + 1);  // remove the top
  const auto issues = validate_plc(cube);
  const auto open = of_kind(issues, PlcIssueKind::OpenBoundary);
  ASSERT_EQ(open.size(), 4u);
  for (const auto& issue : open) {
    EXPECT_TRUE(has(issue.vertices, 4) || has(issue.vertices, 5) || has(issue.vertices, 6) ||
                has(issue.vertices, 7));
  }
  EXPECT_TRUE(validate_open(cube).empty());
}

TEST(PlcValidate, DuplicateVertices) {
  Plc cube = unit_cube();
  cube.points.push_back({1, 1, 1});
  const auto issues = of_kind(validate_plc(cube), PlcIssueKind::DuplicateVertex);
  ASSERT_EQ(issues.size(), 1u);
  EXPECT_EQ(issues[0].vertices, (std::vector<std::uint32_t>{6, 8}));
}

TEST(PlcValidate, DegenerateFacets) {
  Plc plc;
  plc.points = {{0, 0, 0}, {1, 1, 1}, {2, 2, 2}, {3, 0, 0}};
  plc.facets.push_back({{{0, 1, 2}}, {}, 0});     // collinear
  plc.facets.push_back({{{0, 1, 3, 1}}, {}, 0});  // repeated vertex
  plc.facets.push_back({{}, {}, 0});              // no polygon
  const auto issues = of_kind(validate_open(plc), PlcIssueKind::DegenerateFacet);
  std::vector<bool> seen(3, false);
  for (const auto& issue : issues) {
    ASSERT_EQ(issue.facets.size(), 1u);
    seen[issue.facets[0]] = true;
  }
  EXPECT_TRUE(seen[0] && seen[1] && seen[2]);
}

TEST(PlcValidate, InvalidIndexDoesNotCrash) {
  Plc plc = unit_cube();
  plc.facets[2].polygons[0][1] = 99;
  plc.segments.push_back({0, 100, 0});
  const auto issues = of_kind(validate_plc(plc), PlcIssueKind::InvalidIndex);
  ASSERT_EQ(issues.size(), 2u);
  EXPECT_TRUE(has(issues[0].facets, 2));
  EXPECT_TRUE(has(issues[1].segments, 0));
}

TEST(PlcValidate, CrossingTrianglesIntersect) {
  Plc plc;
  plc.points = {{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {0.5, 0.5, -1}, {0.5, 0.5, 1}, {3, 3, 0.5}};
  plc.facets.push_back({{{0, 1, 2}}, {}, 0});
  plc.facets.push_back({{{3, 4, 5}}, {}, 0});
  const auto issues = of_kind(validate_open(plc), PlcIssueKind::Intersection);
  ASSERT_EQ(issues.size(), 1u);
  EXPECT_EQ(issues[0].facets, (std::vector<std::uint32_t>{0, 1}));
}

TEST(PlcValidate, TrianglesSharingAnEdgeOrVertexAreFine) {
  Plc plc;
  plc.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {-1, -1, 5}};
  plc.facets.push_back({{{0, 1, 2}}, {}, 0});
  plc.facets.push_back({{{0, 1, 3}}, {}, 0});  // shares edge 0-1
  plc.facets.push_back({{{2, 3, 4}}, {}, 0});  // shares vertices 2 and 3 with the others
  EXPECT_TRUE(validate_open(plc).empty());
}

TEST(PlcValidate, TJunctionIsAnIntersection) {
  Plc plc;
  // Triangle 1 has its vertex 3 in the middle of edge 0-1 of triangle 0.
  plc.points = {{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {1, 0, 0}, {1, 0, 1}, {1.5, 0.2, 1}};
  plc.facets.push_back({{{0, 1, 2}}, {}, 0});
  plc.facets.push_back({{{3, 4, 5}}, {}, 0});
  const auto issues = of_kind(validate_open(plc), PlcIssueKind::Intersection);
  ASSERT_EQ(issues.size(), 1u);
  EXPECT_EQ(issues[0].facets, (std::vector<std::uint32_t>{0, 1}));
}

TEST(PlcValidate, EdgeBetweenSharedVerticesThroughAnotherVertexIsAnIntersection) {
  // Facet 0 lies in z = 0 with vertex 1 in the middle of its side 0-2; facet 1 stands in
  // y = 0 on vertices 0 and 2 only: its edge 0-2 runs through vertex 1 (a T-junction),
  // though all its other vertices are on one side of facet 0's plane.
  Plc plc;
  plc.points = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 0}, {1, 0, 1}};
  plc.facets.push_back({{{0, 1, 2, 3, 4}}, {}, 0});
  plc.facets.push_back({{{0, 2, 5}}, {}, 0});
  const auto issues = of_kind(validate_open(plc), PlcIssueKind::Intersection);
  ASSERT_EQ(issues.size(), 1u);
  EXPECT_EQ(issues[0].facets, (std::vector<std::uint32_t>{0, 1}));
}

TEST(PlcValidate, CoplanarOverlapIsAnIntersection) {
  Plc plc;
  plc.points = {{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {0.5, 0.5, 0}, {3, 0.5, 0}, {0.5, 3, 0}};
  plc.facets.push_back({{{0, 1, 2}}, {}, 0});
  plc.facets.push_back({{{3, 4, 5}}, {}, 0});
  PlcValidationOptions options;
  options.require_closed = false;
  EXPECT_EQ(of_kind(validate_plc(plc, options), PlcIssueKind::Intersection).size(), 1u);
  // Coplanar neighbours sharing an edge, on opposite sides of it: valid.
  Plc ok;
  ok.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}};
  ok.facets.push_back({{{0, 1, 2}}, {}, 0});
  ok.facets.push_back({{{1, 3, 2}}, {}, 0});
  EXPECT_TRUE(validate_plc(ok, options).empty());
}

TEST(PlcValidate, EdgeAlongAnotherFacetsDiagonalIsAnIntersection) {
  // Triangle 1 (0, 1, 3) lies inside quad 0 (0, 1, 2, 3): its edge 1-3 runs along the
  // quad's diagonal between two quad vertices. Every triangle vertex is a quad vertex,
  // the quad's other vertex 2 lies outside the triangle and no edges cross: only the
  // diagonal shows the overlap.
  Plc plc;
  plc.points = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  plc.facets.push_back({{{0, 1, 2, 3}}, {}, 0});
  plc.facets.push_back({{{0, 1, 3}}, {}, 0});
  const auto issues = of_kind(validate_open(plc), PlcIssueKind::Intersection);
  ASSERT_EQ(issues.size(), 1u);
  EXPECT_EQ(issues[0].facets, (std::vector<std::uint32_t>{0, 1}));
  EXPECT_TRUE(has(issues[0].vertices, 1) && has(issues[0].vertices, 3));
}

TEST(PlcValidate, FreeSegmentAlongAFacetDiagonalIsAnIntersection) {
  Plc plc = unit_cube();
  plc.segments.push_back({0, 2, 0});  // the bottom quad's diagonal
  const auto issues = of_kind(validate_plc(plc), PlcIssueKind::Intersection);
  ASSERT_EQ(issues.size(), 1u);
  EXPECT_EQ(issues[0].segments, (std::vector<std::uint32_t>{0}));
  EXPECT_EQ(issues[0].facets, (std::vector<std::uint32_t>{0}));
}

TEST(PlcValidate, ChordsOutsideAFacetAreFine) {
  // An L-shaped facet and the triangle filling its notch: the triangle's edge 2-4 joins
  // two L vertices but runs outside the L (across the notch).
  Plc plc;
  plc.points = {{0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {1, 1, 0}, {1, 2, 0}, {0, 2, 0}, {2, 2, 0}};
  plc.facets.push_back({{{0, 1, 2, 3, 4, 5}}, {}, 0});
  plc.facets.push_back({{{2, 6, 4}}, {}, 0});
  PlcValidationOptions options;
  options.require_closed = false;
  EXPECT_TRUE(of_kind(validate_plc(plc, options), PlcIssueKind::Intersection).empty());
  // The same with the L's loop given clockwise (orientation must not matter).
  std::reverse(plc.facets[0].polygons[0].begin(), plc.facets[0].polygons[0].end());
  EXPECT_TRUE(of_kind(validate_plc(plc, options), PlcIssueKind::Intersection).empty());
  // The L's diagonal 0-3 (from the outer corner to the reflex corner) runs inside it.
  plc.segments.push_back({0, 3, 0});
  const auto issues = of_kind(validate_plc(plc, options), PlcIssueKind::Intersection);
  ASSERT_EQ(issues.size(), 1u);
  EXPECT_EQ(issues[0].segments, (std::vector<std::uint32_t>{0}));
}

TEST(PlcValidate, ChordsAcrossAHoleOrTheSolidPartOfAFacet) {
  // Square 0..3 with a square hole 4..7 (hole point at its centre).
  Plc plc;
  plc.points = {{0, 0, 0}, {4, 0, 0}, {4, 4, 0}, {0, 4, 0},
                {1, 1, 0}, {3, 1, 0}, {3, 3, 0}, {1, 3, 0}};
  plc.facets.push_back({{{0, 1, 2, 3}, {4, 5, 6, 7}}, {Vec3(2, 2, 0)}, 0});
  plc.segments.push_back({4, 6, 0});  // the hole's diagonal: in the hole, fine
  PlcValidationOptions options;
  options.require_closed = false;
  EXPECT_TRUE(of_kind(validate_plc(plc, options), PlcIssueKind::Intersection).empty());
  plc.segments.push_back({0, 4, 0});  // outer corner to hole corner: through the solid part
  const auto issues = of_kind(validate_plc(plc, options), PlcIssueKind::Intersection);
  ASSERT_EQ(issues.size(), 1u);
  EXPECT_EQ(issues[0].segments, (std::vector<std::uint32_t>{1}));
  // Without the hole point the inner loop is a constraint: the diagonal 4-6 is inside.
  plc.facets[0].holes.clear();
  plc.segments.pop_back();
  EXPECT_EQ(of_kind(validate_plc(plc, options), PlcIssueKind::Intersection).size(), 1u);
}

TEST(PlcValidate, NonSimplePolygon) {
  Plc plc;
  plc.points = {{0, 0, 0}, {1, 1, 0}, {1, 0, 0}, {0, 1, 0}};  // bow tie 0-1-2-3
  plc.facets.push_back({{{0, 1, 2, 3}}, {}, 0});
  const auto issues = of_kind(validate_open(plc), PlcIssueKind::Intersection);
  ASSERT_EQ(issues.size(), 1u);
  EXPECT_EQ(issues[0].facets, (std::vector<std::uint32_t>{0}));
}

TEST(PlcValidate, SegmentThroughFacetHoleOrSolidPart) {
  Plc plc;
  // Square 0..3 with a square hole 4..7 (hole point at its centre).
  plc.points = {{0, 0, 0}, {4, 0, 0}, {4, 4, 0}, {0, 4, 0},
                {1, 1, 0}, {3, 1, 0}, {3, 3, 0}, {1, 3, 0},
                {2, 2, -1}, {2, 2, 1}, {0.5, 0.5, -1}, {0.5, 0.5, 1}};
  plc.facets.push_back({{{0, 1, 2, 3}, {4, 5, 6, 7}}, {Vec3(2, 2, 0)}, 0});
  plc.segments.push_back({8, 9, 0});    // through the hole: fine
  plc.segments.push_back({10, 11, 0});  // through the solid part
  const auto issues = of_kind(validate_open(plc), PlcIssueKind::Intersection);
  ASSERT_EQ(issues.size(), 1u);
  EXPECT_EQ(issues[0].segments, (std::vector<std::uint32_t>{1}));
  EXPECT_EQ(issues[0].facets, (std::vector<std::uint32_t>{0}));
}

TEST(PlcValidate, SegmentTouchingAFacetVertexOrEdgeOrEndingOnIt) {
  Plc plc;
  plc.points = {{0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 0},
                {0, 0, -1}, {0, 0, 1},      // through vertex 0
                {1, 0, -1}, {1, 0, 1},      // through the middle of edge 0-1
                {1, 1, 5}, {1, 1, 0.5},     // above the facet, not touching it
                {3, 3, -1}, {3, 3, 1},      // beside it
                {0, 2, 7}};                 // ends on vertex 3: allowed
  plc.facets.push_back({{{0, 1, 2, 3}}, {}, 0});
  plc.segments = {{4, 5, 0}, {6, 7, 0}, {8, 9, 0}, {10, 11, 0}, {3, 12, 0}};
  const auto issues = of_kind(validate_open(plc), PlcIssueKind::Intersection);
  ASSERT_EQ(issues.size(), 2u);
  EXPECT_EQ(issues[0].segments, (std::vector<std::uint32_t>{0}));
  EXPECT_EQ(issues[1].segments, (std::vector<std::uint32_t>{1}));
}

TEST(PlcValidate, CrossingFreeSegments) {
  Plc plc;
  plc.points = {{0, 0, 0}, {2, 2, 0}, {0, 2, 0}, {2, 0, 0}, {3, 3, 0}};
  plc.segments = {{0, 1, 0}, {2, 3, 0}, {1, 4, 0}};
  const auto issues = of_kind(validate_plc(plc), PlcIssueKind::Intersection);
  ASSERT_EQ(issues.size(), 1u);
  EXPECT_EQ(issues[0].segments, (std::vector<std::uint32_t>{0, 1}));
}

TEST(PlcValidate, NonManifoldEdgeWhenRequested) {
  Plc plc;
  // Three fins on edge 0-1.
  plc.points = {{0, 0, 0}, {1, 0, 0}, {0.5, 1, 0}, {0.5, -1, 0.2}, {0.5, 0, 1}};
  plc.facets = {{{{0, 1, 2}}, {}, 0}, {{{1, 0, 3}}, {}, 0}, {{{0, 1, 4}}, {}, 0}};
  PlcValidationOptions options;
  options.require_closed = false;
  EXPECT_TRUE(validate_plc(plc, options).empty());
  options.require_manifold = true;
  const auto issues = validate_plc(plc, options);
  ASSERT_EQ(issues.size(), 1u);
  EXPECT_EQ(issues[0].kind, PlcIssueKind::NonManifoldEdge);
  EXPECT_EQ(issues[0].vertices, (std::vector<std::uint32_t>{0, 1}));
  EXPECT_EQ(issues[0].facets, (std::vector<std::uint32_t>{0, 1, 2}));
}

TEST(PlcValidate, FreeSegmentWhenRequested) {
  Plc plc = unit_cube();
  plc.points.push_back({0.2, 0.8, 0.3});
  plc.points.push_back({0.2, 0.8, 0.4});
  plc.segments.push_back({8, 9, 0});
  plc.segments.push_back({0, 1, 0});  // a cube edge: bounds facets
  EXPECT_TRUE(validate_plc(plc).empty());
  PlcValidationOptions options;
  options.allow_free_segments = false;
  const auto issues = validate_plc(plc, options);
  ASSERT_EQ(issues.size(), 1u);
  EXPECT_EQ(issues[0].kind, PlcIssueKind::FreeSegment);
  EXPECT_EQ(issues[0].segments, (std::vector<std::uint32_t>{0}));
}

TEST(PlcValidate, RegionAndHolePointsOutside) {
  Plc plc = unit_cube();
  plc.regions.push_back({Vec3(0.5, 0.5, 0.5), 1, -1});
  plc.regions.push_back({Vec3(2, 0.5, 0.5), 2, -1});
  plc.holes.push_back(Vec3(-1, -1, -1));
  const auto issues = validate_plc(plc);
  const auto regions = of_kind(issues, PlcIssueKind::RegionOutside);
  ASSERT_EQ(regions.size(), 1u);
  EXPECT_EQ(regions[0].points, (std::vector<std::uint32_t>{1}));
  EXPECT_EQ(of_kind(issues, PlcIssueKind::HoleOutside).size(), 1u);
}

TEST(PlcValidate, TruncatesAndCounts) {
  Plc plc;
  for (int i = 0; i < 50; ++i) plc.points.push_back({0, 0, 0});
  PlcValidationOptions options;
  options.max_issues = 0;
  const auto issues = validate_plc(plc, options);
  ASSERT_EQ(issues.size(), 1u);
  EXPECT_EQ(issues[0].kind, PlcIssueKind::Truncated);
  const Error error = issues_to_error(issues);
  EXPECT_NE(error.message.find("DuplicateVertex"), std::string::npos);
}

TEST(PlcStatistics, CubeAngles) {
  const auto stats = plc_statistics(unit_cube());
  EXPECT_EQ(stats.vertices, 8u);
  EXPECT_EQ(stats.segments, 12u);
  EXPECT_EQ(stats.facets, 6u);
  EXPECT_NEAR(stats.min_segment_angle_deg, 90.0, 1e-9);
  EXPECT_NEAR(stats.min_dihedral_deg, 90.0, 1e-9);
}

TEST(PlcStatistics, ThinWedge) {
  Plc plc;
  // Two triangles on edge 0-1 opening by 10 degrees.
  const double a = 10.0 * 3.14159265358979323846 / 180.0;
  plc.points = {{0, 0, 0}, {1, 0, 0}, {0.5, 1, 0}, {0.5, std::cos(a), std::sin(a)}};
  plc.facets.push_back({{{0, 1, 2}}, {}, 0});
  plc.facets.push_back({{{1, 0, 3}}, {}, 0});
  const auto stats = plc_statistics(plc);
  EXPECT_NEAR(stats.min_dihedral_deg, 10.0, 1e-9);
  EXPECT_EQ(stats.min_dihedral_edge[0], 0u);
  EXPECT_EQ(stats.min_dihedral_edge[1], 1u);
}

}  // namespace
}  // namespace delmesh
