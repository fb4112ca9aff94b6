// CAD colours from STEP files through the importer and out of every writer that can carry
// them: instance (component) and SHUO colours of an assembly override the product's
// colour, face colours of the product stay (importers/step/cad_reader.cpp); the PLC
// writers (.off per-face colours, .vtu "color", .poly comment table) and the tet mesh
// writers (.vtu boundary_color/region_color, .ovm face_color/cell_color) write the colours
// the XDE document holds.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "importers/import.h"
#include "importers/plc_writer.h"
#include "importers/step/step_importer.h"
#include "refiners/tet3d/mesh_plc.h"
#include "tests/support/scratch_dir.h"
#include "tests/support/test_paths.h"
#include "toolkit/mesh3d/tetra_mesh_writer.h"

namespace delmesh {
namespace {

namespace fs = std::filesystem;
using Rgb = std::array<double, 3>;

bool near(const Plc::Color& c, const Rgb& rgb) {
  return std::abs(c.r - rgb[0]) < 1e-6 && std::abs(c.g - rgb[1]) < 1e-6 && std::abs(c.b - rgb[2]) < 1e-6;
}

std::string slurp(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

/// A colour as the bytes every writer writes (components in [0, 1] times 255, rounded).
std::array<int, 3> bytes_of(const Plc::Color& c) {
  return {static_cast<int>(std::lround(c.r * 255)), static_cast<int>(std::lround(c.g * 255)),
          static_cast<int>(std::lround(c.b * 255))};
}

/// The `count` RGB tuples of the 3-component cell data array `name` of a .vtu.
std::vector<std::array<int, 3>> vtu_rgb(const std::string& vtu, const std::string& name, std::size_t count) {
  const std::size_t at = vtu.find("Name=\"" + name + "\" NumberOfComponents=\"3\"");
  if (at == std::string::npos) return {};
  std::istringstream in(vtu.substr(vtu.find('>', at) + 1));
  std::vector<std::array<int, 3>> tuples(count);
  for (auto& t : tuples) in >> t[0] >> t[1] >> t[2];
  return tuples;
}

// tests/data/step/instance_colours.step (written with OCCT's XDE, see LICENSES.md):
// product "block", a unit cube coloured grey whose face x = xmin is red and named "inlet"
// (a named ADVANCED_FACE); assembly "pair"
// places it at (0,0,0) and, as an instance coloured green, at (2,0,0); assembly "top"
// places "pair" at z = 0 and z = 2, with a SHUO colouring the (0,0,2) block blue.
constexpr Rgb kGrey{0.5, 0.5, 0.5}, kRed{1, 0, 0}, kGreen{0, 1, 0}, kBlue{0, 0, 1};

/// The expected colour of the block with lower corner (x, z).
Rgb block_color(double x, double z) {
  if (x > 1) return kGreen;       // the green instance, in both placements of "pair"
  return z > 1 ? kBlue : kGrey;   // SHUO for the upper left block, else the product's
}

TEST(StepColours, InstanceAndShuoColoursOverrideTheProductColourAndFaceColoursAndNamesStay) {
  const Expected<Plc> plc = import_step(test::test_data_dir() / "step" / "instance_colours.step", StepImportOptions{});
  ASSERT_TRUE(plc.has_value()) << plc.error().describe();
  ASSERT_EQ(plc->regions.size(), 4u);
  std::set<std::pair<int, int>> corners;
  for (const Plc::Region& region : plc->regions) {
    const double x = std::floor(region.point.x()), z = std::floor(region.point.z());
    corners.emplace(static_cast<int>(x), static_cast<int>(z));
    const auto color = plc->region_colors.find(region.id);
    ASSERT_NE(color, plc->region_colors.end()) << "region " << region.id;
    EXPECT_TRUE(near(color->second, block_color(x, z)))
        << "region " << region.id << " at x " << x << " z " << z << ": " << color->second.r << " "
        << color->second.g << " " << color->second.b;
    EXPECT_EQ(plc->region_names.at(region.id), "block");
  }
  EXPECT_EQ(corners, (std::set<std::pair<int, int>>{{0, 0}, {2, 0}, {0, 2}, {2, 2}}));

  ASSERT_EQ(plc->facet_marker_colors.size(), 24u);
  std::map<int, int> red_faces_per_block;
  for (const Plc::Facet& facet : plc->facets) {
    Vec3 lo = plc->points[facet.polygons[0][0]], hi = lo;
    for (const auto& polygon : facet.polygons)
      for (std::uint32_t v : polygon) {
        lo = lo.cwiseMin(plc->points[v]);
        hi = hi.cwiseMax(plc->points[v]);
      }
    const double x0 = lo.x() > 1.5 ? 2 : 0, z0 = lo.z() > 1.5 ? 2 : 0;
    const bool xmin_face = hi.x() == x0;
    const auto color = plc->facet_marker_colors.find(facet.marker);
    ASSERT_NE(color, plc->facet_marker_colors.end()) << "marker " << facet.marker;
    EXPECT_TRUE(near(color->second, xmin_face ? kRed : block_color(x0, z0)))
        << "facet of marker " << facet.marker << " in block x " << x0 << " z " << z0;
    red_faces_per_block[static_cast<int>(x0 + z0 / 2)] += xmin_face;
    const auto name = plc->facet_marker_names.find(facet.marker);
    if (xmin_face) {
      ASSERT_NE(name, plc->facet_marker_names.end()) << "marker " << facet.marker;
      EXPECT_EQ(name->second, "inlet");
    } else {
      EXPECT_EQ(name, plc->facet_marker_names.end()) << "marker " << facet.marker << " " << name->second;
    }
  }
  EXPECT_EQ(red_faces_per_block, (std::map<int, int>{{0, 1}, {1, 1}, {2, 1}, {3, 1}}));
}

class StepColourWriters : public ::testing::TestWithParam<fs::path> {
 protected:
  void SetUp() override { scratch.emplace("step_colours"); }
  std::optional<test::ScratchDir> scratch;
};

TEST_P(StepColourWriters, ColoursOfTheXdeDocumentAreInTheWrittenFiles) {
  const Expected<Plc> plc = import_step(GetParam(), StepImportOptions{});
  ASSERT_TRUE(plc.has_value()) << plc.error().describe();
  ASSERT_FALSE(plc->facet_marker_colors.empty());
  ASSERT_FALSE(plc->region_colors.empty());
  const fs::path dir = scratch->path();

  // PLC .off: one colour per facet, that of its marker.
  ASSERT_TRUE(write_plc(*plc, dir / "plc.off"));
  {
    std::istringstream off(slurp(dir / "plc.off"));
    std::string magic;
    std::size_t nv = 0, nf = 0, ne = 0;
    off >> magic >> nv >> nf >> ne;
    ASSERT_EQ(nf, plc->facets.size());
    std::string line;
    std::getline(off, line);
    for (std::size_t v = 0; v < nv; ++v) std::getline(off, line);
    for (std::size_t f = 0; f < nf; ++f) {
      std::getline(off, line);
      std::istringstream face(line);
      std::size_t n = 0, id = 0;
      face >> n;
      for (std::size_t k = 0; k < n; ++k) face >> id;
      std::array<int, 3> rgb{-1, -1, -1};
      face >> rgb[0] >> rgb[1] >> rgb[2];
      EXPECT_EQ(rgb, bytes_of(plc->facet_marker_colors.at(plc->facets[f].marker))) << "face " << f;
    }
    // The OFF reader skips the colours: the file imports back with as many facets.
    ImportOptions import_options;
    import_options.merge_coplanar = false;
    const Expected<Plc> back = import_file(dir / "plc.off", import_options);
    ASSERT_TRUE(back.has_value()) << back.error().describe();
  }

  // PLC .vtu: cell data "color" per polygon.
  ASSERT_TRUE(write_plc(*plc, dir / "plc.vtu"));
  {
    std::vector<int> polygon_marker;
    for (const auto& facet : plc->facets)
      for (const auto& polygon : facet.polygons)
        if (polygon.size() >= 2) polygon_marker.push_back(facet.marker);
    const auto colors = vtu_rgb(slurp(dir / "plc.vtu"), "color", polygon_marker.size());
    ASSERT_EQ(colors.size(), polygon_marker.size());
    for (std::size_t c = 0; c < colors.size(); ++c)
      EXPECT_EQ(colors[c], bytes_of(plc->facet_marker_colors.at(polygon_marker[c]))) << "cell " << c;
  }

  // PLC .poly: the tables in comment lines; the file reads back unchanged.
  ASSERT_TRUE(write_plc(*plc, dir / "plc.poly"));
  {
    const std::string poly = slurp(dir / "plc.poly");
    const auto& [marker, color] = *plc->facet_marker_colors.begin();
    EXPECT_NE(poly.find("# facet_marker " + std::to_string(marker)), std::string::npos);
    const Expected<Plc> back = import_file(dir / "plc.poly", ImportOptions{});
    ASSERT_TRUE(back.has_value()) << back.error().describe();
    EXPECT_EQ(back->facets.size(), plc->facets.size());
  }

  // Tet mesh .vtu and .ovm.
  MeshOptions options;
  options.quality = false;
  const Expected<MeshResult> result = mesh_plc(*plc, options);
  ASSERT_TRUE(result.has_value()) << result.error().describe();
  const TetraMesh& mesh = result->mesh;
  EXPECT_EQ(mesh.marker_colors.size(), plc->facet_marker_colors.size());
  EXPECT_EQ(mesh.region_colors.size(), plc->region_colors.size());
  ASSERT_TRUE(write_tetra_mesh(dir / "mesh.vtu", mesh));
  {
    const std::string vtu = slurp(dir / "mesh.vtu");
    const std::size_t ntet = mesh.tets.size(), ntri = mesh.boundary_faces.size();
    const auto boundary = vtu_rgb(vtu, "boundary_color", ntet + ntri);
    const auto region = vtu_rgb(vtu, "region_color", ntet + ntri);
    ASSERT_EQ(boundary.size(), ntet + ntri);
    ASSERT_EQ(region.size(), ntet + ntri);
    for (std::size_t t = 0; t < ntet; ++t)
      ASSERT_EQ(region[t], bytes_of(plc->region_colors.at(mesh.region_of(t)))) << "tet " << t;
    for (std::size_t f = 0; f < ntri; ++f)
      ASSERT_EQ(boundary[ntet + f], bytes_of(plc->facet_marker_colors.at(mesh.boundary_markers[f]))) << "face " << f;
  }
  ASSERT_TRUE(write_tetra_mesh(dir / "mesh.ovm", mesh));
  {
    const std::string ovm = slurp(dir / "mesh.ovm");
    const std::string key = "FProp vec4f \"face_color\"\n";
    const std::size_t at = ovm.find(key);
    ASSERT_NE(at, std::string::npos);
    std::istringstream in(ovm.substr(at + key.size()));
    std::multiset<std::array<int, 3>> written, expected;
    double r, g, b, a;
    while (in >> r >> g >> b >> a) {
      if (a == 1) written.insert({static_cast<int>(std::lround(r * 255)), static_cast<int>(std::lround(g * 255)),
                                  static_cast<int>(std::lround(b * 255))});
    }
    for (int m : mesh.boundary_markers) expected.insert(bytes_of(plc->facet_marker_colors.at(m)));
    EXPECT_EQ(written, expected);
  }
}

INSTANTIATE_TEST_SUITE_P(ColouredFiles, StepColourWriters,
                         ::testing::Values(test::test_data_dir() / "step" / "instance_colours.step",
                                           test::corpus_dir() / "step" / "gmsh-boundary-colors.stp"));

}  // namespace
}  // namespace delmesh
