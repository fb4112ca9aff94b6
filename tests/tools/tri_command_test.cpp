// End-to-end tests of `delmesh tri`: the built executable is run on small inputs written
// into a scratch directory; exit codes, printed summaries, the files written and their
// contents, and error messages (file:line) are checked.
#include <sys/wait.h>

#include <gtest/gtest.h>

#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

#include "tests/support/scratch_dir.h"
#include "tests/support/test_paths.h"
#include "toolkit/mesh2d/triangle_angles.h"
#include "toolkit/mesh2d/triangle_format_reader.h"

namespace delmesh {
namespace {

// A 4 x 4 square with a 2 x 2 square hole in the middle; outer segments marked 5.
constexpr const char* kSquareWithHole =
    "8 2 0 1\n"
    "1 0 0 1\n2 4 0 1\n3 4 4 1\n4 0 4 1\n"
    "5 1 1 2\n6 3 1 2\n7 3 3 2\n8 1 3 2\n"
    "8 1\n"
    "1 1 2 5\n2 2 3 5\n3 3 4 5\n4 4 1 5\n"
    "5 5 6 6\n6 6 7 6\n7 7 8 6\n8 8 5 6\n"
    "1\n1 2 2\n";

struct CliRun {
  int code = -1;
  std::string out;
  std::string err;
};

std::string quote(const std::string& s) {
  std::string q = "'";
  for (const char c : s) {
    if (c == '\'') {
      q += "'\\''";
    } else {
      q.push_back(c);
    }
  }
  q.push_back('\'');
  return q;
}

CliRun run_tri(const test::ScratchDir& dir, const std::vector<std::string>& args) {
  std::string command = quote(test::cli_path().string());
  command.append(" tri");
  for (const auto& a : args) {
    command.push_back(' ');
    command.append(quote(a));
  }
  command.append(" >");
  command.append(quote((dir / "stdout.txt").string()));
  command.append(" 2>");
  command.append(quote((dir / "stderr.txt").string()));
  const int status = std::system(command.c_str());
  CliRun run;
  run.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  run.out = test::read_file(dir / "stdout.txt");
  run.err = test::read_file(dir / "stderr.txt");
  return run;
}

struct EleFile {
  std::vector<std::array<long long, 3>> triangles;
  std::vector<double> attributes;
  int attribute_count = 0;
};

EleFile read_ele(const std::filesystem::path& path) {
  std::istringstream in(test::read_file(path));
  EleFile ele;
  long long n = 0, per = 0;
  in >> n >> per >> ele.attribute_count;
  for (long long t = 0; t < n; ++t) {
    long long id = 0;
    std::array<long long, 3> v{};
    in >> id >> v[0] >> v[1] >> v[2];
    ele.triangles.push_back(v);
    for (int a = 0; a < ele.attribute_count; ++a) {
      double value = 0;
      in >> value;
      ele.attributes.push_back(value);
    }
  }
  return ele;
}

double summary_value(const std::string& out, const std::string& key) {
  const auto at = out.find(key + ":");
  if (at == std::string::npos) return -1;
  return std::strtod(out.c_str() + at + key.size() + 1, nullptr);
}

TEST(TriCommand, HelpPrintsUsageAndExitsZero) {
  test::ScratchDir dir("tri-cli");
  const CliRun run = run_tri(dir, {"--help"});
  EXPECT_EQ(run.code, 0);
  EXPECT_NE(run.out.find("usage: delmesh tri"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("--min-angle"), std::string::npos);
}

TEST(TriCommand, UsageErrorsExitWithTwoAndSayWhy) {
  test::ScratchDir dir("tri-cli");
  const auto poly = dir.write("sq.poly", kSquareWithHole);
  struct Case {
    std::vector<std::string> args;
    const char* says;
  };
  const std::vector<Case> cases = {
      {{}, "no input"},
      {{poly.string(), "--bogus"}, "unknown option --bogus"},
      {{"-pD", poly.string()}, "'D'"},
      {{"-pq70", poly.string()}, "-q"},
      {{poly.string(), "--min-angle", "abc"}, "--min-angle"},
      {{poly.string(), "--max-area", "-1"}, "--max-area"},
      {{poly.string(), "--min-angle"}, "--min-angle needs a value"},
      {{poly.string(), "-o"}, "-o needs a file name"},
      {{poly.string(), "-o", (dir / "x.txt").string()}, ".node, .vtu or .svg"},
      {{(dir / "model.stl").string()}, ".poly or .node"},
      {{poly.string(), poly.string()}, "more than one input"},
      {{poly.string(), "--quiet=1"}, "takes no value"},
      {{"-pS", poly.string()}, "-S"},
  };
  for (const Case& c : cases) {
    const CliRun run = run_tri(dir, c.args);
    EXPECT_EQ(run.code, 2) << c.says << "\n" << run.err;
    EXPECT_NE(run.err.find(c.says), std::string::npos) << run.err;
    EXPECT_TRUE(run.out.empty()) << run.out;
  }
}

TEST(TriCommand, RefusedInputsExitWithOneAndNameFileAndLine) {
  test::ScratchDir dir("tri-cli");
  const CliRun missing = run_tri(dir, {(dir / "none.poly").string()});
  EXPECT_EQ(missing.code, 1);
  EXPECT_NE(missing.err.find("none.poly"), std::string::npos) << missing.err;

  const auto bad_segment =
      dir.write("bad.poly", "# square\n4 2 0 0\n1 0 0\n2 1 0\n3 1 1\n4 0 1\n4 0\n1 1 2\n2 2 3\n3 3 9\n4 4 1\n0\n");
  const CliRun segment = run_tri(dir, {"-pq30", bad_segment.string()});
  EXPECT_EQ(segment.code, 1);
  EXPECT_NE(segment.err.find(bad_segment.string() + ":10:"), std::string::npos) << segment.err;
  EXPECT_NE(segment.err.find("vertex 9"), std::string::npos) << segment.err;

  const auto nan = dir.write("nan.node", "3 2 0 0\n1 0 0\n2 1 nan\n3 0 1\n");
  const CliRun not_finite = run_tri(dir, {nan.string()});
  EXPECT_EQ(not_finite.code, 1);
  EXPECT_NE(not_finite.err.find(nan.string() + ":3:"), std::string::npos) << not_finite.err;

  const auto dup = dir.write("dup.node", "3 2 0 0\n1 0 0\n1 1 0\n3 0 1\n");
  const CliRun duplicate = run_tri(dir, {dup.string()});
  EXPECT_EQ(duplicate.code, 1);
  EXPECT_NE(duplicate.err.find(dup.string() + ":3:"), std::string::npos) << duplicate.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "dup.1.node"));
}

TEST(TriCommand, HolePointOutsideTheDomainIsRefusedNamingTheInput) {
  test::ScratchDir dir("tri-cli");
  std::string text = kSquareWithHole;
  text.replace(text.rfind("1 2 2"), 5, "1 9 9");
  const auto poly = dir.write("outside.poly", text);
  const CliRun run = run_tri(dir, {"-pq30", poly.string(), "-o", (dir / "o.node").string()});
  EXPECT_EQ(run.code, 1) << run.out << run.err;
  EXPECT_NE(run.err.find("outside.poly"), std::string::npos) << run.err;
  EXPECT_NE(run.err.find("hole"), std::string::npos) << run.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "o.node"));
}

