// Every parser on thousands of corrupted inputs (seeded byte flips, insertions, deletions
// and truncations of valid files): each call must return a value or an Error, never
// crash, hang or throw. A deterministic stand-in for fuzzing that runs in every build.
#include <gtest/gtest.h>

#include <functional>
#include <random>
#include <string>

#include "importers/line_reader.h"
#include "importers/surface/surface_importer.h"
#include "importers/tetgen/tetgen_reader.h"
#include "tests/support/test_paths.h"

namespace delmesh {
namespace {

std::string mutate(const std::string& input, std::mt19937& rng) {
  std::string s = input;
  std::uniform_int_distribution<int> op(0, 4), byte(0, 255);
  const int edits = 1 + static_cast<int>(rng() % 4);
  for (int e = 0; e < edits && !s.empty(); ++e) {
    const std::size_t at = rng() % s.size();
    switch (op(rng)) {
      case 0: s[at] = static_cast<char>(byte(rng)); break;
      case 1: s.insert(at, 1, "0123456789 -.e\n#"[rng() % 16]); break;
      case 2: s.erase(at, 1 + rng() % 8); break;
      case 3: s.resize(at); break;
      default: s.insert(at, s.substr(rng() % s.size(), 1 + rng() % 16)); break;
    }
  }
  return s;
}

void hammer(const std::string& seed_text, const std::function<void(const std::string&)>& parse, int rounds) {
  std::mt19937 rng(12345);
  for (int i = 0; i < rounds; ++i) {
    const std::string input = mutate(seed_text, rng);
    EXPECT_NO_THROW(parse(input)) << "round " << i;
  }
}

std::string corpus_text(const char* relative) {
  auto text = read_text(test::corpus_dir() / relative);
  EXPECT_TRUE(text) << relative;
  return text ? *text : std::string();
}

TEST(ParserRobustness, TetgenSmeshAndPoly) {
  const std::string smesh = corpus_text("poly3d/td-slit-1.smesh");
  hammer(smesh, [](const std::string& s) { (void)parse_tetgen(s, TetgenFileKind::Smesh, "f.smesh"); }, 3000);
  hammer(smesh, [](const std::string& s) { (void)parse_tetgen(s, TetgenFileKind::Poly, "f.poly"); }, 3000);
}

TEST(ParserRobustness, SurfaceFormatsThroughTheWholeImport) {
  const std::string off = corpus_text("surface/cgal-step.off");
  const std::string stl = "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\n"
                          "endloop\nendfacet\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 0 1 0\n"
                          "vertex 0 0 1\nendloop\nendfacet\nendsolid t\n";
  const std::string obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 2 3 4\nf 3 1 4\n";
  const std::string ply =
      "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
      "element face 4\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n"
      "3 0 2 1\n3 0 1 3\n3 1 2 3\n3 2 0 3\n";
  auto import = [](Expected<SurfaceSoup> soup) {
    if (soup) (void)surface_to_plc(*soup, "f", {});
  };
  hammer(off, [&](const std::string& s) { import(parse_off(s, "f.off")); }, 2000);
  hammer(stl, [&](const std::string& s) { import(parse_stl(s, "f.stl")); }, 2000);
  hammer(obj, [&](const std::string& s) { import(parse_obj(s, "f.obj")); }, 2000);
  hammer(ply, [&](const std::string& s) { import(parse_ply(s, "f.ply")); }, 2000);
  // Binary STL: corrupt a 12-triangle file byte-wise (header count included).
  std::string binary(84 + 50 * 4, '\0');
  binary[80] = 4;
  hammer(binary, [&](const std::string& s) { import(parse_stl(s, "b.stl")); }, 2000);
}

TEST(ParserRobustness, HugeCountsWithoutDataEndQuickly) {
  const auto ply = parse_ply("ply\nformat binary_little_endian 1.0\nelement nothing 18446744073709551615\n"
                             "element vertex 100000000000\nproperty float x\nproperty float y\nproperty float z\n"
                             "end_header\n",
                             "h.ply");
  ASSERT_FALSE(ply);
  EXPECT_NE(ply.error().message.find("end of binary data"), std::string::npos);
  EXPECT_FALSE(parse_off("OFF\n3 99999999999999 0\n0 0 0\n1 0 0\n0 1 0\n", "h.off"));
  EXPECT_FALSE(parse_tetgen("99999999999999 3 0 0\n", TetgenFileKind::Poly, "h.poly"));
}

}  // namespace
}  // namespace delmesh
