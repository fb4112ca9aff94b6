// TetGen switch strings parsed into MeshOptions and CLI flags, TetGen's defaults, refused
// switches, and TetGen's output naming.
#include <gtest/gtest.h>

#include "tools/delmesh/tetgen_switches.h"

namespace delmesh::cli {
namespace {

TetgenSwitches parse_ok(std::string_view text) {
  auto parsed = parse_tetgen_switches(text);
  EXPECT_TRUE(parsed.has_value()) << text << ": " << (parsed ? "" : parsed.error().describe());
  return parsed ? *parsed : TetgenSwitches{};
}

TEST(TetgenSwitches, PlainPlcHasNoQualityRefinement) {
  const auto s = parse_ok("-p");
  EXPECT_FALSE(s.options.quality);
  EXPECT_FALSE(s.options.region_max_volume);
  EXPECT_LE(s.options.max_volume, 0.0);
  EXPECT_FALSE(s.check);
  EXPECT_FALSE(s.quiet);
  EXPECT_TRUE(s.iteration_number);
}

TEST(TetgenSwitches, QualityWithAndWithoutNumbers) {
  auto s = parse_ok("-pq");
  EXPECT_TRUE(s.options.quality);
  EXPECT_DOUBLE_EQ(s.options.max_radius_edge, 2.0);
  EXPECT_DOUBLE_EQ(s.options.min_dihedral_deg, 0.0);
  s = parse_ok("-pq1.414");
  EXPECT_DOUBLE_EQ(s.options.max_radius_edge, 1.414);
  s = parse_ok("-pq1.2/18");
  EXPECT_DOUBLE_EQ(s.options.max_radius_edge, 1.2);
  EXPECT_DOUBLE_EQ(s.options.min_dihedral_deg, 18.0);
  s = parse_ok("-q1.1,20");
  EXPECT_DOUBLE_EQ(s.options.max_radius_edge, 1.1);
  EXPECT_DOUBLE_EQ(s.options.min_dihedral_deg, 20.0);
  s = parse_ok("-q/12");
  EXPECT_DOUBLE_EQ(s.options.max_radius_edge, 2.0);
  EXPECT_DOUBLE_EQ(s.options.min_dihedral_deg, 12.0);
  s = parse_ok("-q.9");
  EXPECT_DOUBLE_EQ(s.options.max_radius_edge, 0.9);
}

TEST(TetgenSwitches, TheIssueExample) {
  const auto s = parse_ok("-pq1.414a0.1");
  EXPECT_TRUE(s.options.quality);
  EXPECT_DOUBLE_EQ(s.options.max_radius_edge, 1.414);
  EXPECT_DOUBLE_EQ(s.options.max_volume, 0.1);
  EXPECT_FALSE(s.options.region_max_volume);
}

TEST(TetgenSwitches, VolumeBoundsGlobalAndPerRegion) {
  auto s = parse_ok("-pa");
  EXPECT_TRUE(s.options.quality);  // -a turns on -q
  EXPECT_TRUE(s.options.region_max_volume);
  EXPECT_LE(s.options.max_volume, 0.0);
  s = parse_ok("-pa1e-3A");
  EXPECT_DOUBLE_EQ(s.options.max_volume, 1e-3);
  s = parse_ok("-pa2.5E+1");
  EXPECT_DOUBLE_EQ(s.options.max_volume, 25.0);
  s = parse_ok("-pa0.5aq");
  EXPECT_DOUBLE_EQ(s.options.max_volume, 0.5);
  EXPECT_TRUE(s.options.region_max_volume);
}

TEST(TetgenSwitches, FlagsAndBudget) {
  const auto s = parse_ok("-pcAzCQVIgS500");
  EXPECT_TRUE(s.options.keep_convex_hull);
  EXPECT_TRUE(s.zero_based);
  EXPECT_TRUE(s.check);
  EXPECT_TRUE(s.quiet);
  EXPECT_TRUE(s.verbose);
  EXPECT_FALSE(s.iteration_number);
  EXPECT_TRUE(s.medit);
  EXPECT_EQ(s.options.max_steiner_points, 500);
}

TEST(TetgenSwitches, SeveralArgumentsAccumulate) {
  TetgenSwitches s;
  ASSERT_TRUE(apply_tetgen_switches("-pq1.3", s).has_value());
  ASSERT_TRUE(apply_tetgen_switches("-a0.2", s).has_value());
  ASSERT_TRUE(apply_tetgen_switches("-Q", s).has_value());
  EXPECT_DOUBLE_EQ(s.options.max_radius_edge, 1.3);
  EXPECT_DOUBLE_EQ(s.options.max_volume, 0.2);
  EXPECT_TRUE(s.quiet);
}

TEST(TetgenSwitches, RefusedSwitchesNameTheLetter) {
  auto r = parse_tetgen_switches("-pY");
  ASSERT_FALSE(r.has_value());
  EXPECT_EQ(r.error().code, ErrorCode::Unsupported);
  EXPECT_NE(r.error().message.find("-Y"), std::string::npos) << r.error().message;
  r = parse_tetgen_switches("-pu");
  ASSERT_FALSE(r.has_value());
  EXPECT_EQ(r.error().code, ErrorCode::InvalidOption);
  EXPECT_NE(r.error().message.find("-u"), std::string::npos);
  r = parse_tetgen_switches("-po2");
  ASSERT_FALSE(r.has_value());
  EXPECT_EQ(r.error().code, ErrorCode::Unsupported);
}

TEST(TetgenSwitches, OptimizationLevelZeroTurnsTheDefaultImprovementOff) {
  EXPECT_TRUE(parse_ok("-pq").options.improve);
  EXPECT_FALSE(parse_ok("-pq1.414O0").options.improve);
  EXPECT_TRUE(parse_ok("-pqO").options.improve);
  EXPECT_TRUE(parse_ok("-pqO2").options.improve);
  auto r = parse_tetgen_switches("-pqO2/7");
  ASSERT_FALSE(r.has_value());
  EXPECT_EQ(r.error().code, ErrorCode::Unsupported);
  EXPECT_NE(r.error().message.find("-O"), std::string::npos) << r.error().message;
  EXPECT_FALSE(parse_tetgen_switches("-pqO1.5").has_value());
}

TEST(TetgenSwitches, BadNumbersAreRefused) {
  for (std::string_view bad : {"-q0", "-q1.2/80", "-q1.2/3/4", "-a0", "-S", "-S1.5", "-p2", "-Q1", "-q1..2", "-",
                               "pq"}) {
    EXPECT_FALSE(parse_tetgen_switches(bad).has_value()) << bad;
  }
}

TEST(TetgenSwitches, OutputNamesFollowTetgen) {
  EXPECT_EQ(tetgen_output_base("dir/part.poly"), "dir/part.1");
  EXPECT_EQ(tetgen_output_base("part.3.smesh"), "part.4");
  EXPECT_EQ(tetgen_output_base("a.b/part.stl"), "a.b/part.1");
  EXPECT_EQ(tetgen_output_base("dir/part.poly", false), "dir/part");
  EXPECT_EQ(tetgen_output_base("v1.2/model.step"), "v1.2/model.1");
}

}  // namespace
}  // namespace delmesh::cli