TEST(TriCommand, QualityRunWritesNodeElePolyThatReadBackAndMeetTheBound) {
  test::ScratchDir dir("tri-cli");
  const auto poly = dir.write("sq.poly", kSquareWithHole);
  const CliRun run = run_tri(dir, {"-pq30", poly.string(), "-o", (dir / "out" / "sq.node").string()});
  ASSERT_EQ(run.code, 0) << run.err;
  for (const char* key : {"vertices:", "triangles:", "segments:", "min angle:", "max angle:", "status:", "time:"}) {
    EXPECT_NE(run.out.find(key), std::string::npos) << key << "\n" << run.out;
  }
  EXPECT_NE(run.out.find("status:     Complete"), std::string::npos) << run.out;
  EXPECT_GE(summary_value(run.out, "min angle"), 30.0) << run.out;
  EXPECT_TRUE(std::filesystem::exists(dir / "out" / "sq.ele"));
  EXPECT_FALSE(std::filesystem::exists(dir / "out" / "sq.edge"));

  auto mesh = read_triangle_poly(dir / "out" / "sq.poly");
  ASSERT_TRUE(mesh) << mesh.error().describe();
  EXPECT_EQ(mesh->first_index, 1);
  const auto& points = mesh->pslg.points;
  EXPECT_EQ(static_cast<double>(points.size()), summary_value(run.out, "vertices"));
  // Subsegments carry the input markers 5 (outer) and 6 (hole).
  ASSERT_FALSE(mesh->pslg.segment_markers.empty());
  for (const int m : mesh->pslg.segment_markers) EXPECT_TRUE(m == 5 || m == 6) << m;

  const EleFile ele = read_ele(dir / "out" / "sq.ele");
  ASSERT_FALSE(ele.triangles.empty());
  EXPECT_EQ(static_cast<double>(ele.triangles.size()), summary_value(run.out, "triangles"));
  double area = 0;
  for (const auto& t : ele.triangles) {
    for (const long long v : t) {
      ASSERT_GE(v, 1);
      ASSERT_LE(v, static_cast<long long>(points.size()));
    }
    const Point2& a = points[static_cast<std::size_t>(t[0] - 1)];
    const Point2& b = points[static_cast<std::size_t>(t[1] - 1)];
    const Point2& c = points[static_cast<std::size_t>(t[2] - 1)];
    const double twice = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
    EXPECT_GT(twice, 0.0);  // counterclockwise
    area += twice / 2;
    EXPECT_GE(triangle_min_angle_deg(a, b, c), 30.0 - 1e-9);
  }
  EXPECT_NEAR(area, 16.0 - 4.0, 1e-9);  // the hole is removed
}

