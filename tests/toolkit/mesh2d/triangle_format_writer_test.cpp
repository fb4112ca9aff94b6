// Tests of the Triangle-format writers: write -> read round trips (bit-exact coordinates,
// markers, attributes, holes, regions, 0- and 1-based numbering), the .ele and .edge
// contents, and refusal of inconsistent meshes and unwritable paths.
#include "toolkit/mesh2d/triangle_format_writer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <sstream>
#include <vector>

#include "tests/support/scratch_dir.h"
#include "toolkit/mesh2d/triangle_format_reader.h"

namespace delmesh {
namespace {

// Unit square split along its diagonal 0-2, with an interior-free layout:
//
//   3 ------ 2
//   |      / |
//   |    /   |
//   |  /     |
//   0 ------ 1
TriangleMesh square_mesh() {
  TriangleMesh mesh;
  mesh.points = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  mesh.point_markers = {1, 1, 2, 1};
  mesh.num_point_attributes = 1;
  mesh.point_attributes = {0.5, 1.0 / 3.0, -2.0, 1e-300};
  mesh.triangles = {{0, 1, 2}, {0, 2, 3}};
  mesh.triangle_attributes = {4.0, 5.5};
  mesh.segments = {{0, 1}, {1, 2}, {2, 3}, {3, 0}};
  mesh.segment_markers = {7, 7, 8, 7};
  mesh.holes = {{5.0, 5.0}};
  return mesh;
}

std::vector<std::vector<std::string>> data_lines(const std::filesystem::path& file) {
  std::istringstream in(test::read_file(file));
  std::vector<std::vector<std::string>> rows;
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream fields(line);
    std::vector<std::string> row;
    for (std::string f; fields >> f;) row.push_back(f);
    if (!row.empty()) rows.push_back(row);
  }
  return rows;
}

TEST(TriangleFormatWriter, NodeAndPolyRoundTripThroughTheReader) {
  test::ScratchDir dir("writer");
  const TriangleMesh mesh = square_mesh();
  ASSERT_TRUE(write_triangle_node(dir / "sq.node", mesh));
  ASSERT_TRUE(write_triangle_poly(dir / "sq.poly", mesh));

  // The .poly lists no vertices, so reading it goes through the sibling .node.
  auto input = read_triangle_poly(dir / "sq.poly");
  ASSERT_TRUE(input) << input.error().describe();
  EXPECT_EQ(input->first_index, 1);
  const Pslg& p = input->pslg;
  EXPECT_EQ(p.points, mesh.points);
  EXPECT_EQ(p.point_markers, mesh.point_markers);
  EXPECT_EQ(p.num_point_attributes, 1);
  EXPECT_EQ(p.point_attributes, mesh.point_attributes);  // bit-exact, including 1/3 and 1e-300
  EXPECT_EQ(p.segments, mesh.segments);
  EXPECT_EQ(p.segment_markers, mesh.segment_markers);
  EXPECT_EQ(p.holes, mesh.holes);
}

TEST(TriangleFormatWriter, EleListsCounterclockwiseTrianglesWithAttributes) {
  test::ScratchDir dir("writer");
  ASSERT_TRUE(write_triangle_ele(dir / "sq.ele", square_mesh()));
  const auto rows = data_lines(dir / "sq.ele");
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_EQ(rows[0], (std::vector<std::string>{"2", "3", "1"}));
  EXPECT_EQ(rows[1], (std::vector<std::string>{"1", "1", "2", "3", "4"}));
  EXPECT_EQ(rows[2], (std::vector<std::string>{"2", "1", "3", "4", "5.5"}));
}

TEST(TriangleFormatWriter, ZeroBasedNumberingAndNoMarkers) {
  test::ScratchDir dir("writer");
  TriangleWriteOptions options;
  options.first_index = 0;
  options.markers = false;
  TriangleMesh mesh = square_mesh();
  ASSERT_TRUE(write_triangle_node(dir / "z.node", mesh, options));
  ASSERT_TRUE(write_triangle_poly(dir / "z.poly", mesh, options));
  ASSERT_TRUE(write_triangle_ele(dir / "z.ele", mesh, options));
  auto input = read_triangle_poly(dir / "z.poly");
  ASSERT_TRUE(input) << input.error().describe();
  EXPECT_EQ(input->first_index, 0);
  EXPECT_TRUE(input->pslg.point_markers.empty());
  EXPECT_TRUE(input->pslg.segment_markers.empty());
  EXPECT_EQ(input->pslg.segments, mesh.segments);
  const auto ele = data_lines(dir / "z.ele");
  EXPECT_EQ(ele[1], (std::vector<std::string>{"0", "0", "1", "2", "4"}));

  options.first_index = 2;
  auto refused = write_triangle_node(dir / "bad.node", mesh, options);
  ASSERT_FALSE(refused);
  EXPECT_EQ(refused.error().code, ErrorCode::InvalidOption);
}

TEST(TriangleFormatWriter, EdgeFileListsEachEdgeOnceWithTriangleMarkers) {
  test::ScratchDir dir("writer");
  TriangleMesh mesh = square_mesh();
  mesh.segments = {{0, 1}, {2, 3}};  // the right and left sides carry no segment
  mesh.segment_markers = {7, 8};
  ASSERT_TRUE(write_triangle_edge(dir / "sq.edge", mesh));
  const auto rows = data_lines(dir / "sq.edge");
  ASSERT_EQ(rows.size(), 6u);
  EXPECT_EQ(rows[0], (std::vector<std::string>{"5", "1"}));
  // Sorted by (smaller id, larger id): 0-1 (segment 7), 0-2 (interior), 0-3 (boundary),
  // 1-2 (boundary), 2-3 (segment 8).
  EXPECT_EQ(rows[1], (std::vector<std::string>{"1", "1", "2", "7"}));
  EXPECT_EQ(rows[2], (std::vector<std::string>{"2", "1", "3", "0"}));
  EXPECT_EQ(rows[3], (std::vector<std::string>{"3", "1", "4", "1"}));
  EXPECT_EQ(rows[4], (std::vector<std::string>{"4", "2", "3", "1"}));
  EXPECT_EQ(rows[5], (std::vector<std::string>{"5", "3", "4", "8"}));
}

TEST(TriangleFormatWriter, PslgPolyRoundTripKeepsRegionsAndAwkwardDoubles) {
  test::ScratchDir dir("writer");
  Pslg pslg;
  pslg.points = {{0.1, -0.0}, {1e-310, 3.0}, {std::nextafter(1.0, 2.0), 1e300}, {-7.25, 0.3}};
  pslg.point_markers = {0, -4, 2, 9};
  pslg.segments = {{0, 1}, {1, 2}, {2, 3}};
  pslg.holes = {{0.25, 0.75}};
  pslg.regions = {{{0.5, 0.5}, 3.0, 0.125}, {{0.1, 0.9}, -1.0, -1.0}};
  ASSERT_TRUE(write_pslg_poly(dir / "p.poly", pslg));
  auto input = read_triangle_poly(dir / "p.poly");
  ASSERT_TRUE(input) << input.error().describe();
  const Pslg& q = input->pslg;
  ASSERT_EQ(q.points.size(), pslg.points.size());
  for (std::size_t i = 0; i < q.points.size(); ++i) {
    EXPECT_EQ(q.points[i], pslg.points[i]) << i;
    EXPECT_EQ(std::signbit(q.points[i][1]), std::signbit(pslg.points[i][1])) << i;
  }
  EXPECT_EQ(q.point_markers, pslg.point_markers);
  EXPECT_EQ(q.segments, pslg.segments);
  EXPECT_TRUE(q.segment_markers.empty());
  EXPECT_EQ(q.holes, pslg.holes);
  ASSERT_EQ(q.regions.size(), 2u);
  EXPECT_EQ(q.regions[0].point, pslg.regions[0].point);
  EXPECT_EQ(q.regions[0].attribute, 3.0);
  EXPECT_EQ(q.regions[0].max_area, 0.125);
  EXPECT_EQ(q.regions[1].max_area, -1.0);

  ASSERT_TRUE(write_pslg_node(dir / "p2.node", pslg));
  auto node = read_triangle_node(dir / "p2.node");
  ASSERT_TRUE(node) << node.error().describe();
  EXPECT_EQ(node->pslg.points, pslg.points);
}

TEST(TriangleFormatWriter, InconsistentMeshesAreRefusedBeforeAnyFileIsWritten) {
  test::ScratchDir dir("writer");
  TriangleMesh bad_index = square_mesh();
  bad_index.triangles[1][2] = 4;
  auto e = write_triangle_ele(dir / "bad.ele", bad_index);
  ASSERT_FALSE(e);
  EXPECT_EQ(e.error().code, ErrorCode::InvalidInput);
  EXPECT_EQ(e.error().entity_ids, std::vector<std::uint32_t>{1});
  EXPECT_FALSE(std::filesystem::exists(dir / "bad.ele"));

  TriangleMesh bad_markers = square_mesh();
  bad_markers.segment_markers.pop_back();
  EXPECT_FALSE(write_triangle_poly(dir / "bad.poly", bad_markers));
  TriangleMesh bad_attributes = square_mesh();
  bad_attributes.point_attributes.pop_back();
  EXPECT_FALSE(write_triangle_node(dir / "bad.node", bad_attributes));
  TriangleMesh nan_point = square_mesh();
  nan_point.points[2][0] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(write_triangle_node(dir / "nan.node", nan_point));

  Pslg bad_segment;
  bad_segment.points = {{0, 0}, {1, 0}};
  bad_segment.segments = {{0, 2}};
  EXPECT_FALSE(write_pslg_poly(dir / "bad2.poly", bad_segment));
}

TEST(TriangleFormatWriter, UnwritablePathIsAnIoErrorNamingTheFile) {
  test::ScratchDir dir("writer");
  const auto path = dir / "missing-dir" / "out.node";
  auto e = write_triangle_node(path, square_mesh());
  ASSERT_FALSE(e);
  EXPECT_EQ(e.error().code, ErrorCode::IoError);
  EXPECT_NE(e.error().describe().find(path.string()), std::string::npos) << e.error().describe();
}

}  // namespace
}  // namespace delmesh
