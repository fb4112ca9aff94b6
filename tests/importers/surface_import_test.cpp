// Surface import: parsers for every format, welding, repairs, orientation, refusals
// naming the defect, shells (nesting, regions, holes), coplanar merge, and every file of
// the corpus's surface/ folder against the MANIFEST.
#include <gtest/gtest.h>

#include <array>
#include <cstring>
#include <filesystem>
#include <map>
#include <string>

#include <Eigen/Geometry>

#include "importers/import.h"
#include "importers/surface/surface_importer.h"
#include "tests/support/test_paths.h"
#include "toolkit/plc/plc_validate.h"

namespace delmesh {
namespace {

using Tri = std::array<Vec3, 3>;

// The 12 outward triangles of the axis-aligned box [lo, hi].
std::vector<Tri> box(const Vec3& lo, const Vec3& hi) {
  auto c = [&](int i) { return Vec3(i & 1 ? hi.x() : lo.x(), i & 2 ? hi.y() : lo.y(), i & 4 ? hi.z() : lo.z()); };
  const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  std::vector<Tri> out;
  for (const auto& q : quads) {
    out.push_back({c(q[0]), c(q[1]), c(q[2])});
    out.push_back({c(q[0]), c(q[2]), c(q[3])});
  }
  return out;
}

std::vector<Tri> unit_cube() { return box(Vec3(0, 0, 0), Vec3(1, 1, 1)); }

SurfaceSoup soup_of(const std::vector<Tri>& tris) {
  SurfaceSoup soup;
  for (const auto& t : tris) {
    std::uint32_t ids[3];
    for (int k = 0; k < 3; ++k) {
      ids[k] = static_cast<std::uint32_t>(soup.points.size());
      soup.points.push_back(t[k]);
    }
    soup.add_face(ids, 3, 0);
  }
  return soup;
}

std::string ascii_stl(const std::vector<Tri>& tris) {
  std::string out = "solid test\n";
  char buffer[128];
  for (const auto& t : tris) {
    out += "facet normal 0 0 0\nouter loop\n";
    for (const auto& p : t) {
      std::snprintf(buffer, sizeof buffer, "vertex %.17g %.17g %.17g\n", p.x(), p.y(), p.z());
      out += buffer;
    }
    out += "endloop\nendfacet\n";
  }
  return out + "endsolid test\n";
}

std::string binary_stl(const std::vector<Tri>& tris) {
  std::string out(80, ' ');
  auto put32 = [&](std::uint32_t v) {
    for (int k = 0; k < 4; ++k) out.push_back(static_cast<char>((v >> (8 * k)) & 0xff));
  };
  auto putf = [&](float f) {
    std::uint32_t bits;
    std::memcpy(&bits, &f, 4);
    put32(bits);
  };
  put32(static_cast<std::uint32_t>(tris.size()));
  for (const auto& t : tris) {
    for (int k = 0; k < 3; ++k) putf(0);
    for (const auto& p : t)
      for (int k = 0; k < 3; ++k) putf(static_cast<float>(p[k]));
    out += std::string(2, '\0');
  }
  return out;
}

// Indexed forms of the unit cube (8 vertices, 12 triangles).
struct Indexed {
  std::vector<Vec3> points;
  std::vector<std::array<int, 3>> faces;
};
Indexed indexed_cube() {
  Indexed m;
  std::map<std::array<double, 3>, int> ids;
  for (const auto& t : unit_cube()) {
    std::array<int, 3> f{};
    for (int k = 0; k < 3; ++k) {
      const std::array<double, 3> key{t[k].x(), t[k].y(), t[k].z()};
      auto it = ids.find(key);
      if (it == ids.end()) {
        it = ids.emplace(key, static_cast<int>(m.points.size())).first;
        m.points.push_back(t[k]);
      }
      f[k] = it->second;
    }
    m.faces.push_back(f);
  }
  return m;
}

Plc import_ok(const SurfaceSoup& soup, const SurfaceImportOptions& options = {},
              SurfaceImportReport* report = nullptr) {
  auto plc = surface_to_plc(soup, "test", options, report);
  EXPECT_TRUE(plc) << plc.error().describe();
  if (!plc) return {};
  for (const auto& issue : validate_plc(*plc)) ADD_FAILURE() << issue.message;
  return *plc;
}

TEST(SurfaceParsers, EveryFormatGivesTheSameCube) {
  const Indexed m = indexed_cube();
  std::string off = "OFF\n# cube\n8 12 0\n", obj = "# cube\no cube\n", ply =
      "ply\nformat ascii 1.0\ncomment cube\nelement vertex 8\nproperty double x\nproperty double y\n"
      "property double z\nelement face 12\nproperty list uchar int vertex_indices\nend_header\n";
  for (const auto& p : m.points) {
    const std::string xyz = std::to_string(p.x()) + " " + std::to_string(p.y()) + " " + std::to_string(p.z());
    off += xyz + "\n";
    obj += "v " + xyz + "\nvn 0 0 1\n";
    ply += xyz + "\n";
  }
  for (const auto& f : m.faces) {
    off += "3 " + std::to_string(f[0]) + " " + std::to_string(f[1]) + " " + std::to_string(f[2]) + "\n";
    // OBJ: 1-based with a normal index, and the last vertex as a negative (relative) index.
    obj += "f " + std::to_string(f[0] + 1) + "//1 " + std::to_string(f[1] + 1) + "/1/1 " +
           std::to_string(f[2] - 8) + "\n";
    ply += "3 " + std::to_string(f[0]) + " " + std::to_string(f[1]) + " " + std::to_string(f[2]) + "\n";
  }
  std::string plyb =
      "ply\nformat binary_big_endian 1.0\nelement vertex 8\nproperty float x\nproperty float y\n"
      "property float z\nproperty uchar red\nelement face 12\nproperty list uchar uint vertex_indices\nend_header\n";
  auto put_be = [&](const void* data, int n) {
    const auto* b = static_cast<const unsigned char*>(data);
    for (int k = n - 1; k >= 0; --k) plyb.push_back(static_cast<char>(b[k]));
  };
  for (const auto& p : m.points) {
    for (int k = 0; k < 3; ++k) {
      const float f = static_cast<float>(p[k]);
      put_be(&f, 4);
    }
    plyb.push_back('\x7f');
  }
  for (const auto& f : m.faces) {
    plyb.push_back('\x03');
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t v = static_cast<std::uint32_t>(f[k]);
      put_be(&v, 4);
    }
  }
  const std::pair<const char*, Expected<SurfaceSoup>> parsed[] = {
      {"ascii stl", parse_stl(ascii_stl(unit_cube()), "a.stl")},
      {"binary stl", parse_stl(binary_stl(unit_cube()), "b.stl")},
      {"off", parse_off(off, "c.off")},
      {"obj", parse_obj(obj, "c.obj")},
      {"ply ascii", parse_ply(ply, "c.ply")},
      {"ply binary", parse_ply(plyb, "b.ply")}};
  for (const auto& [name, soup] : parsed) {
    ASSERT_TRUE(soup) << name << ": " << soup.error().describe();
    EXPECT_EQ(soup->face_count(), 12u) << name;
    SurfaceImportReport report;
    const Plc plc = import_ok(*soup, {}, &report);
    EXPECT_EQ(report.welded_vertices, 8u) << name;
    EXPECT_EQ(plc.points.size(), 8u) << name;
    EXPECT_EQ(plc.facets.size(), 6u) << name;  // coplanar pairs merged into quads
    for (const auto& facet : plc.facets) EXPECT_EQ(facet.polygons.at(0).size(), 4u) << name;
    ASSERT_EQ(plc.regions.size(), 1u) << name;
    EXPECT_EQ(plc.regions[0].id, 1);
    EXPECT_EQ(report.faces_reoriented, 0u) << name;
  }
}

TEST(SurfaceParsers, CoordinatesAreReadInDoublePrecision) {
  const auto soup = parse_off("OFF\n3 1 0\n0.1234567890123456 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", "p.off");
  ASSERT_TRUE(soup);
  EXPECT_EQ(soup->points[0].x(), 0.1234567890123456);
  const auto obj = parse_obj("v 0.1234567890123456 1e-300 -7.000000000000001\n", "p.obj");
  ASSERT_TRUE(obj);
  EXPECT_EQ(obj->points[0], Vec3(0.1234567890123456, 1e-300, -7.000000000000001));
}

struct BadFile {
  const char* what;
  Expected<SurfaceSoup> result;
  std::size_t line;
  const char* message_part;
};

TEST(SurfaceParsers, MalformedFilesGiveLocatedErrors) {
  std::string truncated = binary_stl(unit_cube());
  truncated.resize(truncated.size() - 7);
  truncated[0] = 'x';
  const BadFile cases[] = {
      {"truncated binary stl", parse_stl(truncated, "t.stl"), 0, "announces 12 triangles"},
      {"stl without endloop", parse_stl("solid a\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n", "a.stl"), 3, "end of file inside a facet"},
      {"stl with 4 vertices", parse_stl("solid a\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nvertex 1 1 0\nendloop\n", "a.stl"), 7, "has 4 vertices"},
      {"stl bad number", parse_stl("solid a\nouter loop\nvertex 0 0 zero\n", "a.stl"), 3, "found 'zero'"},
      {"off bad index", parse_off("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n", "a.off"), 6, "names vertex 3"},
      {"off short face", parse_off("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1\n", "a.off"), 6, "announces 3 vertices"},
      {"off missing vertex", parse_off("OFF\n3 1 0\n0 0 0\n1 0 0\n", "a.off"), 4, "end of file"},
      {"off wrong magic", parse_off("PLY\n", "a.off"), 1, "expected an OFF header"},
      {"obj forward index", parse_obj("v 0 0 0\nv 1 0 0\nf 1 2 3\n", "a.obj"), 3, "refers to no vertex"},
      {"obj zero index", parse_obj("v 0 0 0\nf 0 1 1\n", "a.obj"), 2, "bad face vertex"},
      {"ply no end_header", parse_ply("ply\nformat ascii 1.0\nelement vertex 1\n", "a.ply"), 3, "end_header"},
      {"ply truncated binary", parse_ply("ply\nformat binary_little_endian 1.0\nelement vertex 2\nproperty float x\nproperty float y\nproperty float z\nend_header\n\x01\x02", "a.ply"), 0, "end of binary data"},
      {"ply no z", parse_ply("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nend_header\n0 0\n", "a.ply"), 0, "lacks an x, y or z"},
  };
  for (const auto& c : cases) {
    ASSERT_FALSE(c.result) << c.what;
    const Error& e = c.result.error();
    EXPECT_NE(e.message.find(c.message_part), std::string::npos) << c.what << ": " << e.describe();
    ASSERT_TRUE(e.location.has_value()) << c.what;
    EXPECT_EQ(e.location->line, c.line) << c.what << ": " << e.describe();
  }
}

TEST(SurfaceImport, NoMergeKeepsTriangles) {
  SurfaceImportOptions options;
  options.merge_coplanar = false;
  const Plc plc = import_ok(soup_of(unit_cube()), options);
  EXPECT_EQ(plc.facets.size(), 12u);
}

TEST(SurfaceImport, InconsistentAndInwardOrientationsAreFixed) {
  auto tris = unit_cube();
  std::swap(tris[3][1], tris[3][2]);  // one flipped triangle
  SurfaceImportReport report;
  import_ok(soup_of(tris), {}, &report);
  EXPECT_EQ(report.faces_reoriented, 1u);
  for (auto& t : tris) std::swap(t[1], t[2]);  // now 11 inward, 1 outward
  const Plc plc = import_ok(soup_of(tris), {}, &report);
  EXPECT_EQ(report.faces_reoriented, 11u);
  // Outward: the bottom facet (z = 0) loop runs clockwise seen from above.
  for (const auto& facet : plc.facets) {
    const auto& loop = facet.polygons[0];
    const Vec3 n = (plc.points[loop[1]] - plc.points[loop[0]]).cross(plc.points[loop[2]] - plc.points[loop[0]]);
    const Vec3 centre_to_facet = plc.points[loop[0]] - Vec3(0.5, 0.5, 0.5);
    EXPECT_GT(n.dot(centre_to_facet), 0);
  }
}

TEST(SurfaceImport, DuplicateAndCollapsedFacesAreDropped) {
  auto tris = unit_cube();
  tris.push_back(tris[5]);
  tris.push_back({tris[7][2], tris[7][1], tris[7][0]});  // duplicate with the other orientation
  tris.push_back({Vec3(0, 0, 0), Vec3(0, 0, 0), Vec3(1, 1, 1)});
  SurfaceImportReport report;
  import_ok(soup_of(tris), {}, &report);
  EXPECT_EQ(report.duplicates_dropped, 2u);
  EXPECT_EQ(report.collapsed_dropped, 1u);
  EXPECT_EQ(report.input_faces, 15u);
}

TEST(SurfaceImport, OpenSurfaceIsRefusedWithItsBoundaryEdges) {
  auto tris = unit_cube();
  tris.erase(tris.begin() + 2);  // a triangle of the top
  const auto plc = surface_to_plc(soup_of(tris), "open.stl", {});
  ASSERT_FALSE(plc);
  EXPECT_EQ(plc.error().code, ErrorCode::OpenBoundary);
  EXPECT_NE(plc.error().message.find("open: boundary edges on a single face (3)"), std::string::npos)
      << plc.error().message;
  EXPECT_NE(plc.error().message.find("(1, 1, 1)"), std::string::npos);
  SurfaceImportOptions options;
  options.require_closed = false;
  const auto inspect = surface_to_plc(soup_of(tris), "open.stl", options);
  ASSERT_TRUE(inspect) << inspect.error().describe();
  EXPECT_TRUE(inspect->regions.empty());
}

TEST(SurfaceImport, NonManifoldEdgeIsRefused) {
  auto tris = unit_cube();
  const auto other = box(Vec3(1, 1, 0), Vec3(2, 2, 1));  // shares the edge x = y = 1
  tris.insert(tris.end(), other.begin(), other.end());
  const auto plc = surface_to_plc(soup_of(tris), "nm.stl", {});
  ASSERT_FALSE(plc);
  EXPECT_EQ(plc.error().code, ErrorCode::NonManifold);
  EXPECT_NE(plc.error().message.find("on 4 faces"), std::string::npos) << plc.error().message;
  // The edge is listed with its coordinates: x = y = 1, z from 0 to 1.
  EXPECT_NE(plc.error().message.find("edge (1, 1, 0) - (1, 1, 1)"), std::string::npos) << plc.error().message;
}

TEST(SurfaceImport, SelfIntersectionIsRefusedWithFacePairs) {
  auto tris = unit_cube();
  const auto other = box(Vec3(0.5, 0.5, 0.5), Vec3(1.5, 1.5, 1.5));
  tris.insert(tris.end(), other.begin(), other.end());
  const auto plc = surface_to_plc(soup_of(tris), "x.stl", {});
  ASSERT_FALSE(plc);
  EXPECT_EQ(plc.error().code, ErrorCode::SelfIntersection);
  EXPECT_NE(plc.error().message.find("self-intersecting"), std::string::npos);
  EXPECT_FALSE(plc.error().entity_ids.empty());
  // Each crossing pair is listed with the faces' coordinates (0.5 and 1.5 occur only as
  // coordinates of the second box).
  EXPECT_NE(plc.error().message.find(" x "), std::string::npos) << plc.error().message;
  EXPECT_NE(plc.error().message.find("0.5"), std::string::npos) << plc.error().message;
  EXPECT_NE(plc.error().message.find("1.5"), std::string::npos) << plc.error().message;
}

TEST(SurfaceImport, ZeroAreaFaceThatHoldsTheSurfaceTogetherIsRefused) {
  // The bottom of the cube is split at the midpoint m of edge (0,0,0)-(1,0,0) while the
  // front side is not: a zero-area triangle (0, m, 1) closes the T-junction.
  auto tris = unit_cube();
  const Vec3 m(0.5, 0, 0);
  std::vector<Tri> out;
  for (const auto& t : tris) {
    if (t[0].z() == 0 && t[1].z() == 0 && t[2].z() == 0) continue;
    out.push_back(t);
  }
  const Vec3 p0(0, 0, 0), p1(1, 0, 0), p2(1, 1, 0), p3(0, 1, 0);
  out.push_back({p0, p3, m});
  out.push_back({m, p3, p2});
  out.push_back({m, p2, p1});
  out.push_back({p0, m, p1});  // zero area
  const auto plc = surface_to_plc(soup_of(out), "z.stl", {});
  ASSERT_FALSE(plc);
  EXPECT_EQ(plc.error().code, ErrorCode::DegenerateInput) << plc.error().describe();
  EXPECT_NE(plc.error().message.find("zero-area"), std::string::npos);
}

TEST(SurfaceImport, WeldToleranceClosesCracks) {
  auto tris = unit_cube();
  for (auto& t : tris)
    for (auto& p : t)
      if (p == Vec3(1, 1, 1) && (&t - tris.data()) % 2 == 0) p = Vec3(1 + 1e-9, 1, 1);
  EXPECT_FALSE(surface_to_plc(soup_of(tris), "crack.stl", {}));
  SurfaceImportOptions options;
  options.weld_tolerance = 1e-6;
  SurfaceImportReport report;
  import_ok(soup_of(tris), options, &report);
  EXPECT_EQ(report.welded_vertices, 8u);
}

TEST(SurfaceImport, NestedShellsBecomeHolesOrRegions) {
  auto tris = box(Vec3(0, 0, 0), Vec3(4, 4, 4));
  const auto inner = box(Vec3(1, 1, 1), Vec3(3, 3, 3));
  tris.insert(tris.end(), inner.begin(), inner.end());
  const auto far = box(Vec3(10, 0, 0), Vec3(11, 1, 1));
  tris.insert(tris.end(), far.begin(), far.end());
  SurfaceImportReport report;
  const Plc holes = import_ok(soup_of(tris), {}, &report);
  EXPECT_EQ(report.shells, 3u);
  EXPECT_EQ(report.cavities, 1u);
  ASSERT_EQ(holes.holes.size(), 1u);
  EXPECT_TRUE((holes.holes[0].array() > 1).all() && (holes.holes[0].array() < 3).all());
  ASSERT_EQ(holes.regions.size(), 2u);
  EXPECT_EQ(holes.regions[0].id, 1);
  EXPECT_EQ(holes.regions[1].id, 2);
  const Vec3 r0 = holes.regions[0].point;
  EXPECT_TRUE((r0.array() > 0).all() && (r0.array() < 4).all());
  EXPECT_FALSE((r0.array() > 1).all() && (r0.array() < 3).all());  // not in the cavity
  EXPECT_GT(holes.regions[1].point.x(), 10);
  SurfaceImportOptions options;
  options.nested_shells = NestedShells::Regions;
  const Plc regions = import_ok(soup_of(tris), options);
  EXPECT_TRUE(regions.holes.empty());
  EXPECT_EQ(regions.regions.size(), 3u);
}

TEST(SurfaceImport, CoplanarMergeMakesFacetsWithHolesWhenNeeded) {
  // A 3x3x1 slab with a 1x1 square tube through it: the top and bottom faces are
  // annuli, each triangulated; merged they become one facet with a hole.
  std::vector<Vec3> ring_out = {{0, 0, 0}, {3, 0, 0}, {3, 3, 0}, {0, 3, 0}};
  std::vector<Vec3> ring_in = {{1, 1, 0}, {2, 1, 0}, {2, 2, 0}, {1, 2, 0}};
  std::vector<Tri> tris;
  auto lift = [](Vec3 p, double z) { p.z() = z; return p; };
  for (int i = 0; i < 4; ++i) {
    const int j = (i + 1) % 4;
    // top (z = 1, outward +z) and bottom (z = 0, outward -z) annulus quads, two triangles each
    tris.push_back({lift(ring_out[i], 1), lift(ring_out[j], 1), lift(ring_in[j], 1)});
    tris.push_back({lift(ring_out[i], 1), lift(ring_in[j], 1), lift(ring_in[i], 1)});
    tris.push_back({ring_out[i], ring_in[j], ring_out[j]});
    tris.push_back({ring_out[i], ring_in[i], ring_in[j]});
    // outer walls (outward) and tube walls (facing the tube axis)
    tris.push_back({ring_out[i], ring_out[j], lift(ring_out[j], 1)});
    tris.push_back({ring_out[i], lift(ring_out[j], 1), lift(ring_out[i], 1)});
    tris.push_back({ring_in[i], lift(ring_in[j], 1), ring_in[j]});
    tris.push_back({ring_in[i], lift(ring_in[i], 1), lift(ring_in[j], 1)});
  }
  SurfaceImportReport report;
  const Plc plc = import_ok(soup_of(tris), {}, &report);
  EXPECT_EQ(report.faces_reoriented, 0u);
  EXPECT_EQ(plc.facets.size(), 10u);  // top, bottom, 4 outer walls, 4 tube walls
  std::size_t with_holes = 0;
  for (const auto& facet : plc.facets) {
    if (facet.holes.empty()) continue;
    ++with_holes;
    ASSERT_EQ(facet.polygons.size(), 2u);
    EXPECT_EQ(facet.polygons[0].size(), 4u);
    const Vec3 h = facet.holes[0];
    EXPECT_TRUE(h.x() > 1 && h.x() < 2 && h.y() > 1 && h.y() < 2);
  }
  EXPECT_EQ(with_holes, 2u);
}

struct CorpusExpectation {
  const char* file;
  bool accepted;
  std::size_t vertices, triangles;  // MANIFEST counts (after exact welding)
  const char* defect;               // for refused files: text the error must contain
  std::size_t regions;
};

TEST(SurfaceImport, CorpusFilesAreImportedOrRefusedAsTheManifestSays) {
  const CorpusExpectation expected[] = {
      {"cgal-anchor.off", true, 519, 1050, "", 1},
      {"cgal-armadillo.off", true, 26002, 52000, "", 1},
      {"cgal-bear.off", true, 13826, 27648, "", 1},
      {"cgal-boeing.off", true, 1264, 2564, "", 1},  // repaired: reoriented
      {"cgal-bunny00.off", true, 37706, 75408, "", 1},
      {"cgal-couplingdown.off", true, 1841, 3714, "", 1},
      {"cgal-dino.off", true, 3916, 7828, "", 1},
      {"cgal-fandisk.off", true, 6475, 12946, "", 1},
      {"cgal-homer.off", true, 4930, 9856, "", 1},
      {"cgal-knot2.off", true, 5760, 11520, "", 2},
      {"cgal-nonmanifold-facegraph.off", false, 0, 0, "non-manifold", 0},
      {"cgal-schonhardt.off", true, 6, 8, "", 1},  // repaired: reoriented
      {"cgal-sphere.off", true, 162, 320, "", 1},
      {"cgal-step.off", true, 10, 16, "", 1},
      {"cgal-u-arch.off", true, 12365, 24726, "", 1},
      {"gmsh-aorta.stl", false, 0, 0, "open: boundary edges on a single face (107)", 0},
      {"gmsh-netgen-hinge.stl", true, 598, 1212, "", 1},
      {"occt-motor.stl", false, 0, 0, "non-manifold", 0},
      {"occt-propeller.stl", true, 3689, 7374, "", 1},  // repaired: 1 collapsed, reoriented
      {"occt-sh2.stl", true, 3600, 7196, "", 1},
      {"occt-tr12j.stl", true, 13441, 26966, "", 1},
      {"occt-video-part.stl", false, 0, 0, "open: boundary edges on a single face (244)", 0},
      {"pocc-bottle.stl", false, 0, 0, "open: boundary edges", 0},
      {"trimesh-busted.stl", true, 1941, 3878, "", 1},
      {"trimesh-soup.stl", false, 0, 0, "open: boundary edges on a single face (300)", 0},
      {"trimesh-teapot.stl", false, 0, 0, "open: boundary edges on a single face (64)", 0},
      {"trimesh-tray-bottom.stl", true, 2216, 4520, "", 1},
  };
  std::size_t seen = 0;
  for (const auto& entry : std::filesystem::directory_iterator(test::corpus_dir() / "surface")) {
    ++seen;
    const std::string name = entry.path().filename().string();
    const CorpusExpectation* e = nullptr;
    for (const auto& x : expected) {
      if (name == x.file) e = &x;
    }
    ASSERT_NE(e, nullptr) << name << " has no expectation";
    SurfaceImportReport report;
    const auto plc = import_surface(entry.path(), {}, &report);
    if (!e->accepted) {
      ASSERT_FALSE(plc) << name << " should be refused";
      EXPECT_NE(plc.error().message.find(e->defect), std::string::npos) << name << ": " << plc.error().describe();
      continue;
    }
    ASSERT_TRUE(plc) << name << ": " << plc.error().describe();
    EXPECT_EQ(report.welded_vertices, e->vertices) << name;
    // The MANIFEST counts faces with a repeated vertex (which the import drops) out.
    EXPECT_EQ(report.input_faces - report.collapsed_dropped, e->triangles) << name;
    EXPECT_EQ(plc->regions.size(), e->regions) << name;
    for (const auto& issue : validate_plc(*plc)) ADD_FAILURE() << name << ": " << issue.message;
    if (name == "cgal-boeing.off" || name == "cgal-schonhardt.off") {
      EXPECT_GT(report.faces_reoriented, 0u) << name;
    }
    if (name == "occt-propeller.stl") {
      EXPECT_EQ(report.collapsed_dropped, 1u);
      EXPECT_GT(report.faces_reoriented, 0u);
    }
  }
  EXPECT_EQ(seen, std::size(expected));
}

TEST(SurfaceImport, BottleWeldedWithToleranceIsStillRefusedAsSelfIntersecting) {
  SurfaceImportOptions options;
  options.weld_tolerance = 2e-4;  // its shells miss each other by 1e-4
  const auto plc = import_surface(test::corpus_dir() / "surface" / "pocc-bottle.stl", options);
  ASSERT_FALSE(plc);
  EXPECT_EQ(plc.error().code, ErrorCode::SelfIntersection) << plc.error().describe();
}

TEST(SurfaceImport, OpenVideoPartIsSelfIntersectingWhenOpenSurfacesAreAllowed) {
  // The MANIFEST reports it self-intersecting (tetgen -d): merged facets meet it at a
  // T-junction along a shared line.
  SurfaceImportOptions options;
  options.require_closed = false;
  const auto plc = import_surface(test::corpus_dir() / "surface" / "occt-video-part.stl", options);
  ASSERT_FALSE(plc);
  EXPECT_EQ(plc.error().code, ErrorCode::SelfIntersection) << plc.error().describe();
}

TEST(ImportFile, DispatchesOnExtension) {
  const auto off = import_file(test::corpus_dir() / "surface" / "cgal-step.off", {});
  ASSERT_TRUE(off);
  const auto smesh = import_file(test::corpus_dir() / "poly3d" / "td-wedge-5.smesh", {});
  ASSERT_TRUE(smesh);
  EXPECT_EQ(smesh->points.size(), 6u);
  const auto unknown = import_file("model.xyz", {});
  ASSERT_FALSE(unknown);
  EXPECT_EQ(unknown.error().code, ErrorCode::Unsupported);
  const auto step = import_file("/nonexistent/part.step", {});
  ASSERT_FALSE(step);
  EXPECT_EQ(step.error().code, cad_import_available() ? ErrorCode::IoError : ErrorCode::Unsupported)
      << step.error().describe();
}

}  // namespace
}  // namespace delmesh