TEST(TriCommand, SteinerBudgetExhaustedGivesPartialStatusWithItsCount) {
  test::ScratchDir dir("tri-cli");
  const auto poly = dir.write("sq.poly", kSquareWithHole);
  const CliRun run = run_tri(dir, {"-pq30S0", poly.string(), "--no-output"});
  ASSERT_EQ(run.code, 0) << run.err;
  EXPECT_EQ(summary_value(run.out, "vertices"), 8.0) << run.out;
  EXPECT_LT(summary_value(run.out, "min angle"), 30.0) << run.out;
  const auto at = run.out.find("status:     Partial (");
  ASSERT_NE(at, std::string::npos) << run.out;
  EXPECT_GT(std::strtol(run.out.c_str() + at + 21, nullptr, 10), 0) << run.out;
}

TEST(TriCommand, UnwritableOutputIsAnErrorNamingTheFile) {
  test::ScratchDir dir("tri-cli");
  const auto poly = dir.write("sq.poly", kSquareWithHole);
  const std::string out = (dir / "sq.poly" / "x.node").string();  // parent is a file
  const CliRun run = run_tri(dir, {"-pq", poly.string(), "-o", out});
  EXPECT_EQ(run.code, 1);
  EXPECT_NE(run.err.find(out), std::string::npos) << run.err;
}

