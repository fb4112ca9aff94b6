// Tet mesh quality measures and writers: a unit cube cut into the six Kuhn tetrahedra,
// two regions and one marker per cube side, written in every format and read back with
// small independent parsers that check counts, numbering, orientation and tags.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <optional>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "tests/support/scratch_dir.h"
#include "toolkit/mesh3d/tetra_mesh_writer.h"
#include "toolkit/quality/tet_quality.h"

namespace delmesh {
namespace {

namespace fs = std::filesystem;

/// Unit cube, vertices indexed by bits (x = bit 0, y = bit 1, z = bit 2), six tets around
/// the diagonal 0-7; tets 0-2 in region 1, 3-5 in region 2; boundary faces outward with
/// markers 1..6 for x=0, x=1, y=0, y=1, z=0, z=1.
TetraMesh kuhn_cube() {
  TetraMesh mesh;
  for (int i = 0; i < 8; ++i) mesh.points.emplace_back(i & 1, (i >> 1) & 1, (i >> 2) & 1);
  const int axes[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  for (const auto& a : axes) {
    const std::uint32_t v1 = 1u << a[0], v2 = v1 | (1u << a[1]);
    std::array<std::uint32_t, 4> t{0, v1, v2, 7};
    if (signed_volume(mesh.points[t[0]], mesh.points[t[1]], mesh.points[t[2]], mesh.points[t[3]]) < 0)
      std::swap(t[1], t[2]);
    mesh.tets.push_back(t);
  }
  mesh.tet_regions = {1, 1, 1, 2, 2, 2};
  // boundary: faces of exactly one tet, outward cycles
  std::map<FaceKey, std::pair<std::array<std::uint32_t, 3>, int>> count;
  for (const auto& t : mesh.tets) {
    const std::array<std::array<std::uint32_t, 3>, 4> outward{
        {{t[1], t[2], t[3]}, {t[0], t[3], t[2]}, {t[0], t[1], t[3]}, {t[0], t[2], t[1]}}};
    for (const auto& f : outward) {
      auto& entry = count[face_key(f[0], f[1], f[2])];
      entry.first = f;
      ++entry.second;
    }
  }
  for (const auto& [key, entry] : count) {
    if (entry.second != 1) continue;
    const auto& f = entry.first;
    int marker = 0;
    for (int axis = 0; axis < 3 && marker == 0; ++axis)
      for (int side = 0; side < 2; ++side)
        if (mesh.points[f[0]][axis] == side && mesh.points[f[1]][axis] == side && mesh.points[f[2]][axis] == side)
          marker = 1 + 2 * axis + side;
    mesh.boundary_faces.push_back(f);
    mesh.boundary_markers.push_back(marker);
  }
  mesh.marker_names = {{1, "inlet"}, {2, "outlet"}};
  mesh.region_names = {{1, "steel part"}};
  return mesh;
}

std::string slurp(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

class TetraWritersTest : public ::testing::Test {
 protected:
  void SetUp() override {
    scratch.emplace("writers");
    dir = scratch->path();
  }
  void TearDown() override { scratch.reset(); }
  std::optional<test::ScratchDir> scratch;
  fs::path dir;
  TetraMesh mesh = kuhn_cube();
};

TEST(TetQualityTest, MeasuresOfKnownTetrahedra) {
  const Vec3 a(1, 1, 1), b(1, -1, -1), c(-1, 1, -1), d(-1, -1, 1);  // regular
  const double volume = std::abs(signed_volume(a, b, c, d));
  EXPECT_NEAR(volume, 8.0 / 3.0, 1e-12);
  EXPECT_NEAR(radius_edge_ratio(a, b, c, d), std::sqrt(6.0) / 4.0, 1e-12);
  for (double angle : dihedral_angles_deg(a, b, c, d)) EXPECT_NEAR(angle, 70.528779365509308, 1e-9);
  // corner tet: right angles at the three axis edges, arccos(1/sqrt(3)) at the others
  const Vec3 o(0, 0, 0), x(1, 0, 0), y(0, 1, 0), z(0, 0, 1);
  EXPECT_GT(signed_volume(o, x, y, z), 0);
  const auto angles = dihedral_angles_deg(o, x, y, z);
  EXPECT_NEAR(angles[0], 90, 1e-9);  // edge ox
  EXPECT_NEAR(angles[1], 90, 1e-9);  // edge oy
  EXPECT_NEAR(angles[2], 90, 1e-9);  // edge oz
  EXPECT_NEAR(angles[3], std::acos(1.0 / std::sqrt(3.0)) * 180.0 / M_PI, 1e-9);  // edge xy
  const Vec3 flat(0.5, 0.5, 0);
  EXPECT_TRUE(std::isinf(circumradius(o, x, y, flat)));
}

TEST_F(TetraWritersTest, QualityReportOfTheCube) {
  ASSERT_EQ(mesh.boundary_faces.size(), 12u);
  const TetQualityReport report = tet_quality_report(mesh, 0.8, 30, 100);
  EXPECT_EQ(report.tets, 6u);
  EXPECT_NEAR(report.total_volume, 1.0, 1e-15);
  EXPECT_NEAR(report.min_volume, 1.0 / 6.0, 1e-15);
  EXPECT_NEAR(report.max_dihedral_deg, 90.0, 1e-9);
  EXPECT_NEAR(report.min_dihedral_deg, 45.0, 1e-9);
  EXPECT_NEAR(report.max_radius_edge, std::sqrt(3.0) / 2.0, 1e-12);
  EXPECT_EQ(report.above_radius_edge, 6u);  // sqrt(3)/2 > 0.8
  EXPECT_EQ(report.outside_dihedral_window, 0u);
  std::size_t total = 0;
  for (auto c : report.radius_edge_counts) total += c;
  EXPECT_EQ(total, 6u);
  for (const auto& t : mesh.tets) EXPECT_GT(signed_volume(mesh.points[t[0]], mesh.points[t[1]], mesh.points[t[2]], mesh.points[t[3]]), 0);
}

TEST_F(TetraWritersTest, TetgenFilesAreOneBasedWithRegionsAndMarkers) {
  auto written = write_tetra_mesh(dir / "cube.node", mesh);
  ASSERT_TRUE(written) << written.error().describe();
  ASSERT_EQ(written->size(), 3u);
  std::istringstream node(slurp(dir / "cube.node")), ele(slurp(dir / "cube.ele")), face(slurp(dir / "cube.face"));
  int n, dim, attrs, markers;
  node >> n >> dim >> attrs >> markers;
  EXPECT_EQ(n, 8);
  EXPECT_EQ(dim, 3);
  int id;
  double x, y, z;
  node >> id >> x >> y >> z;
  EXPECT_EQ(id, 1);
  int ntet, per, nattr;
  ele >> ntet >> per >> nattr;
  EXPECT_EQ(ntet, 6);
  EXPECT_EQ(per, 4);
  EXPECT_EQ(nattr, 1);
  for (int t = 0; t < 6; ++t) {
    int i, a, b, c, d, region;
    ele >> i >> a >> b >> c >> d >> region;
    EXPECT_EQ(i, t + 1);
    EXPECT_EQ(static_cast<std::uint32_t>(a - 1), mesh.tets[t][0]);
    EXPECT_EQ(static_cast<std::uint32_t>(d - 1), mesh.tets[t][3]);
    EXPECT_EQ(region, mesh.tet_regions[t]);
  }
  int nface, has_markers;
  face >> nface >> has_markers;
  EXPECT_EQ(nface, 12);
  std::set<int> seen;
  for (int f = 0; f < nface; ++f) {
    int i, a, b, c, marker;
    face >> i >> a >> b >> c >> marker;
    seen.insert(marker);
  }
  EXPECT_EQ(seen, (std::set<int>{1, 2, 3, 4, 5, 6}));
  auto zero = write_tetgen(dir / "zero", mesh, true);
  ASSERT_TRUE(zero);
  std::istringstream zn(slurp(dir / "zero.node"));
  zn >> n >> dim >> attrs >> markers >> id;
  EXPECT_EQ(id, 0);
}

TEST_F(TetraWritersTest, GmshFilesCarryNamedPhysicalGroups) {
  for (int version : {41, 22}) {
    const fs::path path = dir / ("cube" + std::to_string(version) + ".msh");
    TetraWriteOptions options;
    options.gmsh_version = version;
    ASSERT_TRUE(write_tetra_mesh(path, mesh, options));
    const std::string text = slurp(path);
    EXPECT_NE(text.find(version == 41 ? "4.1 0 8" : "2.2 0 8"), std::string::npos);
    EXPECT_NE(text.find("2 1 \"inlet\""), std::string::npos);
    EXPECT_NE(text.find("2 2 \"outlet\""), std::string::npos);
    EXPECT_NE(text.find("2 3 \"facet_3\""), std::string::npos);
    EXPECT_NE(text.find("3 1 \"steel part\""), std::string::npos);
    EXPECT_NE(text.find("3 2 \"region_2\""), std::string::npos);
    // element count line after $Elements
    std::istringstream in(text.substr(text.find("$Elements") + 10));
    if (version == 41) {
      std::size_t blocks, count, lo, hi;
      in >> blocks >> count >> lo >> hi;
      EXPECT_EQ(blocks, 8u);  // 6 surfaces + 2 volumes
      EXPECT_EQ(count, 18u);
      EXPECT_EQ(lo, 1u);
      EXPECT_EQ(hi, 18u);
      std::istringstream entities(text.substr(text.find("$Entities") + 10));
      std::size_t np, nc, ns, nv;
      entities >> np >> nc >> ns >> nv;
      EXPECT_EQ(ns, 6u);
      EXPECT_EQ(nv, 2u);
    } else {
      std::size_t count;
      in >> count;
      EXPECT_EQ(count, 18u);
      std::size_t id, type, ntags, phys, elem, a, b, c, d;
      for (int i = 0; i < 12; ++i) in >> id >> type >> ntags >> phys >> elem >> a >> b >> c;
      in >> id >> type >> ntags >> phys >> elem >> a >> b >> c >> d;
      EXPECT_EQ(type, 4u);
      EXPECT_EQ(phys, 1u);
      EXPECT_EQ(a - 1, mesh.tets[0][0]);
    }
  }
}

TEST_F(TetraWritersTest, MeditAndVtuContainEveryElement) {
  ASSERT_TRUE(write_tetra_mesh(dir / "cube.mesh", mesh));
  const std::string medit = slurp(dir / "cube.mesh");
  std::istringstream tets(medit.substr(medit.find("Tetrahedra") + 10));
  int count, a, b, c, d, ref;
  tets >> count >> a >> b >> c >> d >> ref;
  EXPECT_EQ(count, 6);
  EXPECT_EQ(static_cast<std::uint32_t>(a - 1), mesh.tets[0][0]);
  EXPECT_EQ(ref, 1);
  EXPECT_NE(medit.find("End"), std::string::npos);

  ASSERT_TRUE(write_tetra_mesh(dir / "cube.vtu", mesh));
  const std::string vtu = slurp(dir / "cube.vtu");
  EXPECT_NE(vtu.find("NumberOfPoints=\"8\" NumberOfCells=\"18\""), std::string::npos);
  for (const char* name : {"\"region\"", "\"boundary_marker\"", "\"radius_edge\"", "\"min_dihedral\""})
    EXPECT_NE(vtu.find(name), std::string::npos) << name;
}

TEST_F(TetraWritersTest, AbaqusSurfacesNameTheRightElementFaces) {
  ASSERT_TRUE(write_tetra_mesh(dir / "cube.inp", mesh));
  std::istringstream in(slurp(dir / "cube.inp"));
  std::string line, surface;
  std::map<std::string, int> faces_per_surface;
  std::set<std::string> elsets;
  // C3D4 faces: local node triples (1-based) of S1..S4
  const int face_nodes[4][3] = {{1, 2, 3}, {1, 4, 2}, {2, 4, 3}, {3, 4, 1}};
  std::map<std::string, int> marker_of{{"inlet", 1}, {"outlet", 2}};
  for (int m = 3; m <= 6; ++m) marker_of["facet_" + std::to_string(m)] = m;
  while (std::getline(in, line)) {
    if (line.rfind("*Element", 0) == 0) {
      elsets.insert(line.substr(line.find("elset=") + 6));
      surface.clear();
    } else if (line.rfind("*Surface", 0) == 0) {
      surface = line.substr(line.find("name=") + 5);
    } else if (!surface.empty() && !line.empty() && line[0] != '*') {
      const int element = std::stoi(line.substr(0, line.find(',')));
      const int side = std::stoi(line.substr(line.find('S') + 1));
      const auto& t = mesh.tets[element - 1];
      const FaceKey key = face_key(t[face_nodes[side - 1][0] - 1], t[face_nodes[side - 1][1] - 1],
                                   t[face_nodes[side - 1][2] - 1]);
      bool found = false;
      for (std::size_t f = 0; f < mesh.boundary_faces.size(); ++f) {
        const auto& bf = mesh.boundary_faces[f];
        if (face_key(bf[0], bf[1], bf[2]) == key) {
          EXPECT_EQ(mesh.boundary_markers[f], marker_of.at(surface)) << line;
          found = true;
        }
      }
      EXPECT_TRUE(found) << line;
      ++faces_per_surface[surface];
    }
  }
  EXPECT_EQ(elsets, (std::set<std::string>{"steel_part", "region_2"}));
  EXPECT_EQ(faces_per_surface.size(), 6u);
  for (const auto& [name, n] : faces_per_surface) EXPECT_EQ(n, 2) << name;
}

TEST_F(TetraWritersTest, AbaqusSetNamesAreUniqueWhenNamesRepeat) {
  mesh.marker_names = {{1, "PartBody"}, {2, "PartBody"}, {3, "Part Body"}};
  mesh.region_names = {{1, "nut"}, {2, "nut"}};
  ASSERT_TRUE(write_tetra_mesh(dir / "same.inp", mesh));
  std::istringstream in(slurp(dir / "same.inp"));
  std::string line;
  std::vector<std::string> surfaces, elsets;
  while (std::getline(in, line)) {
    if (line.rfind("*Surface", 0) == 0) surfaces.push_back(line.substr(line.find("name=") + 5));
    if (line.rfind("*Element", 0) == 0) elsets.push_back(line.substr(line.find("elset=") + 6));
  }
  EXPECT_EQ(surfaces, (std::vector<std::string>{"PartBody", "PartBody_2", "Part_Body", "facet_4", "facet_5",
                                                "facet_6"}));
  EXPECT_EQ(elsets, (std::vector<std::string>{"nut", "nut_2"}));
}

TEST_F(TetraWritersTest, OvmHalfFacesPointIntoTheirCells) {
  ASSERT_TRUE(write_tetra_mesh(dir / "cube.ovm", mesh));
  std::istringstream in(slurp(dir / "cube.ovm"));
  std::string word;
  std::getline(in, word);
  EXPECT_EQ(word, "OVM ASCII");
  std::size_t n;
  in >> word >> n;
  ASSERT_EQ(word, "Vertices");
  std::vector<Vec3> points(n);
  for (auto& p : points) in >> p.x() >> p.y() >> p.z();
  in >> word >> n;
  ASSERT_EQ(word, "Edges");
  std::vector<std::array<std::uint32_t, 2>> edges(n);
  for (auto& e : edges) in >> e[0] >> e[1];
  EXPECT_EQ(n, 19u);  // 12 cube edges + 6 face diagonals + the main diagonal
  auto from = [&](std::uint32_t he) { return edges[he / 2][he % 2]; };
  auto to = [&](std::uint32_t he) { return edges[he / 2][1 - he % 2]; };
  in >> word >> n;
  ASSERT_EQ(word, "Faces");
  std::vector<std::array<std::uint32_t, 3>> faces(n);
  for (auto& f : faces) {
    int k;
    in >> k >> f[0] >> f[1] >> f[2];
    ASSERT_EQ(k, 3);
    for (int i = 0; i < 3; ++i) ASSERT_EQ(to(f[i]), from(f[(i + 1) % 3]));  // closed chain
  }
  in >> word >> n;
  ASSERT_EQ(word, "Polyhedra");
  std::map<std::uint32_t, int> halfface_use;
  for (std::size_t c = 0; c < n; ++c) {
    int k;
    in >> k;
    ASSERT_EQ(k, 4);
    Vec3 centroid = Vec3::Zero();
    for (auto v : mesh.tets[c]) centroid += points[v] / 4.0;
    for (int i = 0; i < 4; ++i) {
      std::uint32_t hf;
      in >> hf;
      ++halfface_use[hf];
      const auto& f = faces[hf / 2];
      Vec3 p0 = points[from(f[0])], p1 = points[from(f[1])], p2 = points[from(f[2])];
      if (hf % 2) std::swap(p1, p2);
      const Vec3 normal = (p1 - p0).cross(p2 - p0);
      EXPECT_GT(normal.dot(centroid - p0), 0) << "cell " << c << " half-face " << hf;
    }
  }
  for (const auto& [hf, uses] : halfface_use) EXPECT_EQ(uses, 1);
  std::string tag, type, name;
  in >> tag >> type >> name;
  EXPECT_EQ(tag + type + name, "CPropint\"region\"");
  for (std::size_t c = 0; c < 6; ++c) {
    int region;
    in >> region;
    EXPECT_EQ(region, mesh.tet_regions[c]);
  }
  in >> tag >> type >> name;
  EXPECT_EQ(tag + type + name, "FPropint\"boundary_marker\"");
  int marked = 0;
  for (std::size_t f = 0; f < faces.size(); ++f) {
    int marker;
    in >> marker;
    marked += marker != 0;
  }
  EXPECT_EQ(marked, 12);
}

/// The `count` tuples of `components` numbers of the cell data array `name` of a .vtu.
std::vector<std::vector<double>> vtu_array(const std::string& vtu, const std::string& name, int components,
                                           std::size_t count) {
  const std::size_t at = vtu.find("Name=\"" + name + "\"");
  if (at == std::string::npos) return {};
  const std::string header = vtu.substr(at, vtu.find('>', at) - at);
  EXPECT_NE(header.find("NumberOfComponents=\"" + std::to_string(components) + "\""), std::string::npos) << header;
  std::istringstream in(vtu.substr(vtu.find('>', at) + 1));
  std::vector<std::vector<double>> tuples(count, std::vector<double>(components));
  for (auto& t : tuples)
    for (double& x : t) in >> x;
  return tuples;
}

TEST_F(TetraWritersTest, ColoursAndNamesReachEveryFormatThatCanCarryThem) {
  mesh.marker_colors = {{1, {1.0, 0.0, 0.0}}, {3, {0.0, 0.5, 1.0}}};
  mesh.region_colors = {{2, {0.0, 1.0, 0.0}}};
  const std::map<int, std::vector<double>> marker_rgb{{1, {255, 0, 0}}, {3, {0, 128, 255}}};

  ASSERT_TRUE(write_tetra_mesh(dir / "cube.vtu", mesh));
  const std::string vtu = slurp(dir / "cube.vtu");
  EXPECT_NE(vtu.find("<DataArray type=\"UInt8\" Name=\"boundary_color\""), std::string::npos);
  const auto boundary = vtu_array(vtu, "boundary_color", 3, 18);
  const auto region = vtu_array(vtu, "region_color", 3, 18);
  ASSERT_EQ(boundary.size(), 18u);
  ASSERT_EQ(region.size(), 18u);
  int coloured_faces = 0;
  for (std::size_t c = 0; c < 18; ++c) {
    if (c < 6) {
      EXPECT_EQ(boundary[c], (std::vector<double>{0, 0, 0})) << c;
      EXPECT_EQ(region[c], (mesh.tet_regions[c] == 2 ? std::vector<double>{0, 255, 0} : std::vector<double>{0, 0, 0}))
          << c;
      continue;
    }
    const auto expected = marker_rgb.find(mesh.boundary_markers[c - 6]);
    const std::vector<double> none(3, 0.0);
    EXPECT_EQ(boundary[c], (expected == marker_rgb.end() ? none : expected->second)) << c;
    EXPECT_EQ(region[c], (std::vector<double>{0, 0, 0})) << c;
    coloured_faces += expected != marker_rgb.end();
  }
  EXPECT_EQ(coloured_faces, 4);  // two triangles on each of the two coloured sides

  ASSERT_TRUE(write_tetra_mesh(dir / "cube.ovm", mesh));
  const std::string ovm = slurp(dir / "cube.ovm");
  const std::size_t faces_at = ovm.find("Faces\n");
  ASSERT_NE(faces_at, std::string::npos);
  const std::size_t nfaces = std::stoul(ovm.substr(faces_at + 6));
  const auto after = [&](const std::string& key) {
    const std::size_t at = ovm.find(key);
    EXPECT_NE(at, std::string::npos) << key;
    return at == std::string::npos ? std::string() : ovm.substr(at + key.size());
  };
  std::istringstream markers(after("FProp int \"boundary_marker\"\n"));
  std::vector<int> face_marker(nfaces);
  for (int& m : face_marker) markers >> m;
  std::istringstream colors(after("FProp vec4f \"face_color\"\n"));
  int opaque = 0;
  for (std::size_t f = 0; f < nfaces; ++f) {
    std::vector<double> rgba(4);
    for (double& x : rgba) colors >> x;
    const auto expected = marker_rgb.find(face_marker[f]);
    if (expected == marker_rgb.end()) {
      EXPECT_EQ(rgba, (std::vector<double>{0, 0, 0, 0})) << f;
      continue;
    }
    ++opaque;
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(rgba[k] * 255.0, expected->second[k], 1e-4) << f;
    EXPECT_EQ(rgba[3], 1.0);
  }
  EXPECT_EQ(opaque, 4);
  std::istringstream cells(after("CProp vec4f \"cell_color\"\n"));
  for (std::size_t c = 0; c < 6; ++c) {
    std::vector<double> rgba(4);
    for (double& x : rgba) cells >> x;
    EXPECT_EQ(rgba, (mesh.tet_regions[c] == 2 ? std::vector<double>{0, 1, 0, 1} : std::vector<double>{0, 0, 0, 0}));
  }

  // Formats without a colour field list the tables in comment lines.
  ASSERT_TRUE(write_tetra_mesh(dir / "cube.inp", mesh));
  ASSERT_TRUE(write_tetra_mesh(dir / "cube.mesh", mesh));
  ASSERT_TRUE(write_tetra_mesh(dir / "cube.node", mesh));
  const std::string inp = slurp(dir / "cube.inp"), medit = slurp(dir / "cube.mesh");
  const std::string face = slurp(dir / "cube.face"), ele = slurp(dir / "cube.ele");
  EXPECT_NE(inp.find("** facet_marker 1 name \"inlet\" color #ff0000\n"), std::string::npos) << inp;
  EXPECT_NE(inp.find("** region 2 color #00ff00\n"), std::string::npos) << inp;
  EXPECT_NE(medit.find("# facet_marker 3 color #0080ff\n"), std::string::npos) << medit;
  EXPECT_NE(medit.find("# region 1 name \"steel part\"\n"), std::string::npos) << medit;
  EXPECT_LT(medit.find("# facet_marker"), medit.find("End"));
  EXPECT_NE(face.find("# facet_marker 2 name \"outlet\"\n"), std::string::npos) << face;
  EXPECT_EQ(face.find("# region"), std::string::npos) << face;
  EXPECT_NE(ele.find("# region 2 color #00ff00\n"), std::string::npos) << ele;

  // Without colour tables the colour arrays and properties are left out.
  mesh.marker_colors.clear();
  mesh.region_colors.clear();
  ASSERT_TRUE(write_tetra_mesh(dir / "plain.vtu", mesh));
  ASSERT_TRUE(write_tetra_mesh(dir / "plain.ovm", mesh));
  EXPECT_EQ(slurp(dir / "plain.vtu").find("_color"), std::string::npos);
  EXPECT_EQ(slurp(dir / "plain.ovm").find("_color"), std::string::npos);
}

// The refiner's per-tet small-angle flags (MeshResult::tet_at_small_angle) reach the .vtu
// as cell data at_small_angle, tet by tet, 0 on the boundary triangles; without them the
// array is not written, and a flag array of the wrong length is refused.
TEST_F(TetraWritersTest, VtuCarriesTheSmallAngleFlags) {
  const std::vector<std::uint8_t> flags{0, 1, 2, 0, 1, 0};
  TetraWriteOptions options;
  options.tet_at_small_angle = &flags;
  ASSERT_TRUE(write_tetra_mesh(dir / "flags.vtu", mesh, options));
  const auto cells = vtu_array(slurp(dir / "flags.vtu"), "at_small_angle", 1, 18);
  ASSERT_EQ(cells.size(), 18u);
  for (std::size_t i = 0; i < 18; ++i) EXPECT_EQ(cells[i][0], i < flags.size() ? flags[i] : 0) << "cell " << i;
  ASSERT_TRUE(write_tetra_mesh(dir / "plain.vtu", mesh));
  EXPECT_EQ(slurp(dir / "plain.vtu").find("at_small_angle"), std::string::npos);
  const std::vector<std::uint8_t> short_flags{1, 2};
  options.tet_at_small_angle = &short_flags;
  auto refused = write_tetra_mesh(dir / "short.vtu", mesh, options);
  ASSERT_FALSE(refused);
  EXPECT_EQ(refused.error().code, ErrorCode::InvalidOption);
}

TEST_F(TetraWritersTest, UnknownExtensionAndUnwritablePathAreErrors) {
  auto bad = write_tetra_mesh(dir / "cube.xyz", mesh);
  ASSERT_FALSE(bad);
  EXPECT_EQ(bad.error().code, ErrorCode::InvalidOption);
  auto unwritable = write_tetra_mesh(dir / "missing_dir" / "cube.vtu", mesh);
  ASSERT_FALSE(unwritable);
  EXPECT_EQ(unwritable.error().code, ErrorCode::IoError);
  EXPECT_NE(unwritable.error().message.find("missing_dir"), std::string::npos);
}

}  // namespace
}  // namespace delmesh
