// Tests of the .vtu and .svg writers and of the helpers they use (edge extraction, angles).
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "tests/support/scratch_dir.h"
#include "toolkit/mesh2d/svg_writer.h"
#include "toolkit/mesh2d/triangle_angles.h"
#include "toolkit/mesh2d/triangle_mesh_edges.h"
#include "toolkit/mesh2d/vtu_writer.h"

namespace delmesh {
namespace {

// A 4x1 strip of points: three fat triangles and one sliver (a very flat triangle whose
// apex 4 sits just above the bottom edge).
//
//   2 ----------- 3
//   |  \        / |
//   0 ---- 4 ---- 1      (4 is at (0.5, 0.01))
TriangleMesh strip_with_sliver() {
  TriangleMesh mesh;
  mesh.points = {{0, 0}, {1, 0}, {0, 1}, {1, 1}, {0.5, 0.01}};
  mesh.point_markers = {1, 1, 1, 1, 0};
  mesh.triangles = {{0, 4, 2}, {4, 1, 3}, {4, 3, 2}, {0, 1, 4}};
  mesh.triangle_attributes = {1, 1, 2, 2};
  mesh.segments = {{0, 1}, {1, 3}, {3, 2}, {2, 0}};
  mesh.segment_markers = {1, 1, 1, 1};
  return mesh;
}

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (auto at = text.find(what); at != std::string::npos; at = text.find(what, at + what.size())) ++n;
  return n;
}

/// The d="..." attribute of the first <path> whose attributes contain `marker`.
std::string path_data(const std::string& svg, const std::string& marker) {
  const auto at = svg.find(marker);
  if (at == std::string::npos) return {};
  const auto d = svg.find("d=\"", at);
  const auto end = svg.find('"', d + 3);
  return svg.substr(d + 3, end - d - 3);
}

TEST(TriangleAngles, RightIsoscelesAndDegenerateTriangles) {
  const auto a = triangle_angles_deg({0, 0}, {1, 0}, {0, 1});
  EXPECT_NEAR(a[0], 90.0, 1e-12);
  EXPECT_NEAR(a[1], 45.0, 1e-12);
  EXPECT_NEAR(a[2], 45.0, 1e-12);
  EXPECT_NEAR(a[0] + a[1] + a[2], 180.0, 1e-12);
  EXPECT_NEAR(triangle_min_angle_deg({0, 0}, {2, 0}, {1, std::sqrt(3.0)}), 60.0, 1e-12);
  EXPECT_EQ(triangle_min_angle_deg({0, 0}, {1, 0}, {2, 0}), 0.0);
  const AngleRange range = mesh_angle_range(strip_with_sliver());
  EXPECT_LT(range.min_deg, 2.5);
  EXPECT_GT(range.max_deg, 175.0);
}

TEST(TriangleMeshEdges, EachEdgeOnceWithSegmentAndBoundaryFlags) {
  const auto edges = mesh_edges(strip_with_sliver());
  ASSERT_EQ(edges.size(), 8u);  // 5 points, 4 triangles: E = V + T - 1
  std::size_t boundary = 0, segment = 0;
  for (const auto& e : edges) {
    EXPECT_LT(e.a, e.b);
    boundary += e.is_boundary;
    segment += e.is_segment;
  }
  EXPECT_EQ(boundary, 4u);
  EXPECT_EQ(segment, 4u);
}

TEST(VtuWriter, WritesPointsCellsAndCellData) {
  test::ScratchDir dir("vtu");
  ASSERT_TRUE(write_vtu(dir / "m.vtu", strip_with_sliver()));
  const std::string vtu = test::read_file(dir / "m.vtu");
  EXPECT_NE(vtu.find("NumberOfPoints=\"5\" NumberOfCells=\"4\""), std::string::npos);
  EXPECT_NE(vtu.find("Name=\"min_angle\""), std::string::npos);
  EXPECT_NE(vtu.find("Name=\"region\""), std::string::npos);
  EXPECT_NE(vtu.find("Name=\"marker\""), std::string::npos);
  EXPECT_NE(vtu.find("0 4 2\n4 1 3\n4 3 2\n0 1 4\n"), std::string::npos);
  EXPECT_NE(vtu.find("3\n6\n9\n12\n</DataArray>"), std::string::npos);
  EXPECT_EQ(count(vtu, "<DataArray"), count(vtu, "</DataArray>"));
  EXPECT_NE(vtu.find("</VTKFile>"), std::string::npos);

  TriangleMesh bad = strip_with_sliver();
  bad.triangle_attributes.push_back(3);
  EXPECT_FALSE(write_vtu(dir / "bad.vtu", bad));
}

TEST(SvgWriter, HighlightsTheWorstTrianglesAndDrawsSegmentsApart) {
  test::ScratchDir dir("svg");
  const TriangleMesh mesh = strip_with_sliver();
  ASSERT_TRUE(write_svg(dir / "m.svg", mesh));
  const std::string svg = test::read_file(dir / "m.svg");
  EXPECT_EQ(svg.rfind("<?xml", 0), 0u);
  EXPECT_NE(svg.find("</svg>"), std::string::npos);
  // 1% of 4 triangles rounds up to one: the sliver.
  const std::string red = path_data(svg, "fill=\"#e02020\"");
  EXPECT_EQ(count(red, "M"), 1u);
  EXPECT_EQ(count(red, "Z"), 1u);
  // The sliver 0-1-4 starts at point 0, drawn at the bottom-left margin corner.
  EXPECT_EQ(red.rfind("M10.00 990.00", 0), 0u) << red;
  // Thin edges: the 4 interior edges; thick: the 4 segments.
  EXPECT_EQ(count(path_data(svg, "stroke-width=\"0.4\""), "M"), 4u);
  EXPECT_EQ(count(path_data(svg, "stroke-width=\"1.6\""), "M"), 4u);
  EXPECT_NE(svg.find("4 triangles"), std::string::npos);

  SvgOptions half;
  half.worst_fraction = 0.5;
  ASSERT_TRUE(write_svg(dir / "half.svg", mesh, half));
  EXPECT_EQ(count(path_data(test::read_file(dir / "half.svg"), "fill=\"#e02020\""), "M"), 2u);

  SvgOptions bad;
  bad.worst_fraction = 2.0;
  auto refused = write_svg(dir / "bad.svg", mesh, bad);
  ASSERT_FALSE(refused);
  EXPECT_EQ(refused.error().code, ErrorCode::InvalidOption);
}

TEST(SvgWriter, EmptyMeshStillGivesAValidPicture) {
  test::ScratchDir dir("svg");
  ASSERT_TRUE(write_svg(dir / "empty.svg", TriangleMesh{}));
  EXPECT_NE(test::read_file(dir / "empty.svg").find("0 triangles"), std::string::npos);
}

}  // namespace
}  // namespace delmesh