TEST(TriCommand, DefaultOutputNamesFollowTriangle) {
  test::ScratchDir dir("tri-cli");
  const auto poly = dir.write("sq.poly", kSquareWithHole);
  ASSERT_EQ(run_tri(dir, {"-pQ", poly.string()}).code, 0);
  for (const char* f : {"sq.1.node", "sq.1.ele", "sq.1.poly"}) {
    EXPECT_TRUE(std::filesystem::exists(dir / f)) << f;
  }
  const CliRun again = run_tri(dir, {"-pqe", (dir / "sq.1.poly").string()});
  ASSERT_EQ(again.code, 0) << again.err;
  for (const char* f : {"sq.2.node", "sq.2.ele", "sq.2.poly", "sq.2.edge"}) {
    EXPECT_TRUE(std::filesystem::exists(dir / f)) << f;
  }
}

TEST(TriCommand, QuietZeroBasedVtuSvgAndNoOutput) {
  test::ScratchDir dir("tri-cli");
  const auto poly = dir.write("sq.poly", kSquareWithHole);
  const CliRun quiet = run_tri(dir, {"-pq25zQ", poly.string(), "-o", (dir / "z.node").string()});
  ASSERT_EQ(quiet.code, 0) << quiet.err;
  EXPECT_TRUE(quiet.out.empty()) << quiet.out;
  auto zero = read_triangle_node(dir / "z.node");
  ASSERT_TRUE(zero) << zero.error().describe();
  EXPECT_EQ(zero->first_index, 0);

  const CliRun pictures = run_tri(dir, {poly.string(), "--min-angle", "30", "--quiet", "-o",
                                     (dir / "p.vtu").string(), "-o", (dir / "p.svg").string()});
  ASSERT_EQ(pictures.code, 0) << pictures.err;
  EXPECT_NE(test::read_file(dir / "p.vtu").find("Name=\"min_angle\""), std::string::npos);
  EXPECT_NE(test::read_file(dir / "p.svg").find("</svg>"), std::string::npos);
  EXPECT_FALSE(std::filesystem::exists(dir / "p.node"));

  const CliRun none = run_tri(dir, {"-pq", poly.string(), "--no-output"});
  ASSERT_EQ(none.code, 0) << none.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "sq.1.node"));
  EXPECT_NE(none.out.find("triangles:"), std::string::npos);
}

TEST(TriCommand, NodeInputGivesTheDelaunayTriangulationOfThePoints) {
  test::ScratchDir dir("tri-cli");
  // Square corners and an off-center interior point: 4 triangles, no Steiner points.
  const auto node = dir.write("pts.node", "5 2 0 0\n1 0 0\n2 2 0\n3 2 2\n4 0 2\n5 0.7 1.1\n");
  const CliRun run = run_tri(dir, {node.string(), "-o", (dir / "d.node").string()});
  ASSERT_EQ(run.code, 0) << run.err;
  EXPECT_EQ(summary_value(run.out, "vertices"), 5.0) << run.out;
  EXPECT_EQ(summary_value(run.out, "triangles"), 4.0) << run.out;
  EXPECT_EQ(read_ele(dir / "d.ele").triangles.size(), 4u);
}

TEST(TriCommand, SegmentsEnclosingNothingAreRefusedUnlessTheHullIsKept) {
  test::ScratchDir dir("tri-cli");
  // Four corners and only one side as a segment: removing concavities leaves nothing.
  const auto poly = dir.write("open.poly", "4 2 0 0\n1 0 0\n2 1 0\n3 1 1\n4 0 1\n1 0\n1 1 2\n0\n");
  const CliRun empty = run_tri(dir, {"-pq30", poly.string()});
  EXPECT_EQ(empty.code, 1);
  EXPECT_NE(empty.err.find("open.poly"), std::string::npos) << empty.err;
  EXPECT_NE(empty.err.find("--convex-hull"), std::string::npos) << empty.err;
  const CliRun hull = run_tri(dir, {"-pcq30", poly.string(), "--no-output"});
  EXPECT_EQ(hull.code, 0) << hull.err;
  EXPECT_GE(summary_value(hull.out, "triangles"), 2.0) << hull.out;
}

