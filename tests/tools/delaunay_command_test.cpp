// End-to-end tests of `delmesh delaunay`: output files, --check, and error reporting.

#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "tests/support/test_paths.h"
#include "toolkit/tetmesh/tet_node_io.h"

namespace delmesh {
namespace {

namespace fs = std::filesystem;

struct CliRun {
  int code;
  std::string err;
};

CliRun run_cli(const std::string& args, const fs::path& dir) {
  const fs::path err = dir / "stderr.txt";
  const std::string cmd = test::cli_path().string() + " delaunay " + args + " 2> " + err.string() + " > /dev/null";
  const int status = std::system(cmd.c_str());
  std::ifstream in(err);
  std::stringstream ss;
  ss << in.rdbuf();
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, ss.str()};
}

fs::path scratch_dir(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("delmesh_delaunay_cli_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

TEST(DelaunayCommand, WritesNodeAndEleAndPassesCheck) {
  const fs::path dir = scratch_dir("ok");
  {
    std::ofstream node(dir / "cube.node");
    node << "# unit cube corners and centre, 0-based like tetgen -z\n9 3 0 1\n";
    int i = 0;
    for (int x = 0; x < 2; ++x)
      for (int y = 0; y < 2; ++y)
        for (int z = 0; z < 2; ++z) node << i++ << "  " << x << ' ' << y << ' ' << z << " 1\n";
    node << "8 0.5 0.5 0.5 0\n";
  }
  const CliRun r = run_cli((dir / "cube.node").string() + " -o " + (dir / "out.node").string() + " --check", dir);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("verified"), std::string::npos) << r.err;
  auto points = read_node_file(dir / "out.node");
  ASSERT_TRUE(points.has_value()) << points.error().describe();
  ASSERT_EQ(points->points.size(), 9u);
  EXPECT_EQ(points->first_index, 1);
  EXPECT_EQ(points->points[8], Vec3(0.5, 0.5, 0.5));
  std::ifstream ele(dir / "out.ele");
  std::size_t tets = 0, per = 0, attrs = 1;
  ele >> tets >> per >> attrs;
  // The centre is in every tet of the cube's Delaunay tetrahedralization: 12 tets, two per
  // cube face.
  EXPECT_EQ(tets, 12u);
  EXPECT_EQ(per, 4u);
  EXPECT_EQ(attrs, 0u);
  std::size_t index = 0, a = 0, b = 0, c = 0, d = 0, rows = 0;
  while (ele >> index >> a >> b >> c >> d) {
    ++rows;
    EXPECT_EQ(index, rows);
    for (const std::size_t v : {a, b, c, d}) {
      EXPECT_GE(v, 1u);
      EXPECT_LE(v, 9u);
    }
    EXPECT_TRUE(a == 9 || b == 9 || c == 9 || d == 9);
  }
  EXPECT_EQ(rows, 12u);
}

TEST(DelaunayCommand, DefaultOutputNameAndDuplicateWarning) {
  const fs::path dir = scratch_dir("default");
  {
    std::ofstream node(dir / "pts.node");
    node << "6 3\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n5 1 0 0\n6 1 1 1\n";
  }
  const CliRun r = run_cli((dir / "pts.node").string(), dir);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("1 duplicate points merged"), std::string::npos) << r.err;
  EXPECT_TRUE(fs::exists(dir / "pts.1.node"));
  EXPECT_TRUE(fs::exists(dir / "pts.1.ele"));
}

TEST(DelaunayCommand, BadInputNamesFileAndLine) {
  const fs::path dir = scratch_dir("bad");
  {
    std::ofstream node(dir / "bad.node");
    node << "3 3 0 0\n1 0 0 0\n\n# comment\n2 1 0\n3 0 1 0\n";
  }
  const CliRun r = run_cli((dir / "bad.node").string(), dir);
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("bad.node:5:"), std::string::npos) << r.err;

  {
    std::ofstream node(dir / "flat.node");
    node << "5 3 0 0\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 1 1 0\n5 2 3 0\n";
  }
  const CliRun flat = run_cli((dir / "flat.node").string(), dir);
  EXPECT_EQ(flat.code, 1);
  EXPECT_NE(flat.err.find("coplanar"), std::string::npos) << flat.err;

  const CliRun usage = run_cli("--bogus", dir);
  EXPECT_EQ(usage.code, 2);
  const CliRun help = run_cli("--help", dir);
  EXPECT_EQ(help.code, 0);
}

}  // namespace
}  // namespace delmesh
