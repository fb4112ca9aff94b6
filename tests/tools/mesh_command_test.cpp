// End-to-end tests of `delmesh mesh`: the built CLI on the small PLCs of tests/data/mesh
// (unit cube as .poly and .smesh, two boxes sharing a facet, a malformed .poly): exit
// codes, every output format, TetGen switches and output naming, --stats JSON, --check,
// the default improvement and its off switches (with the radius-edge polish's stage),
// regions and facet markers carried to the files, located errors.
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "tests/support/json_value.h"
#include "tests/support/scratch_dir.h"
#include "tests/support/test_paths.h"

namespace delmesh {
namespace {

namespace fs = std::filesystem;

struct CliRun {
  int code = -1;
  std::string out;
  std::string err;
};

std::string slurp(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

class MeshCommand : public ::testing::Test {
 protected:
  void SetUp() override {
    scratch.emplace("mesh-cli");
    dir = scratch->path();
  }
  void TearDown() override { scratch.reset(); }
  std::optional<test::ScratchDir> scratch;

  CliRun run(const std::string& args) const {
    const std::string cmd = test::cli_path().string() + " mesh " + args + " > " + (dir / "stdout.txt").string() +
                            " 2> " + (dir / "stderr.txt").string();
    const int status = std::system(cmd.c_str());
    return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, slurp(dir / "stdout.txt"), slurp(dir / "stderr.txt")};
  }

  static std::string data(const std::string& name) { return (test::test_data_dir() / "mesh" / name).string(); }
  std::string at(const std::string& name) const { return (dir / name).string(); }

  fs::path dir;
};

/// Data lines of a TetGen file (comments and blank lines dropped), split into tokens.
std::vector<std::vector<std::string>> tetgen_lines(const fs::path& path) {
  std::vector<std::vector<std::string>> lines;
  std::istringstream in(slurp(path));
  std::string line;
  while (std::getline(in, line)) {
    line = line.substr(0, line.find('#'));
    std::istringstream words(line);
    std::vector<std::string> tokens;
    for (std::string w; words >> w;) tokens.push_back(w);
    if (!tokens.empty()) lines.push_back(tokens);
  }
  return lines;
}

TEST_F(MeshCommand, HelpAndUsageErrors) {
  CliRun r = run("--help");
  EXPECT_EQ(r.code, 0);
  EXPECT_NE(r.out.find("usage: delmesh mesh"), std::string::npos);
  EXPECT_EQ(run("").code, 2);
  EXPECT_EQ(run(data("cube.poly") + " --frobnicate").code, 2);
  EXPECT_EQ(run(data("cube.poly") + " --radius-edge abc").code, 2);
  EXPECT_EQ(run(data("cube.poly") + " -o " + at("x.xyz")).code, 2);
  r = run("-pY " + data("cube.poly"));
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("-Y"), std::string::npos) << r.err;
  EXPECT_EQ(run(data("cube.poly") + " " + data("cube.smesh")).code, 2);
}

TEST_F(MeshCommand, CubeWithStatsAndCheck) {
  const CliRun r = run(data("cube.poly") + " -o " + at("cube.vtu") + " --radius-edge 1.414 --max-volume 0.05 --check"
                       " --stats " + at("stats.json"));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_GT(fs::file_size(at("cube.vtu")), 0u);
  EXPECT_NE(r.err.find("check: mesh verified"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("radius-edge histogram"), std::string::npos) << r.err;
  std::string error;
  const auto stats = test::parse_json(slurp(at("stats.json")), &error);
  ASSERT_TRUE(stats.has_value()) << error;
  for (const char* key : {"input", "options", "mesh", "status", "quality", "stages", "seconds", "outputs",
                          "check_issues", "unmet_tets"}) {
    EXPECT_TRUE(stats->has(key)) << key;
  }
  const auto& mesh = (*stats)["mesh"];
  EXPECT_GE(mesh["tets"].number, 20);  // volume 1 at <= 0.05 per tet
  EXPECT_GE(mesh["boundary_faces"].number, 12);
  EXPECT_NEAR(mesh["volume"].number, 1.0, 1e-9);
  EXPECT_EQ((*stats)["check_issues"].number, 0);
  EXPECT_EQ((*stats)["input"]["facets"].number, 6);
  EXPECT_EQ((*stats)["options"]["radius_edge_bound"].number, 1.414);
  const std::string status = (*stats)["status"].string;
  EXPECT_TRUE(status == "Complete" || status == "Partial") << status;
  if (status == "Complete") {
    EXPECT_EQ((*stats)["quality"]["above_radius_edge_bound"].number, 0);
  }
}

TEST_F(MeshCommand, DihedralWindowWithOffCenters) {
  // --off-centers changes where slivers are split; both meshes pass --check and meet the
  // window on the cube.
  const std::string common = data("cube.poly") + " --max-volume 0.0005 --min-dihedral 20 --max-dihedral 150 --check";
  const CliRun centers = run(common + " -o " + at("centers.node"));
  const CliRun off = run(common + " --off-centers -o " + at("off.node"));
  ASSERT_EQ(centers.code, 0) << centers.err;
  ASSERT_EQ(off.code, 0) << off.err;
  for (const CliRun* r : {&centers, &off}) {
    EXPECT_NE(r->err.find("check: mesh verified"), std::string::npos) << r->err;
    EXPECT_NE(r->err.find("window [20, 150] deg: 0 tets"), std::string::npos) << r->err;
  }
  EXPECT_TRUE(slurp(at("centers.node")) != slurp(at("off.node"))) << "--off-centers changed nothing";
}

TEST_F(MeshCommand, DefaultImprovementAndItsOffSwitches) {
  // TetGen's example leaves tets below 5 degrees after refinement alone: the default run
  // improves them and passes --check; --no-improve and -O0 give the same mesh, with
  // those tets, still constrained Delaunay (--check tests that).
  const std::string input = data("tetgen_example.poly");
  const CliRun on = run("-pq " + input + " -C -o " + at("on.node") + " --stats " + at("on.json"));
  const CliRun off = run("-pq " + input + " --no-improve -C -o " + at("off.node") + " --stats " + at("off.json"));
  const CliRun o0 = run("-pqO0 " + input + " -C -o " + at("o0.node"));
  for (const CliRun* r : {&on, &off, &o0}) {
    ASSERT_EQ(r->code, 0) << r->err;
    EXPECT_NE(r->err.find("check: mesh verified"), std::string::npos) << r->err;
  }
  EXPECT_EQ(slurp(at("off.node")), slurp(at("o0.node")));
  EXPECT_EQ(slurp(at("off.ele")), slurp(at("o0.ele")));
  std::string error;
  const auto on_stats = test::parse_json(slurp(at("on.json")), &error);
  ASSERT_TRUE(on_stats.has_value()) << error;
  const auto off_stats = test::parse_json(slurp(at("off.json")), &error);
  ASSERT_TRUE(off_stats.has_value()) << error;
  EXPECT_LT((*off_stats)["quality"]["min_dihedral_deg"].number, 5.0);
  EXPECT_GT((*on_stats)["quality"]["min_dihedral_deg"].number, (*off_stats)["quality"]["min_dihedral_deg"].number);
  EXPECT_LE((*on_stats)["unmet_tets"].number, (*off_stats)["unmet_tets"].number);
  // The radius-edge polish after the improvement is a stage of its own, in the JSON and
  // the summary; without the improvement it does not run.
  const auto stage_names = [](const auto& stats) {
    std::vector<std::string> names;
    for (const auto& stage : stats["stages"].array) names.push_back(stage["name"].string);
    return names;
  };
  EXPECT_EQ(stage_names(*on_stats),
            (std::vector<std::string>{"delaunay", "segments", "facets", "domain", "quality", "slivers", "polish"}));
  EXPECT_EQ(stage_names(*off_stats), (std::vector<std::string>{"delaunay", "segments", "facets", "domain", "quality"}));
  EXPECT_NE(on.err.find("\n  polish "), std::string::npos) << on.err;
  EXPECT_EQ(off.err.find("\n  polish "), std::string::npos) << off.err;
}

TEST_F(MeshCommand, EveryOutputFormat) {
  for (const std::string name : {"cube.vtu", "cube.msh", "cube.mesh", "cube.inp", "cube.ovm"}) {
    const CliRun r = run(data("cube.poly") + " --quiet -o " + at(name));
    ASSERT_EQ(r.code, 0) << name << ": " << r.err;
    EXPECT_GT(fs::file_size(at(name)), 0u) << name;
  }
  EXPECT_NE(slurp(at("cube.msh")).find("$MeshFormat\n4.1"), std::string::npos);
  ASSERT_EQ(run(data("cube.poly") + " --quiet --gmsh22 -o " + at("old.msh")).code, 0);
  EXPECT_NE(slurp(at("old.msh")).find("$MeshFormat\n2.2"), std::string::npos);
  ASSERT_EQ(run(data("cube.poly") + " --quiet -o " + at("cube.node")).code, 0);
  for (const char* ext : {".node", ".ele", ".face"}) {
    ASSERT_TRUE(fs::exists(at(std::string("cube") + ext))) << ext;
    EXPECT_GT(fs::file_size(at(std::string("cube") + ext)), 0u) << ext;
  }
}

TEST_F(MeshCommand, QuietPrintsNothing) {
  const CliRun r = run(data("cube.poly") + " --quiet -o " + at("cube.vtu"));
  ASSERT_EQ(r.code, 0);
  EXPECT_EQ(r.err, "");
  EXPECT_EQ(r.out, "");
}

TEST_F(MeshCommand, TetgenSwitchesAndDefaultNames) {
  fs::copy_file(data("cube.poly"), at("cube.poly"));
  CliRun r = run("-pq1.414a0.1 " + at("cube.poly"));
  ASSERT_EQ(r.code, 0) << r.err;
  for (const char* ext : {".node", ".ele", ".face"}) EXPECT_TRUE(fs::exists(at(std::string("cube.1") + ext))) << ext;
  const auto ele = tetgen_lines(at("cube.1.ele"));
  ASSERT_FALSE(ele.empty());
  EXPECT_GE(std::stoul(ele[0][0]), 10u);  // volume 1 at <= 0.1 per tet
  EXPECT_EQ(tetgen_lines(at("cube.1.node"))[1][0], "1");  // 1-based as TetGen writes

  // -z numbers from zero, -I drops the iteration number, -g adds Medit, -C checks, -Q quiets.
  r = run("-pzIgCQ " + at("cube.poly"));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.err, "");
  EXPECT_EQ(tetgen_lines(at("cube.node"))[1][0], "0");
  EXPECT_TRUE(fs::exists(at("cube.mesh")));

}

TEST_F(MeshCommand, SmeshInputPassesCheck) {
  const CliRun r = run(data("cube.smesh") + " --radius-edge 1.414 --check -o " + at("cube.mesh"));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(slurp(at("cube.mesh")).find("Tetrahedra"), std::string::npos);
}

TEST_F(MeshCommand, RegionsAndMarkersReachTheFiles) {
  const CliRun r = run(data("two_boxes.poly") + " --radius-edge 1.414 --check -o " + at("boxes.node"));
  ASSERT_EQ(r.code, 0) << r.err;
  const auto ele = tetgen_lines(at("boxes.ele"));
  ASSERT_GE(ele.size(), 2u);
  ASSERT_EQ(ele[0].size(), 3u);
  EXPECT_EQ(ele[0][2], "1");  // one attribute: the region
  std::set<std::string> regions;
  for (std::size_t i = 1; i < ele.size(); ++i) regions.insert(ele[i].back());
  EXPECT_EQ(regions, (std::set<std::string>{"1", "2"}));
  const auto face = tetgen_lines(at("boxes.face"));
  std::set<std::string> markers;
  for (std::size_t i = 1; i < face.size(); ++i) markers.insert(face[i].back());
  EXPECT_EQ(markers, (std::set<std::string>{"1", "2", "3", "4", "5", "6", "13", "14", "15", "16", "100"}));
}

TEST_F(MeshCommand, MalformedInputNamesFileAndLine) {
  const CliRun r = run(data("bad_vertex.poly") + " -o " + at("bad.vtu"));
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("bad_vertex.poly:23"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(at("bad.vtu")));
  const CliRun missing = run(at("nowhere.poly") + " -o " + at("x.vtu"));
  EXPECT_EQ(missing.code, 1);
  EXPECT_NE(missing.err.find("nowhere.poly"), std::string::npos) << missing.err;
}

}  // namespace
}  // namespace delmesh