TEST(TriCommand, QualityOnAPointSetRefinesInsideTheConvexHull) {
  test::ScratchDir dir("tri-cli");
  const auto node = dir.write("pts.node", "4 2 0 0\n1 0 0\n2 10 0\n3 10 1\n4 0 1\n");
  const CliRun run = run_tri(dir, {"-q30", node.string(), "-o", (dir / "q.node").string()});
  ASSERT_EQ(run.code, 0) << run.err;
  EXPECT_GE(summary_value(run.out, "min angle"), 30.0) << run.out;
  EXPECT_GT(summary_value(run.out, "vertices"), 4.0) << run.out;
  double area = 0;
  auto points = read_triangle_node(dir / "q.node");
  ASSERT_TRUE(points) << points.error().describe();
  for (const auto& t : read_ele(dir / "q.ele").triangles) {
    const Point2& a = points->pslg.points[static_cast<std::size_t>(t[0] - 1)];
    const Point2& b = points->pslg.points[static_cast<std::size_t>(t[1] - 1)];
    const Point2& c = points->pslg.points[static_cast<std::size_t>(t[2] - 1)];
    area += ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])) / 2;
  }
  EXPECT_NEAR(area, 10.0, 1e-9);
}

TEST(TriCommand, RegionalAttributesAndAreaBoundsReachTheTriangles) {
  test::ScratchDir dir("tri-cli");
  // Two unit squares side by side sharing the segment x = 1; region attributes 1 and 2, and
  // a max area only in the right one.
  const auto poly = dir.write(
      "two.poly",
      "6 2 0 0\n1 0 0\n2 1 0\n3 2 0\n4 2 1\n5 1 1\n6 0 1\n"
      "7 0\n1 1 2\n2 2 3\n3 3 4\n4 4 5\n5 5 6\n6 6 1\n7 2 5\n"
      "0\n2\n1 0.5 0.5 1 -1\n2 1.5 0.5 2 0.01\n");
  const CliRun run = run_tri(dir, {"-pAa", poly.string(), "-o", (dir / "r.node").string()});
  ASSERT_EQ(run.code, 0) << run.err;
  const EleFile ele = read_ele(dir / "r.ele");
  ASSERT_EQ(ele.attribute_count, 1);
  auto node = read_triangle_node(dir / "r.node");
  ASSERT_TRUE(node) << node.error().describe();
  const auto& p = node->pslg.points;
  std::size_t left = 0, right = 0;
  for (std::size_t t = 0; t < ele.triangles.size(); ++t) {
    const auto& tri = ele.triangles[t];
    const Point2& a = p[static_cast<std::size_t>(tri[0] - 1)];
    const Point2& b = p[static_cast<std::size_t>(tri[1] - 1)];
    const Point2& c = p[static_cast<std::size_t>(tri[2] - 1)];
    const double cx = (a[0] + b[0] + c[0]) / 3;
    const double area = ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])) / 2;
    if (cx < 1) {
      ++left;
      EXPECT_EQ(ele.attributes[t], 1.0);
    } else {
      ++right;
      EXPECT_EQ(ele.attributes[t], 2.0);
      EXPECT_LE(area, 0.01 * (1 + 1e-12));
    }
  }
  EXPECT_GE(right, 100u);  // area 1 at <= 0.01 per triangle
  EXPECT_LT(left, right);
}

TEST(TriCommand, ReadmeMainCommandRunsOnTheBundledExample) {
  test::ScratchDir dir("tri-cli");
  const auto example = test::test_data_dir().parent_path().parent_path() /
                       "examples" / "A.poly";
  const CliRun run = run_tri(dir, {"-pq30", example.string(), "-o", (dir / "A.1.node").string()});
  ASSERT_EQ(run.code, 0) << run.err;
  EXPECT_GE(summary_value(run.out, "min angle"), 30.0) << run.out;
  EXPECT_NE(run.out.find("status:     Complete"), std::string::npos) << run.out;
  EXPECT_TRUE(std::filesystem::exists(dir / "A.1.ele"));
}

}  // namespace
}  // namespace delmesh
