// TetGen .node/.poly/.smesh reading and writing: corpus files, round trips, and malformed
// inputs that must give a located error (never a crash).
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <string>

#include "importers/tetgen/tetgen_reader.h"
#include "importers/tetgen/tetgen_writer.h"
#include "tests/support/test_paths.h"
#include "toolkit/plc/plc_validate.h"

namespace delmesh {
namespace {

// A cube with a square hole through its top facet's polygon list, a volume hole, two
// regions, point markers and one free segment; 1-based like most TetGen files.
constexpr const char* kPoly = R"(# test PLC
10 3 0 1
1 0 0 0 5
2 1 0 0 5
3 1 1 0 5
4 0 1 0 5
5 0 0 1 6
6 1 0 1 6
7 1 1 1 6
8 0 1 1 6
9 0.25 0.25 0.5 0
10 0.75 0.75 0.5 0
7 1
1 0 10
4 1 2 3 4
1 0 20
4 5 6 7 8
1 0 30
4 1 2 6 5
1 0 30
4 2 3 7 6
1 0 30
4 3 4 8 7
2 1 40   # two polygons and a hole point
4 4 1 5 8
4 4 1 5 8
1 0 0.5 0.5
1 0 -7
2 9 10
1
1 5 5 5
2
1 0.5 0.5 0.25 3 0.125
2 0.5 0.5 0.75 4
)";

bool same_plc(const Plc& a, const Plc& b) {
  if (a.points != b.points || a.point_markers != b.point_markers) return false;
  if (a.facets.size() != b.facets.size() || a.segments.size() != b.segments.size()) return false;
  for (std::size_t f = 0; f < a.facets.size(); ++f) {
    if (a.facets[f].polygons != b.facets[f].polygons || a.facets[f].holes != b.facets[f].holes ||
        a.facets[f].marker != b.facets[f].marker) {
      return false;
    }
  }
  for (std::size_t s = 0; s < a.segments.size(); ++s) {
    if (a.segments[s].a != b.segments[s].a || a.segments[s].b != b.segments[s].b ||
        a.segments[s].marker != b.segments[s].marker) {
      return false;
    }
  }
  if (a.holes != b.holes || a.regions.size() != b.regions.size()) return false;
  for (std::size_t r = 0; r < a.regions.size(); ++r) {
    if (a.regions[r].point != b.regions[r].point || a.regions[r].id != b.regions[r].id ||
        a.regions[r].max_volume != b.regions[r].max_volume) {
      return false;
    }
  }
  return true;
}

TEST(TetgenReader, ReadsPolyWithHolesRegionsMarkersAndSegments) {
  const auto plc = parse_tetgen(kPoly, TetgenFileKind::Poly, "test.poly");
  ASSERT_TRUE(plc) << plc.error().describe();
  EXPECT_EQ(plc->points.size(), 10u);
  EXPECT_EQ(plc->point_markers, (std::vector<int>{5, 5, 5, 5, 6, 6, 6, 6, 0, 0}));
  ASSERT_EQ(plc->facets.size(), 6u);  // the 2-vertex facet became a segment
  EXPECT_EQ(plc->facets[0].polygons[0], (Plc::Polygon{0, 1, 2, 3}));
  EXPECT_EQ(plc->facets[0].marker, 10);
  EXPECT_EQ(plc->facets[5].polygons.size(), 2u);
  EXPECT_EQ(plc->facets[5].holes.size(), 1u);
  EXPECT_EQ(plc->facets[5].marker, 40);
  ASSERT_EQ(plc->segments.size(), 1u);
  EXPECT_EQ(plc->segments[0].a, 8u);
  EXPECT_EQ(plc->segments[0].marker, -7);
  EXPECT_EQ(plc->holes, (std::vector<Vec3>{Vec3(5, 5, 5)}));
  ASSERT_EQ(plc->regions.size(), 2u);
  EXPECT_EQ(plc->regions[0].id, 3);
  EXPECT_EQ(plc->regions[0].max_volume, 0.125);
  EXPECT_EQ(plc->regions[1].id, 4);
  EXPECT_EQ(plc->regions[1].max_volume, -1.0);
}

TEST(TetgenWriter, PolyRoundTripIsExact) {
  auto plc = parse_tetgen(kPoly, TetgenFileKind::Poly, "test.poly");
  ASSERT_TRUE(plc);
  plc->points[8] = Vec3(0.1, 1.0 / 3.0, 0x1.fffffffffffffp-2);  // needs all 17 digits
  const auto text = format_tetgen_poly(*plc);
  ASSERT_TRUE(text);
  const auto back = parse_tetgen(*text, TetgenFileKind::Poly, "round.poly");
  ASSERT_TRUE(back) << back.error().describe();
  EXPECT_TRUE(same_plc(*plc, *back));
}

TEST(TetgenWriter, NamesAndColoursRoundTripThroughCommentTables) {
  auto plc = parse_tetgen(kPoly, TetgenFileKind::Poly, "test.poly");
  ASSERT_TRUE(plc);
  EXPECT_TRUE(plc->facet_marker_names.empty());
  plc->facet_marker_names = {{1, "bottom face"}, {2, "say \"top\""}};
  plc->facet_marker_colors = {{2, {1.0, 0.0, 0.0}}, {7, {0.2, 0.4, 0.6}}};
  plc->region_names = {{3, "steel"}};
  plc->region_colors = {{4, {0.0, 0.0, 1.0}}};
  for (const bool smesh : {false, true}) {
    Plc source = *plc;
    if (smesh) source.facets.pop_back();  // the facet with a hole: not expressible in .smesh
    const auto text = smesh ? format_tetgen_smesh(source) : format_tetgen_poly(source);
    ASSERT_TRUE(text);
    EXPECT_NE(text->find("# facet_marker 2 name \"say  top \" color #ff0000\n"), std::string::npos) << *text;
    const auto back = parse_tetgen(*text, smesh ? TetgenFileKind::Smesh : TetgenFileKind::Poly, "round");
    ASSERT_TRUE(back) << back.error().describe();
    EXPECT_TRUE(same_plc(source, *back));
    EXPECT_EQ(back->facet_marker_names, (std::map<int, std::string>{{1, "bottom face"}, {2, "say  top "}}));
    EXPECT_EQ(back->region_names, plc->region_names);
    ASSERT_EQ(back->facet_marker_colors.size(), 2u);
    EXPECT_EQ(back->facet_marker_colors.at(2).r, 1.0);
    EXPECT_EQ(back->facet_marker_colors.at(7).g, 102 / 255.0);  // 0.4 written as byte 102
    ASSERT_EQ(back->region_colors.size(), 1u);
    EXPECT_EQ(back->region_colors.at(4).b, 1.0);
  }
  // Comments of another form are ordinary comments.
  const std::string other = std::string(kPoly) +
                            "# facet_marker 5\n# facet_marker x name \"a\"\n# region 1 name \"open\n"
                            "# region 2 color #12345\n#facet_marker 3 name \"b\"\n# facet_marker 4 name \"c\" extra\n";
  const auto plain = parse_tetgen(other, TetgenFileKind::Poly, "other.poly");
  ASSERT_TRUE(plain) << plain.error().describe();
  EXPECT_TRUE(plain->facet_marker_names.empty());
  EXPECT_TRUE(plain->region_names.empty());
  EXPECT_TRUE(plain->region_colors.empty());
}

TEST(TetgenWriter, SmeshRefusesFacetsWithHolesButRoundTripsSimpleOnes) {
  const auto plc = parse_tetgen(kPoly, TetgenFileKind::Poly, "test.poly");
  ASSERT_TRUE(plc);
  const auto refused = format_tetgen_smesh(*plc);
  ASSERT_FALSE(refused);
  EXPECT_EQ(refused.error().code, ErrorCode::Unsupported);
  EXPECT_NE(refused.error().message.find("facet 5"), std::string::npos);
  Plc simple = *plc;
  simple.facets.pop_back();
  const auto text = format_tetgen_smesh(simple);
  ASSERT_TRUE(text);
  const auto back = parse_tetgen(*text, TetgenFileKind::Smesh, "round.smesh");
  ASSERT_TRUE(back) << back.error().describe();
  EXPECT_TRUE(same_plc(simple, *back));
  EXPECT_FALSE(format_off(*plc));
  const auto off = format_off(simple);
  ASSERT_TRUE(off);
  EXPECT_EQ(off->rfind("OFF\n10 5 0\n", 0), 0u);
}

TEST(TetgenReader, CorpusSmeshFilesReadValidateAndRoundTrip) {
  struct Expect {
    const char* file;
    std::size_t nodes, facets;
  };
  const Expect files[] = {{"td-slit-1.smesh", 14, 13},   {"td-slit-10.smesh", 14, 13},
                          {"td-slit-5.smesh", 14, 13},   {"td-spike-10-4.smesh", 5, 5},
                          {"td-spike-5-7.smesh", 8, 8},  {"td-wedge-10.smesh", 6, 5},
                          {"td-wedge-5.smesh", 6, 5}};
  std::size_t seen = 0;
  for (const auto& entry : std::filesystem::directory_iterator(test::corpus_dir() / "poly3d")) {
    ++seen;
    const std::string name = entry.path().filename().string();
    const auto plc = read_tetgen(entry.path());
    ASSERT_TRUE(plc) << name << ": " << plc.error().describe();
    bool listed = false;
    for (const auto& e : files) {
      if (name != e.file) continue;
      listed = true;
      EXPECT_EQ(plc->points.size(), e.nodes) << name;
      EXPECT_EQ(plc->facets.size(), e.facets) << name;
    }
    EXPECT_TRUE(listed) << name << " is not in the expected list";
    for (const auto& issue : validate_plc(*plc)) ADD_FAILURE() << name << ": " << issue.message;
    const auto text = format_tetgen_smesh(*plc);
    ASSERT_TRUE(text) << name;
    const auto back = parse_tetgen(*text, TetgenFileKind::Smesh, name);
    ASSERT_TRUE(back) << name;
    EXPECT_TRUE(same_plc(*plc, *back)) << name;
  }
  EXPECT_EQ(seen, std::size(files));
}

TEST(TetgenReader, EmptyNodeListReadsSiblingNodeFile) {
  const auto dir = std::filesystem::temp_directory_path() / ("delmesh_tetgen_node_test_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  {
    std::ofstream(dir / "tet.node") << "4 3 0 0\n0 0 0 0\n1 1 0 0\n2 0 1 0\n3 0 0 1\n";
    std::ofstream(dir / "tet.poly") << "0 3 0 0\n4 0\n1\n3 0 1 2\n1\n3 0 1 3\n1\n3 1 2 3\n1\n3 0 2 3\n0\n";
  }
  const auto plc = read_tetgen(dir / "tet.poly");
  ASSERT_TRUE(plc) << plc.error().describe();
  EXPECT_EQ(plc->points.size(), 4u);
  EXPECT_EQ(plc->facets.size(), 4u);
  EXPECT_EQ(plc->facets[3].polygons[0], (Plc::Polygon{0, 2, 3}));  // 0-based from the .node
  EXPECT_TRUE(validate_plc(*plc).empty());
  const auto nodes = read_tetgen(dir / "tet.node");
  ASSERT_TRUE(nodes);
  EXPECT_EQ(nodes->points.size(), 4u);
  std::filesystem::remove_all(dir);
}

struct BadInput {
  const char* text;
  std::size_t line;
  const char* message_part;
};

TEST(TetgenReader, MalformedInputsGiveLocatedErrors) {
  const BadInput cases[] = {
      {"", 0, "end of file"},
      {"4 2 0 0\n", 1, "dimension is 2"},
      {"2 3 0 0\n1 0 0 0\n", 2, "end of file"},
      {"1 3 0 0\n1 0 zero 0\n", 2, "found 'zero'"},
      {"1 3 0 0\n7 0 0 0\n", 2, "expected 0 or 1"},
      {"2 3 0 0\n0 0 0 0\n5 1 0 0\n", 3, "expected 1"},
      {"1 3 0 0\n0 nan 0 0\n", 2, "finite"},
      {"-3 3 0 0\n", 1, "negative"},
      {"1000000000000000000 3 0 0\n0 0 0 0\n", 0, "end of file"},
      {"3 3 0 0\n0 0 0 0\n1 1 0 0\n2 0 1 0\n1 0\n1\n3 0 1 3\n", 7, "names vertex 3"},
      {"3 3 0 0\n0 0 0 0\n1 1 0 0\n2 0 1 0\n1 0\n1 0\n4 0 1 2\n", 7, "end of file"},
      {"3 3 0 0\n0 0 0 0\n1 1 0 0\n2 0 1 0\n1 0\n1 0\n3 0 1 2\n1\n", 8, "end of file"},
      {"3 3 0 0\n0 0 0 0\n1 1 0 0\n2 0 1 0\n1 0\n1 0\n3 0 1 2\n0\n1\n0 1 1 1 0.5\n", 10,
       "not an integer"},
      {"3 3 0 0\n0 0 0 0\n1 1 0 0\n2 0 1 0\n0 0\n0\n0\nextra\n", 8, "unexpected data"},
      {"0 3 0 0\n", 1, "no .node file"},
  };
  for (const auto& c : cases) {
    const auto plc = parse_tetgen(c.text, TetgenFileKind::Poly, "bad.poly");
    ASSERT_FALSE(plc) << c.text;
    const Error& e = plc.error();
    EXPECT_NE(e.message.find(c.message_part), std::string::npos) << c.text << " -> " << e.describe();
    if (c.line > 0) {
      ASSERT_TRUE(e.location.has_value()) << c.text;
      EXPECT_EQ(e.location->file, "bad.poly");
      EXPECT_EQ(e.location->line, c.line) << c.text << " -> " << e.describe();
    }
  }
  const auto smesh = parse_tetgen("3 3 0 0\n0 0 0 0\n1 1 0 0\n2 0 1 0\n1 0\n3 0 1\n",
                                  TetgenFileKind::Smesh, "bad.smesh");
  ASSERT_FALSE(smesh);
  EXPECT_EQ(smesh.error().location->line, 6u);
  const auto missing = read_tetgen("/nonexistent/delmesh.poly");
  ASSERT_FALSE(missing);
  EXPECT_EQ(missing.error().code, ErrorCode::IoError);
}

// The reader names the value it was reading (point, coordinate, facet, polygon, corner)
// only when it reports an error: the whole messages, as they read with eager names.
TEST(TetgenReader, ErrorMessagesNameTheValueRead) {
  const std::string nodes = "3 3 0 0\n0 0 0 0\n1 1 0 0\n2 0 1 0\n";
  const std::pair<std::string, std::string> cases[] = {
      {"2 3 0 0\n0 0 0 0\n", "unexpected end of file, expected point 1"},
      {"1 3 0 0\n0 0 nan 0\n", "expected a finite number for coordinate y, found 'nan'"},
      {"1 3 0 0\n0 0 0\n", "missing coordinate z"},
      {nodes + "2 1\n", "unexpected end of file, expected facet 0"},
      {nodes + "1 1\n1 0 x\n", "expected an integer for marker of facet 0, found 'x'"},
      {nodes + "1 0\n-1\n", "number of polygons of facet 0 is negative (-1)"},
      {nodes + "1 0\n1 y\n", "expected an integer for number of holes of facet 0, found 'y'"},
      {nodes + "1 0\n1\n", "unexpected end of file, expected facet 0 polygon 0"},
      {nodes + "1 0\n1\nz\n", "expected an integer for number of corners of facet 0 polygon 0, found 'z'"},
      {nodes + "1 0\n1\n3 0 1 w\n", "expected an integer for vertex number of facet 0 polygon 0, found 'w'"},
      {nodes + "1 0\n1\n4 0 1 2\n", "unexpected end of file, expected vertex number of facet 0 polygon 0"},
      {nodes + "2 0\n1\n3 0 1 2\n2\n3 0 1 2\n3 0 1 9\n",
       "facet 1 polygon 1 names vertex 9, but vertices are numbered 0..2"},
  };
  for (const auto& [text, message] : cases) {
    const auto plc = parse_tetgen(text, TetgenFileKind::Poly, "bad.poly");
    ASSERT_FALSE(plc) << text;
    EXPECT_EQ(plc.error().message, message) << text;
  }
  const auto smesh = parse_tetgen(nodes + "1 0\n3 0 1 7\n", TetgenFileKind::Smesh, "bad.smesh");
  ASSERT_FALSE(smesh);
  EXPECT_EQ(smesh.error().message, "facet 0 names vertex 7, but vertices are numbered 0..2");
}

}  // namespace
}  // namespace delmesh
