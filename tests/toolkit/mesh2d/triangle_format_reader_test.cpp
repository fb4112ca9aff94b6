// Tests of the Triangle .node/.poly reader: good inputs in the forms real files take
// (comments, blank lines, 0- and 1-based numbering, attributes, markers, holes, regions,
// a .poly whose vertices live in the sibling .node) and bad inputs, each of which must be
// refused with an Error naming the file and the line.
#include "toolkit/mesh2d/triangle_format_reader.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <string>

#include "tests/support/scratch_dir.h"
#include "tests/support/test_paths.h"

namespace delmesh {
namespace {

constexpr const char* kBoxPoly =
    "# a square with a square hole\n"
    "8 2 1 1   # header\n"
    "\n"
    "1 0 0 10.5 1\n"
    "2 3 0 11 1\n"
    "3 3 3 12 1\n"
    "4 0 3 13 33  # a special marker\n"
    "5 1 1 0 0\n"
    "6 2 1 0 0\n"
    "7 2 2 0 0\n"
    "8 1 2 0 0\n"
    "8 1\n"
    "1 1 2 5\n"
    "2 2 3 5\n"
    "3 3 4 5\n"
    "4 4 1 5\n"
    "5 5 6 0\n"
    "6 6 7 0\n"
    "7 7 8 -2\n"
    "8 8 5 0\n"
    "1\n"
    "1 1.5 1.5\n"
    "2\n"
    "1 0.5 0.5 7 0.25\n"
    "2 2.5 2.5 -3\n";

Error parse_error(std::string_view text) {
  auto result = parse_triangle_poly(text, "bad.poly");
  EXPECT_FALSE(result.has_value()) << "accepted:\n" << text;
  if (result) return make_error(ErrorCode::InvalidInput, "unexpectedly accepted");
  return result.error();
}

Error node_error(std::string_view text) {
  auto result = parse_triangle_node(text, "bad.node");
  EXPECT_FALSE(result.has_value()) << "accepted:\n" << text;
  if (result) return make_error(ErrorCode::InvalidInput, "unexpectedly accepted");
  return result.error();
}

void expect_at(const Error& e, std::string_view file, std::size_t line) {
  ASSERT_TRUE(e.location.has_value()) << e.describe();
  EXPECT_EQ(e.location->file, file) << e.describe();
  EXPECT_EQ(e.location->line, line) << e.describe();
  EXPECT_NE(e.describe().find(std::string(file) + ":" + std::to_string(line) + ": "), std::string::npos)
      << e.describe();
}

TEST(TriangleFormatReader, ReadsFullPolyWithCommentsAttributesMarkersHolesRegions) {
  auto input = parse_triangle_poly(kBoxPoly, "box.poly");
  ASSERT_TRUE(input) << input.error().describe();
  const Pslg& p = input->pslg;
  EXPECT_EQ(input->first_index, 1);
  EXPECT_TRUE(input->has_segment_section);
  ASSERT_EQ(p.points.size(), 8u);
  EXPECT_EQ(p.points[2], (Point2{3, 3}));
  EXPECT_EQ(p.num_point_attributes, 1);
  ASSERT_EQ(p.point_attributes.size(), 8u);
  EXPECT_EQ(p.point_attributes[0], 10.5);
  ASSERT_EQ(p.point_markers.size(), 8u);
  EXPECT_EQ(p.point_markers[3], 33);
  EXPECT_EQ(p.point_markers[4], 0);
  ASSERT_EQ(p.segments.size(), 8u);
  EXPECT_EQ(p.segments[0], (std::array<std::uint32_t, 2>{0, 1}));
  EXPECT_EQ(p.segments[7], (std::array<std::uint32_t, 2>{7, 4}));
  ASSERT_EQ(p.segment_markers.size(), 8u);
  EXPECT_EQ(p.segment_markers[6], -2);
  ASSERT_EQ(p.holes.size(), 1u);
  EXPECT_EQ(p.holes[0], (Point2{1.5, 1.5}));
  ASSERT_EQ(p.regions.size(), 2u);
  EXPECT_EQ(p.regions[0].point, (Point2{0.5, 0.5}));
  EXPECT_EQ(p.regions[0].attribute, 7.0);
  EXPECT_EQ(p.regions[0].max_area, 0.25);
  // With one value after the coordinates, Triangle uses it as attribute and area bound.
  EXPECT_EQ(p.regions[1].attribute, -3.0);
  EXPECT_EQ(p.regions[1].max_area, -3.0);
}

TEST(TriangleFormatReader, ZeroBasedNumberingIsDetectedFromTheFirstVertex) {
  auto input = parse_triangle_poly("3 2 0 0\n0 0 0\n1 1 0\n2 0 1\n3 0\n0 0 1\n1 1 2\n2 2 0\n0\n", "z.poly");
  ASSERT_TRUE(input) << input.error().describe();
  EXPECT_EQ(input->first_index, 0);
  ASSERT_EQ(input->pslg.segments.size(), 3u);
  EXPECT_EQ(input->pslg.segments[2], (std::array<std::uint32_t, 2>{2, 0}));
  EXPECT_TRUE(input->pslg.point_markers.empty());
  EXPECT_TRUE(input->pslg.segment_markers.empty());
  EXPECT_TRUE(input->pslg.regions.empty());
}

TEST(TriangleFormatReader, PolyEndingAfterTheSegmentsHasNoHoles) {
  auto input = parse_triangle_poly("3 2 0 0\n1 0 0\n2 1 0\n3 0 1\n1 0\n1 1 2\n# end\n", "cgal.poly");
  ASSERT_TRUE(input) << input.error().describe();
  EXPECT_EQ(input->pslg.segments.size(), 1u);
  EXPECT_TRUE(input->pslg.holes.empty());
}

TEST(TriangleFormatReader, ShortHeadersCrlfSignsAndExponents) {
  auto input = parse_triangle_node("3\r\n1 +1.5e2 -2E-3\r\n2\t0\t.5\r\n3 -0 1e+1\r\n", "short.node");
  ASSERT_TRUE(input) << input.error().describe();
  const auto& pts = input->pslg.points;
  ASSERT_EQ(pts.size(), 3u);
  EXPECT_EQ(pts[0], (Point2{150.0, -0.002}));
  EXPECT_EQ(pts[1], (Point2{0.0, 0.5}));
  EXPECT_EQ(pts[2], (Point2{0.0, 10.0}));
  EXPECT_FALSE(input->has_segment_section);
}

TEST(TriangleFormatReader, PolyWithoutVerticesReadsTheSiblingNodeFile) {
  test::ScratchDir dir("reader");
  dir.write("mesh.node", "# points\n4 2 0 1\n0 0 0 1\n1 1 0 1\n2 1 1 2\n3 0 1 1\n");
  const auto poly = dir.write("mesh.poly", "0 2 0 1\n4 1\n0 0 1 3\n1 1 2 3\n2 2 3 3\n3 3 0 4\n0\n");
  auto input = read_triangle_poly(poly);
  ASSERT_TRUE(input) << input.error().describe();
  EXPECT_EQ(input->first_index, 0);
  EXPECT_EQ(input->node_file, (dir / "mesh.node").string());
  ASSERT_EQ(input->pslg.points.size(), 4u);
  EXPECT_EQ(input->pslg.point_markers[2], 2);
  ASSERT_EQ(input->pslg.segments.size(), 4u);
  EXPECT_EQ(input->pslg.segments[3], (std::array<std::uint32_t, 2>{3, 0}));
  EXPECT_EQ(input->pslg.segment_markers[3], 4);

  auto dispatched = read_triangle_input(poly);
  ASSERT_TRUE(dispatched) << dispatched.error().describe();
  EXPECT_EQ(dispatched->pslg.segments.size(), 4u);
}

TEST(TriangleFormatReader, PolyWithoutVerticesAndWithoutSiblingIsAnIoErrorNamingTheNodeFile) {
  test::ScratchDir dir("reader");
  const auto poly = dir.write("lonely.poly", "0 2 0 0\n0 0\n0\n");
  auto input = read_triangle_poly(poly);
  ASSERT_FALSE(input);
  EXPECT_EQ(input.error().code, ErrorCode::IoError);
  EXPECT_NE(input.error().describe().find("lonely.node"), std::string::npos) << input.error().describe();

  auto in_memory = parse_triangle_poly("0 2 0 0\n0 0\n0\n", "mem.poly");
  ASSERT_FALSE(in_memory);
  expect_at(in_memory.error(), "mem.poly", 1);
}

TEST(TriangleFormatReader, ErrorsInTheSiblingNodeNameTheNodeFile) {
  test::ScratchDir dir("reader");
  dir.write("m.node", "2 2 0 0\n1 0 0\n2 nan 1\n");
  auto input = read_triangle_poly(dir.write("m.poly", "0 2 0 0\n0 0\n0\n"));
  ASSERT_FALSE(input);
  expect_at(input.error(), (dir / "m.node").string(), 3);
}

TEST(TriangleFormatReader, MissingFileDirectoryAndUnknownExtension) {
  test::ScratchDir dir("reader");
  auto missing = read_triangle_node(dir / "none.node");
  ASSERT_FALSE(missing);
  EXPECT_EQ(missing.error().code, ErrorCode::IoError);
  EXPECT_NE(missing.error().describe().find("none.node"), std::string::npos);

  std::filesystem::create_directories(dir / "folder.poly");
  auto folder = read_triangle_poly(dir / "folder.poly");
  ASSERT_FALSE(folder);
  EXPECT_EQ(folder.error().code, ErrorCode::IoError);

  auto other = read_triangle_input(dir.write("x.ele", "1 3 0\n1 1 2 3\n"));
  ASSERT_FALSE(other);
  EXPECT_EQ(other.error().code, ErrorCode::Unsupported);
}

TEST(TriangleFormatReader, MalformedNumbersAreParseErrorsAtTheirLine) {
  Error e = parse_error("3 2 0 0\n1 0 0\n2 1 abc\n3 0 1\n0 0\n0\n");
  EXPECT_EQ(e.code, ErrorCode::ParseError);
  expect_at(e, "bad.poly", 3);
  EXPECT_NE(e.message.find("'abc'"), std::string::npos) << e.message;

  e = parse_error("3 2 0 0\n1 0 0\n2 1 0.5x\n3 0 1\n0 0\n0\n");
  expect_at(e, "bad.poly", 3);
  e = parse_error("3 2 0 0\n1.0 0 0\n2 1 0\n3 0 1\n0 0\n0\n");
  expect_at(e, "bad.poly", 2);
  e = parse_error("three 2 0 0\n");
  expect_at(e, "bad.poly", 1);
}

TEST(TriangleFormatReader, NonFiniteCoordinatesAreRefused) {
  for (const char* bad : {"nan", "-inf", "inf", "1e999", "NaN"}) {
    Error e = node_error(std::string("# c\n2 2 0 0\n1 0 0\n2 ") + bad + " 1\n");
    EXPECT_EQ(e.code, ErrorCode::InvalidInput) << bad;
    expect_at(e, "bad.node", 4);
    EXPECT_NE(e.message.find("finite"), std::string::npos) << e.message;
  }
  Error hole = parse_error("3 2 0 0\n1 0 0\n2 1 0\n3 0 1\n0 0\n1\n1 inf 0\n");
  expect_at(hole, "bad.poly", 7);
  Error region = parse_error("3 2 0 0\n1 0 0\n2 1 0\n3 0 1\n0 0\n0\n1\n1 0.2 0.2 1 nan\n");
  expect_at(region, "bad.poly", 8);
}

TEST(TriangleFormatReader, WrongFieldCountsAreRefused) {
  Error few = node_error("2 2 1 1\n1 0 0 5 1\n2 1 0 1\n");
  EXPECT_EQ(few.code, ErrorCode::ParseError);
  expect_at(few, "bad.node", 3);
  EXPECT_NE(few.message.find("has 4 fields; the header asks for 5"), std::string::npos) << few.message;

  Error many = node_error("2 2 0 0\n1 0 0\n2 1 0 7\n");
  expect_at(many, "bad.node", 3);

  Error segment = parse_error("3 2 0 0\n1 0 0\n2 1 0\n3 0 1\n2 1\n1 1 2 0\n2 2 3\n0\n");
  expect_at(segment, "bad.poly", 7);

  Error hole = parse_error("3 2 0 0\n1 0 0\n2 1 0\n3 0 1\n0 0\n1\n1 0.5\n");
  expect_at(hole, "bad.poly", 7);

  Error region = parse_error("3 2 0 0\n1 0 0\n2 1 0\n3 0 1\n0 0\n0\n1\n1 0.5 0.5\n");
  expect_at(region, "bad.poly", 8);

  Error header = node_error("2 2 0 0 9\n1 0 0\n2 1 0\n");
  expect_at(header, "bad.node", 1);
}

TEST(TriangleFormatReader, DuplicateAndOutOfSequenceVertexIdsAreRefused) {
  Error dup = node_error("3 2 0 0\n1 0 0\n2 1 0\n2 0 1\n");
  EXPECT_EQ(dup.code, ErrorCode::InvalidInput);
  expect_at(dup, "bad.node", 4);
  EXPECT_NE(dup.message.find("duplicate vertex id 2"), std::string::npos) << dup.message;
  ASSERT_EQ(dup.entity_ids.size(), 1u);
  EXPECT_EQ(dup.entity_ids[0], 2u);

  Error gap = node_error("3 2 0 0\n1 0 0\n2 1 0\n4 0 1\n");
  expect_at(gap, "bad.node", 4);
  EXPECT_NE(gap.message.find("out of sequence"), std::string::npos) << gap.message;

  Error first = node_error("2 2 0 0\n5 0 0\n6 1 0\n");
  expect_at(first, "bad.node", 2);
}

TEST(TriangleFormatReader, SegmentsNamingMissingVerticesOrJoiningAVertexToItself) {
  Error missing = parse_error("3 2 0 0\n1 0 0\n2 1 0\n3 0 1\n3 0\n1 1 2\n2 2 4\n3 3 1\n0\n");
  EXPECT_EQ(missing.code, ErrorCode::InvalidInput);
  expect_at(missing, "bad.poly", 7);
  EXPECT_NE(missing.message.find("vertex 4"), std::string::npos) << missing.message;
  EXPECT_NE(missing.message.find("1..3"), std::string::npos) << missing.message;
  ASSERT_EQ(missing.entity_ids.size(), 1u);
  EXPECT_EQ(missing.entity_ids[0], 1u);

  // 0 names no vertex in a 1-based file.
  Error zero = parse_error("3 2 0 0\n1 0 0\n2 1 0\n3 0 1\n1 0\n1 0 2\n0\n");
  expect_at(zero, "bad.poly", 6);

  Error loop = parse_error("3 2 0 0\n1 0 0\n2 1 0\n3 0 1\n1 0\n1 2 2\n0\n");
  EXPECT_EQ(loop.code, ErrorCode::DegenerateInput);
  expect_at(loop, "bad.poly", 6);
}

TEST(TriangleFormatReader, NegativeCountsAreRefused) {
  expect_at(node_error("-1 2 0 0\n"), "bad.node", 1);
  expect_at(node_error("1 2 -1 0\n1 0 0\n"), "bad.node", 1);
  expect_at(parse_error("1 2 0 0\n1 0 0\n-2 0\n"), "bad.poly", 3);
  expect_at(parse_error("1 2 0 0\n1 0 0\n0 0\n-1\n"), "bad.poly", 4);
  expect_at(parse_error("1 2 0 0\n1 0 0\n0 0\n0\n-3\n"), "bad.poly", 5);
}

TEST(TriangleFormatReader, AbsurdCountsFailAtTheEndOfTheFileWithoutAllocatingForThem) {
  // A count near the 32-bit id limit with three vertices present: reading must stop at the
  // end of the text with an error, having reserved storage only for what the text holds.
  Error e = node_error("4000000000 2 0 0\n1 0 0\n2 1 0\n3 0 1\n");
  EXPECT_EQ(e.code, ErrorCode::ParseError);
  expect_at(e, "bad.node", 4);
  EXPECT_NE(e.message.find("3 of 4000000000"), std::string::npos) << e.message;

  Error huge_attributes = node_error("1 2 2000000000 0\n1 0 0\n");
  expect_at(huge_attributes, "bad.node", 1);
  EXPECT_NE(huge_attributes.message.find("supported maximum"), std::string::npos) << huge_attributes.message;

  // One line of 200,000 fields: refused, keeping at most TextLines::kMaxFields + 1 of them.
  std::string long_line = "1 2 0 0\n1";
  for (int i = 0; i < 200000; ++i) long_line += " 0";
  Error wide = node_error(long_line + "\n");
  expect_at(wide, "bad.node", 2);
  EXPECT_NE(wide.message.find("more than 65536 fields"), std::string::npos) << wide.message;

  Error too_many = node_error("99999999999999 2 0 0\n1 0 0\n");
  expect_at(too_many, "bad.node", 1);
  Error overflow = node_error("999999999999999999999999 2 0 0\n1 0 0\n");
  expect_at(overflow, "bad.node", 1);
}

TEST(TriangleFormatReader, TruncatedFilesNameTheLastLineAndTheMissingSection) {
  Error vertices = parse_error("4 2 0 0\n1 0 0\n2 1 0\n");
  expect_at(vertices, "bad.poly", 3);
  EXPECT_NE(vertices.message.find("2 of 4 vertices"), std::string::npos) << vertices.message;

  Error no_segments = parse_error("3 2 0 0\n1 0 0\n2 1 0\n3 0 1\n# end\n");
  expect_at(no_segments, "bad.poly", 5);
  EXPECT_NE(no_segments.message.find("segments"), std::string::npos) << no_segments.message;

  Error segments = parse_error("3 2 0 0\n1 0 0\n2 1 0\n3 0 1\n3 0\n1 1 2\n");
  expect_at(segments, "bad.poly", 6);
  Error holes = parse_error("3 2 0 0\n1 0 0\n2 1 0\n3 0 1\n0 0\n2\n1 0.1 0.1\n");
  expect_at(holes, "bad.poly", 7);
  Error regions = parse_error("3 2 0 0\n1 0 0\n2 1 0\n3 0 1\n0 0\n0\n2\n1 0.1 0.1 1 1\n");
  expect_at(regions, "bad.poly", 8);
  Error empty = node_error("# only a comment\n\n");
  EXPECT_EQ(empty.code, ErrorCode::ParseError);
  EXPECT_NE(empty.describe().find("bad.node"), std::string::npos);
}

TEST(TriangleFormatReader, HeaderValuesOutOfRangeAndTrailingData) {
  expect_at(node_error("1 3 0 0\n1 0 0 0\n"), "bad.node", 1);
  expect_at(node_error("1 2 0 2\n1 0 0 0\n"), "bad.node", 1);
  expect_at(parse_error("1 2 0 0\n1 0 0\n0 7\n0\n"), "bad.poly", 3);
  expect_at(node_error("1 2 0 0\n1 0 0\n1 0 0\n"), "bad.node", 3);
  expect_at(parse_error("1 2 0 0\n1 0 0\n0 0\n0\n0\n5 5\n"), "bad.poly", 6);
}

TEST(TriangleFormatReader, CorpusFilesParseWithTheirManifestCounts) {
  struct Expect {
    const char* file;
    std::size_t vertices, segments, holes;
  };
  for (const Expect& c : {Expect{"drufat-a.poly", 29, 29, 1}, Expect{"drufat-box.poly", 8, 5, 1},
                          Expect{"drufat-face.poly", 26, 22, 3}, Expect{"drufat-dots.node", 100, 0, 0},
                          Expect{"cgal-fish-and-rectangle.poly", 31, 44, 3},
                          Expect{"p2t-dude.poly", 104, 104, 2}}) {
    auto input = read_triangle_input(test::corpus_dir() / "poly2d" / c.file);
    ASSERT_TRUE(input) << input.error().describe();
    EXPECT_EQ(input->pslg.points.size(), c.vertices) << c.file;
    EXPECT_EQ(input->pslg.segments.size(), c.segments) << c.file;
    EXPECT_EQ(input->pslg.holes.size(), c.holes) << c.file;
  }
}

// Random byte edits of a valid file must never crash the reader, and every refusal must
// carry a location in the file.
TEST(TriangleFormatReader, RandomCorruptionsNeverCrashAndAlwaysLocateTheError) {
  const std::string original = kBoxPoly;
  const std::string alphabet = "0123456789 .-+eE#\nnaix\t";
  std::mt19937 rng(12345);
  int refused = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    std::string text = original;
    const int edits = 1 + static_cast<int>(rng() % 4);
    for (int k = 0; k < edits; ++k) {
      const std::size_t at = rng() % text.size();
      switch (rng() % 3) {
        case 0: text[at] = alphabet[rng() % alphabet.size()]; break;
        case 1: text.erase(at, 1 + rng() % 8); break;
        default: text.insert(at, 1, alphabet[rng() % alphabet.size()]); break;
      }
      if (text.empty()) text.push_back('x');
    }
    auto result = parse_triangle_poly(text, "fuzz.poly");
    if (result) {
      const Pslg& p = result->pslg;
      for (const auto& s : p.segments) {
        ASSERT_LT(s[0], p.points.size());
        ASSERT_LT(s[1], p.points.size());
        ASSERT_NE(s[0], s[1]);
      }
    } else {
      ++refused;
      ASSERT_TRUE(result.error().location.has_value()) << result.error().describe();
      EXPECT_EQ(result.error().location->file, "fuzz.poly");
    }
  }
  EXPECT_GT(refused, 1000);
}

}  // namespace
}  // namespace delmesh
