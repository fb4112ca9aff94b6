// End-to-end tests of `delmesh import`: summary on stdout, written PLC readable again,
// refused input with exit code 1 and the defect on stderr, usage errors with exit code 2.
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "importers/tetgen/tetgen_reader.h"
#include "tests/support/scratch_dir.h"
#include "tests/support/test_paths.h"

namespace delmesh {
namespace {

struct CliRun {
  int exit_code = -1;
  std::string out, err;
};

std::string slurp(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

/// Runs `program import arguments`, its output captured.
CliRun run_import(const std::filesystem::path& program, const std::string& arguments) {
  const auto dir = std::filesystem::temp_directory_path();
  // ctest runs tests of this file in parallel processes: one file pair per process.
  const std::string stem = "delmesh_import_cli_" + std::to_string(::getpid());
  const auto out = dir / (stem + ".out"), err = dir / (stem + ".err");
  const std::string command = program.string() + " import " + arguments + " >" + out.string() + " 2>" + err.string();
  const int status = std::system(command.c_str());
  CliRun run;
  run.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  run.out = slurp(out);
  run.err = slurp(err);
  std::filesystem::remove(out);
  std::filesystem::remove(err);
  return run;
}

CliRun run_cli(const std::string& arguments) { return run_import(test::cli_path(), arguments); }

/// The number after `label` in a summary ("vertices                 1234").
long summary_count(const std::string& out, const std::string& label) {
  const std::size_t at = out.find(label + " ");
  if (at == std::string::npos) return -1;
  return std::stol(out.substr(out.find_first_not_of(' ', at + label.size())));
}

TEST(ImportCommand, PrintsSummaryAndWritesPoly) {
  const auto output = std::filesystem::temp_directory_path() /
                      ("delmesh_import_cli_" + std::to_string(::getpid()) + ".poly");
  const auto input = test::corpus_dir() / "surface" / "cgal-step.off";
  const CliRun run = run_cli(input.string() + " -o " + output.string());
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.out.find("vertices                 10\n"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("regions                  1\n"), std::string::npos) << run.out;
  // cgal-step.off: 16 triangles (MANIFEST), none coplanar with a neighbour, 24 edges.
  EXPECT_EQ(summary_count(run.out, "segments"), 24) << run.out;
  EXPECT_EQ(summary_count(run.out, "facets"), 16) << run.out;
  EXPECT_NE(run.out.find("\ntime                     "), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("smallest segment angle"), std::string::npos);
  EXPECT_NE(run.out.find("smallest facet dihedral"), std::string::npos);
  EXPECT_NE(run.out.find("validation issues        0\n"), std::string::npos);
  const auto back = read_tetgen(output);
  ASSERT_TRUE(back) << back.error().describe();
  EXPECT_EQ(back->points.size(), 10u);
  EXPECT_EQ(back->regions.size(), 1u);
  std::filesystem::remove(output);
}

TEST(ImportCommand, QuietPrintsNothingOnSuccess) {
  const CliRun run = run_cli((test::corpus_dir() / "poly3d" / "td-wedge-5.smesh").string() + " --quiet");
  EXPECT_EQ(run.exit_code, 0) << run.err;
  EXPECT_TRUE(run.out.empty());
}

TEST(ImportCommand, RefusedInputExitsWithOneAndNamesTheDefect) {
  const CliRun run = run_cli((test::corpus_dir() / "surface" / "trimesh-teapot.stl").string());
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.err.find("open: boundary edges"), std::string::npos) << run.err;
  const CliRun missing = run_cli("/nonexistent/part.off");
  EXPECT_EQ(missing.exit_code, 1);
  EXPECT_NE(missing.err.find("cannot open"), std::string::npos) << missing.err;
}

TEST(ImportCommand, CadTessellationAndGluingOptionsReachTheImporter) {
  const std::string cylinders = (test::corpus_dir() / "step" / "pocc-eight-cyl.stp").string();
  const CliRun fine = run_cli(cylinders + " --deflection 0.0005 --angle 10");
  const CliRun coarse = run_cli(cylinders + " --deflection 0.01 --angle 60");
  ASSERT_EQ(fine.exit_code, 0) << fine.err;
  ASSERT_EQ(coarse.exit_code, 0) << coarse.err;
  const long fine_vertices = summary_count(fine.out, "vertices"), coarse_vertices = summary_count(coarse.out, "vertices");
  EXPECT_GT(coarse_vertices, 0) << coarse.out;
  EXPECT_GT(fine_vertices, 2 * coarse_vertices) << fine.out << coarse.out;
  // as-mechanism.stp: three touching solids. Glued, they share their interface facets;
  // with --no-glue each solid keeps its own copy of the contact faces, and the PLC is
  // refused for the coincident vertices and overlapping facets that leaves.
  const std::string mechanism = (test::corpus_dir() / "step" / "as-mechanism.stp").string();
  const CliRun glued = run_cli(mechanism);
  ASSERT_EQ(glued.exit_code, 0) << glued.err;
  EXPECT_EQ(summary_count(glued.out, "regions"), 3) << glued.out;
  EXPECT_NE(glued.out.find("validation issues        0\n"), std::string::npos) << glued.out;
  const CliRun unglued = run_cli(mechanism + " --no-glue");
  EXPECT_EQ(unglued.exit_code, 1) << unglued.out;
  EXPECT_NE(unglued.err.find("DuplicateVertex"), std::string::npos) << unglued.err;
}

TEST(ImportCommand, PlaneToleranceMergesPlanesAndSaysSo) {
  // ulp_planes.step: a block placed one ulp above its base (tests/importers/step/
  // plane_tolerance_test.cpp). Merged by default, with a warning; --plane-tol 0 keeps the
  // two planes and triangulates the faces at the contact.
  const std::string planes = (test::test_data_dir() / "step" / "ulp_planes.step").string();
  const CliRun merged = run_cli(planes);
  ASSERT_EQ(merged.exit_code, 0) << merged.err;
  EXPECT_NE(merged.err.find("1 coordinate-plane value(s) merged"), std::string::npos) << merged.err;
  EXPECT_NE(merged.out.find("facets                   12 (13 polygons)\n"), std::string::npos) << merged.out;
  const CliRun apart = run_cli(planes + " --plane-tol 0");
  ASSERT_EQ(apart.exit_code, 0) << apart.err;
  EXPECT_EQ(apart.err.find("merged"), std::string::npos) << apart.err;
  EXPECT_GT(summary_count(apart.out, "facets"), 12) << apart.out;
}

// The program reads CAD files through the module libdelmesh_cad.so at ../lib/delmesh from
// itself (tools/cad_module/), loaded only for such files: without it the error names the
// module; with a copy of it beside a copy of the program, the copy reads STEP.
TEST(ImportCommand, CadModuleIsFoundBesideTheProgramOrNamedWhenMissing) {
#ifndef DELMESH_CAD_MODULE_PATH
  GTEST_SKIP() << "built without the CAD import module (DELMESH_WITH_OCCT=OFF)";
#else
  const test::ScratchDir dir("cad-module");
  std::filesystem::create_directories(dir / "bin");
  const std::filesystem::path program = dir / "bin" / "delmesh";
  std::filesystem::copy_file(test::cli_path(), program);
  const std::string planes = (test::test_data_dir() / "step" / "ulp_planes.step").string();
  const CliRun missing = run_import(program, planes);
  EXPECT_EQ(missing.exit_code, 1) << missing.out;
  const std::filesystem::path module = dir.path() / "lib" / "delmesh" / "libdelmesh_cad.so";
  EXPECT_NE(missing.err.find("the CAD import module '" + module.string() + "' cannot be loaded"), std::string::npos)
      << missing.err;
  std::filesystem::create_directories(module.parent_path());
  std::filesystem::copy_file(DELMESH_CAD_MODULE_PATH, module);
  const CliRun found = run_import(program, planes);
  EXPECT_EQ(found.exit_code, 0) << found.err;
  EXPECT_NE(found.out.find("facets                   12 (13 polygons)\n"), std::string::npos) << found.out;
#endif
}

// Only the module needs OpenCASCADE: the program's start loads none of its libraries
// (relocating them cost some 50 ms of CPU per run).
TEST(ImportCommand, ProgramLoadsNoOpenCascadeLibrary) {
#ifndef DELMESH_CAD_MODULE_PATH
  GTEST_SKIP() << "built without the CAD import module (DELMESH_WITH_OCCT=OFF)";
#else
  const test::ScratchDir dir("cad-libraries");
  const std::string command =
      "LD_TRACE_LOADED_OBJECTS=1 " + test::cli_path().string() + " >" + (dir / "libraries").string();
  ASSERT_EQ(std::system(command.c_str()), 0);
  const std::string libraries = test::read_file(dir / "libraries");
  EXPECT_NE(libraries.find("libc.so"), std::string::npos) << libraries;
  EXPECT_EQ(libraries.find("libTK"), std::string::npos) << libraries;
#endif
}

TEST(ImportCommand, UsageErrorsExitWithTwo) {
  EXPECT_EQ(run_cli("").exit_code, 2);
  EXPECT_EQ(run_cli("a.off --frobnicate").exit_code, 2);
  EXPECT_EQ(run_cli("a.off --weld -1").exit_code, 2);
  EXPECT_EQ(run_cli("a.step --deflection 0").exit_code, 2);
  EXPECT_EQ(run_cli("a.step --deflection 1").exit_code, 2);
  EXPECT_EQ(run_cli("a.step --angle 180").exit_code, 2);
  EXPECT_EQ(run_cli("a.step --angle").exit_code, 2);
  EXPECT_EQ(run_cli("a.step --plane-tol -1").exit_code, 2);
  EXPECT_EQ(run_cli("a.step --plane-tol 0.001").exit_code, 2);
  EXPECT_EQ(run_cli("a.step --plane-tol").exit_code, 2);
  EXPECT_EQ(run_cli("--help").exit_code, 0);
}

}  // namespace
}  // namespace delmesh
