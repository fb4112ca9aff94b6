// Corpus regression for the CAD importer (importers/step/): every STEP file of the corpus
// imports into a PLC whose counts match the corpus MANIFEST, whose facets are exactly
// planar, whose markers are valid CAD face ids and whose boundary is closed; or is
// refused with the documented error.
#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <map>
#include <numbers>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "importers/step/step_importer.h"
#include "tests/support/corpus_inputs.h"
#include "tests/support/test_paths.h"
#include "toolkit/plc/plc_validate.h"
#include "toolkit/predicates/predicates.h"

namespace delmesh {
namespace {

struct CorpusFile {
  const char* name;
  int solids;  ///< MANIFEST
  int faces;   ///< MANIFEST
  /// Solids touch: glued interfaces are shared by two solids and keep one face id.
  bool glued;
  std::optional<ErrorCode> refused;
  /// Faces whose every triangle lies under a fold of a neighbour's BRepMesh triangulation
  /// (the coincident opposite pairs are cancelled, so these faces leave no facet).
  int faces_folded_away = 0;
};

// Counts from /work/shared/corpus/MANIFEST.md. Faces-only files (solids 0 there) are
// sewn into one solid. gmsh-cube-fillet.stp is refused: its 25 faces (17 cylindrical
// fillet pieces and 8 spherical corners of a filleted box) lack all six planar sides and
// three fillet pieces, so 40 free edges in 3 loops remain at any sewing tolerance.
const CorpusFile kCorpus[] = {
    {"as-anc101.stp", 1, 87, false, {}},
    {"as-capot-40mm.stp", 1, 291, false, {}},
    {"as-mechanism.stp", 3, 28, true, {}},
    {"as-tie-rod.step", 1, 68, false, {}, 4},  // 4 tiny faces at the rod ends
    {"as-wavy-cube.stp", 0, 6, false, {}},
    {"gmsh-angled.step", 1, 69, false, {}},
    {"gmsh-as1-tu-203.stp", 18, 160, true, {}},
    {"gmsh-boundary-colors.stp", 1, 6, false, {}},
    {"gmsh-cube-fillet.stp", 0, 25, false, ErrorCode::OpenBoundary},
    {"gmsh-fusee-rocket.stp", 1, 249, false, {}},
    {"gmsh-laufrad-impeller.stp", 1, 123, false, {}},
    {"gmsh-mambo-s34.step", 1, 46, false, {}},
    {"gmsh-part.step", 1, 26, false, {}},
    {"gmsh-periodic-u.step", 1, 3, false, {}},
    {"gmsh-t106-blade.step", 0, 8, false, {}},
    {"gmsh-t20-data.step", 1, 21, false, {}},
    {"gmsh-wing-fuselage.step", 2, 16, true, {}},
    {"gmsh-wrenchnut.stp", 2, 36, false, {}},
    {"occt-linkrods.step", 1, 37, false, {}},
    {"occt-screw.step", 1, 10, false, {}},
    {"pocc-eight-cyl.stp", 8, 24, false, {}},
    {"pocc-io1-ug-214.stp", 1, 17, false, {}},
    {"pocc-multi-shape-root.stp", 3, 43, true, {}},
    {"trimesh-box-sides.step", 10, 417, true, {}},
};

/// The bounded-angle refinement of the curved (and tilted planar) faces, measured with
/// the default options: faces that kept BRepMesh's triangles, the smallest angle of the
/// refined faces away from face corners under 60 degrees (angles between two CAD
/// segments, fixed by the input, not counted; surface_mesh_quality.h), rounded down, and
/// the accepted faces still below the 20-degree bound there, with the reason.
struct SurfaceExpectation {
  int excluded;
  double min_angle_deg;
  int faces_below_bound;
  const char* reason;  ///< why faces stay below the bound ("" when none does)
};

constexpr const char* kStopsShort =
    "refinement stops short: the circumcentre lies within the edge-length floor of a node, or beyond a segment never "
    "split (at a face corner under 10 degrees, or shared by two CAD edges), or its segment split would still spoil a "
    "triangle on the segment; and bisecting its longest inner edge would crowd a segment or make a worse triangle";

const std::map<std::string, SurfaceExpectation> kSurface = {
    {"as-anc101.stp", {0, 20.0, 0, ""}},
    {"as-capot-40mm.stp", {0, 20.0, 0, ""}},
    {"as-mechanism.stp", {0, 20.8, 0, ""}},
    {"as-tie-rod.step", {0, 20.0, 0, ""}},
    {"as-wavy-cube.stp", {0, 20.1, 0, ""}},
    {"gmsh-angled.step", {0, 20.0, 0, ""}},
    {"gmsh-as1-tu-203.stp", {0, 20.0, 0, ""}},
    {"gmsh-boundary-colors.stp", {0, 180.0, 0, ""}},  // planar faces only: nothing refined
    // B-spline face 107 stays below 20, at 16.35 (7.84 before crowded inner nodes were
    // collapsed after refinement, surface_coarsening.h: its last needle sits on a 10.99-unit
    // segment held at face 106's balanced corner; 15 faces and B-spline face 106 excluded
    // before the balancing splits at small corners and the node moves; face 2, 15.7 beside a
    // segment held at a small corner, reaches 20.3 with the lifted points). Faces 44 (1.31
    // beside its 4.9-degree corner) and 61 (15.98) reach 20 since the balancing split of
    // their shared 13-unit segment, 0.6 from face 44's corner, refused for the 0.94-degree
    // triangle it gave face 61, goes in halfway to the corner first. Face 22 (0.46: needles
    // waiting on a 39.6-unit segment that the single-triangle face 196, guarded, kept
    // whole) reaches 20 since segments held at a small corner are balanced across the
    // other corners under the bound there (face 196's 17.2-degree corner beside face 195's
    // 8.7-degree one): face 196 is no longer fanned, nor guarded.
    {"gmsh-fusee-rocket.stp", {0, 16.35, 1, kStopsShort}},
    {"gmsh-laufrad-impeller.stp", {0, 20.0, 0, ""}},
    {"gmsh-mambo-s34.step", {0, 20.0, 0, ""}},
    {"gmsh-part.step", {0, 20.0, 0, ""}},
    // Periodic B-spline faces 1, 3 were left at 18.26 and 18.85 beside their poles by
    // refinement; node moves after it (surface_smoothing.h) take them to 20.00.
    {"gmsh-periodic-u.step", {0, 20.0, 0, ""}},
    // A loose model (sewn at 0.092): the surface at its edge nodes' parameters lies up to one
    // chordal deflection from them. Refined with offsets (SurfaceMeshes::Face::offset),
    // extrusion faces 5 and 6 (excluded before: they folded, or ended below BRepMesh's 15.3)
    // and B-spline faces 2 and 8 reach 20; extrusion faces 3 and 4 still fold at the
    // trailing edge, where the offsets exceed the features (0.06-unit segments), and keep
    // BRepMesh's triangles (0.54).
    // Extrusion faces 3 and 4 folded when refined on their surface and were excluded
    // (BRepMesh's needles, 0.54): at the trailing edge their nodes lie up to 0.68 and 0.15
    // units off it beside segments of 0.064 to 0.07 units. Face 4, refined with offsets
    // since its nodes lie farther off than half their shortest edge, reaches 20; face 3,
    // refined on its own tessellation (its offsets still fold it), 5.9: BRepMesh's first row
    // of triangles there bridged the 0.72 units between its cap edge and its surface in a lip
    // 0.01 above the cap. Refined with its edges' offsets blended into it over twice their
    // size (offset_blend.h: the face ramps from the edge onto the surface), it reaches 20.02.
    {"gmsh-t106-blade.step", {0, 20.0, 0, ""}},
    // 9 B-spline faces were left at 12.88 to 18.3 next to the model's 3-degree corners,
    // whose first segments were never split; balancing splits there (the longer first
    // segment split at the shorter one's length) and node moves take them to 20.05.
    {"gmsh-t20-data.step", {0, 20.0, 0, ""}},
    // Surfaces of revolution 1 and 10 (the fuselage halves) refined beside the tail's pole:
    // 1.42 -> 3.30 and 0.59 -> 3.11 (face 1 was excluded while encroachment was judged in the
    // parameter plane only); node moves take face 1 to 20 and face 10 to 10.8 (then 20).
    // B-spline faces 3 and 14, whose 17-18 degree wing-tip corners are poles of their
    // parametrisation, cascaded into the corner (0.03 degrees, then guarded at 15.1 and
    // 8.1); a node in the pole's collapsed triangle at the corner's first nodes' distance
    // takes them to 20.2. B-spline face 13 (10.4 while a widened small corner was never
    // balanced: its 11-degree corner's other first segment, twice as long, was held) reaches
    // 21.2. Extrusion faces 2 and 9 (17.5, 19.4: their circumcentres would make triangles
    // under 20 on segments held at the balanced 10-degree corners of their neighbours) and
    // surface of revolution 1 (19.4, waiting on the same segment at the tail) reach 20 with
    // the points lifted off those segments (20.0008).
    {"gmsh-wing-fuselage.step", {0, 20.0, 0, ""}},
    {"gmsh-wrenchnut.stp", {0, 20.0, 0, ""}},
    {"occt-linkrods.step", {0, 20.0, 0, ""}},
    {"occt-screw.step", {0, 20.2, 0, ""}},
    {"pocc-eight-cyl.stp", {0, 19.99, 0, ""}},
    {"pocc-io1-ug-214.stp", {0, 20.0, 0, ""}},
    {"pocc-multi-shape-root.stp", {0, 20.1, 0, ""}},
    {"trimesh-box-sides.step", {0, 20.0, 0, ""}},
};

/// Every vertex of the facet lies exactly in the plane of three non-collinear ones.
bool facet_is_planar(const Plc& plc, const Plc::Facet& facet) {
  std::vector<std::uint32_t> ids;
  for (const Plc::Polygon& p : facet.polygons) ids.insert(ids.end(), p.begin(), p.end());
  if (ids.size() < 3) return false;
  const double* a = plc.points[ids[0]].data();
  const double* b = plc.points[ids[1]].data();
  std::optional<std::size_t> third;
  for (std::size_t k = 2; k < ids.size() && !third; ++k) {
    for (Axis axis : {Axis::X, Axis::Y, Axis::Z}) {
      if (predicates::orient2d_projected(a, b, plc.points[ids[k]].data(), axis) != Sign::Zero) third = k;
    }
  }
  if (!third) return false;
  const double* c = plc.points[ids[*third]].data();
  for (std::uint32_t v : ids) {
    if (predicates::orient3d(a, b, c, plc.points[v].data()) != Sign::Zero) return false;
  }
  return true;
}

/// Directed facet-side counts: (a, b) -> number of polygon sides a -> b.
std::map<std::pair<std::uint32_t, std::uint32_t>, int> directed_sides(const Plc& plc) {
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> sides;
  for (const Plc::Facet& facet : plc.facets) {
    for (const Plc::Polygon& loop : facet.polygons) {
      for (std::size_t i = 0; i < loop.size(); ++i) ++sides[{loop[i], loop[(i + 1) % loop.size()]}];
    }
  }
  return sides;
}

/// Generalised winding number of the facets around p (Van Oosterom-Strackee solid angles
/// of a fan of each loop): +-1 inside a closed consistently oriented surface, 0 outside.
double winding_number(const Plc& plc, const Vec3& p) {
  double total = 0.0;
  for (const Plc::Facet& facet : plc.facets) {
    for (const Plc::Polygon& loop : facet.polygons) {
      for (std::size_t i = 1; i + 1 < loop.size(); ++i) {
        const Vec3 a = plc.points[loop[0]] - p;
        const Vec3 b = plc.points[loop[i]] - p;
        const Vec3 c = plc.points[loop[i + 1]] - p;
        const double la = a.norm(), lb = b.norm(), lc = c.norm();
        const double numerator = a.dot(b.cross(c));
        const double denominator = la * lb * lc + a.dot(b) * lc + b.dot(c) * la + c.dot(a) * lb;
        total += 2.0 * std::atan2(numerator, denominator);
      }
    }
  }
  return total / (4.0 * std::numbers::pi);
}

class StepCorpus : public ::testing::TestWithParam<CorpusFile> {};

TEST_P(StepCorpus, ImportsWithManifestCountsAndClosedPlanarBoundary) {
  const CorpusFile& expected = GetParam();
  const auto path = test::corpus_dir() / "step" / expected.name;
  ASSERT_TRUE(std::filesystem::exists(path)) << path;
  const auto start = std::chrono::steady_clock::now();
  StepSurfaceSummary summary;
  StepImportOptions options;
  options.surface_summary = &summary;
  const Expected<Plc> plc = import_step(path, options);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  RecordProperty("import_seconds", std::to_string(seconds));
  if (expected.refused) {
    ASSERT_FALSE(plc.has_value()) << expected.name << " should be refused";
    EXPECT_EQ(plc.error().code, *expected.refused) << plc.error().describe();
    EXPECT_NE(plc.error().message.find(expected.name), std::string::npos) << plc.error().describe();
    return;
  }
  ASSERT_TRUE(plc.has_value()) << plc.error().describe();

  // Bounded angles on the curved faces (figures and reasons in kSurface).
  const auto surface = kSurface.find(expected.name);
  ASSERT_NE(surface, kSurface.end()) << expected.name << " has no surface expectation";
  EXPECT_FALSE(summary.reverted);
  EXPECT_EQ(summary.faces_excluded, surface->second.excluded);
  EXPECT_GE(summary.min_angle_away_from_small_corners_deg, surface->second.min_angle_deg);
  EXPECT_GE(summary.min_angle_away_from_small_corners_deg, summary.min_angle_after_deg);
  EXPECT_EQ(summary.faces_below_bound, surface->second.faces_below_bound) << surface->second.reason;
  if (surface->second.faces_below_bound == 0 && surface->second.excluded == 0) {
    EXPECT_GE(summary.min_angle_away_from_small_corners_deg, 19.99);
  }

  // Regions: one id per CAD solid (faces-only files are sewn into one solid); pieces of
  // overlapping solids share their solid's id.
  const int solids = std::max(expected.solids, 1);
  std::set<int> region_ids;
  for (const Plc::Region& region : plc->regions) {
    EXPECT_GE(region.id, 1);
    EXPECT_LE(region.id, solids);
    region_ids.insert(region.id);
  }
  EXPECT_EQ(static_cast<int>(region_ids.size()), solids);

  // Markers: CAD face ids; all of them survive unless gluing merged interface faces.
  std::set<int> markers;
  for (const Plc::Facet& facet : plc->facets) {
    ASSERT_FALSE(facet.polygons.empty());
    EXPECT_GE(facet.marker, 1);
    EXPECT_LE(facet.marker, expected.faces);
    markers.insert(facet.marker);
    EXPECT_EQ(facet.holes.size() + 1, facet.polygons.size());
    EXPECT_TRUE(facet_is_planar(*plc, facet)) << "facet with marker " << facet.marker << " is not planar";
    for (const Plc::Polygon& loop : facet.polygons) {
      for (std::uint32_t v : loop) ASSERT_LT(v, plc->points.size());
    }
  }
  if (expected.glued) {
    EXPECT_LE(static_cast<int>(markers.size()), expected.faces);
    EXPECT_GT(static_cast<int>(markers.size()), expected.faces / 2);
  } else {
    EXPECT_EQ(static_cast<int>(markers.size()), expected.faces - expected.faces_folded_away);
  }
  for (const auto& [marker, name] : plc->facet_marker_names) EXPECT_TRUE(markers.count(marker)) << name;

  // Closed boundary: without interfaces every side a->b is matched by exactly one side
  // b->a (closed, consistently oriented); glued interface edges are used by more sides.
  const auto sides = directed_sides(*plc);
  int unmatched = 0;
  for (const auto& [side, count] : sides) {
    const auto reverse = sides.find({side.second, side.first});
    const int opposite = reverse == sides.end() ? 0 : reverse->second;
    if (expected.glued ? count + opposite < 2 : (count != 1 || opposite != 1)) ++unmatched;
  }
  EXPECT_EQ(unmatched, 0) << expected.name << ": facet sides without a partner";

  // The PLC is valid: exact intersection checks (refinement of curved faces must not make
  // faces cross), closed, no degenerate or non-planar facet, no duplicate vertex, region
  // points inside.
  const std::vector<PlcIssue> issues = validate_plc(*plc);
  EXPECT_TRUE(issues.empty()) << expected.name << ": " << issues_to_error(issues).message;

  // Region points lie inside: winding number +-1 (checked where the surface is one
  // closed oriented surface per solid, i.e. without interfaces).
  if (!expected.glued) {
    for (const Plc::Region& region : plc->regions) {
      EXPECT_NEAR(std::abs(winding_number(*plc, region.point)), 1.0, 1e-6) << "region " << region.id;
    }
  }
}

std::string test_name(const ::testing::TestParamInfo<CorpusFile>& file) { return test::parameter_name(file.param.name); }

INSTANTIATE_TEST_SUITE_P(Corpus, StepCorpus, ::testing::ValuesIn(kCorpus), test_name);

TEST(StepImport, MissingFileIsAnIoError) {
  const Expected<Plc> plc = import_step("/nonexistent/part.step", StepImportOptions{});
  ASSERT_FALSE(plc.has_value());
  EXPECT_EQ(plc.error().code, ErrorCode::IoError);
}

TEST(StepImport, OutOfRangeDeflectionIsRefused) {
  StepImportOptions options;
  options.relative_linear_deflection = 2.0;
  const Expected<Plc> plc = import_step(test::corpus_dir() / "step" / "occt-screw.step", options);
  ASSERT_FALSE(plc.has_value());
  EXPECT_EQ(plc.error().code, ErrorCode::InvalidOption);
}

TEST(StepImport, OpenSurfaceRefusalSaysFacesAreMissing) {
  // gmsh-cube-fillet.stp has no planar face at all: the free edges left after sewing are
  // the boundaries of the missing sides, far from any other free edge.
  const Expected<Plc> plc = import_step(test::corpus_dir() / "step" / "gmsh-cube-fillet.stp", StepImportOptions{});
  ASSERT_FALSE(plc.has_value());
  EXPECT_EQ(plc.error().code, ErrorCode::OpenBoundary);
  const std::string& message = plc.error().message;
  EXPECT_NE(message.find("25 of 25 faces"), std::string::npos) << message;
  EXPECT_NE(message.find("40 free edges"), std::string::npos) << message;
  EXPECT_NE(message.find("3 closed loop(s)"), std::string::npos) << message;
  EXPECT_NE(message.find("2 of the loops planar"), std::string::npos) << message;
  EXPECT_NE(message.find("faces are missing"), std::string::npos) << message;
}

TEST(StepImport, FaceAndSolidColoursReachTheMarkerAndRegionTables) {
  // gmsh-boundary-colors.stp: a light grey cube (COLOUR_RGB 0.882) whose faces are
  // overridden with pre-defined green and red and with COLOUR_RGB (0, 0.502, 1).
  const Expected<Plc> plc = import_step(test::corpus_dir() / "step" / "gmsh-boundary-colors.stp", StepImportOptions{});
  ASSERT_TRUE(plc.has_value()) << plc.error().describe();
  const auto near = [](const Plc::Color& c, double r, double g, double b) {
    return std::abs(c.r - r) < 1e-6 && std::abs(c.g - g) < 1e-6 && std::abs(c.b - b) < 1e-6;
  };
  constexpr double kGrey = 0.882352941176;
  ASSERT_EQ(plc->facet_marker_colors.size(), 6u);
  int grey = 0, green = 0, red = 0, blue = 0;
  for (const auto& [marker, color] : plc->facet_marker_colors) {
    EXPECT_GE(marker, 1);
    EXPECT_LE(marker, 6);
    grey += near(color, kGrey, kGrey, kGrey);
    green += near(color, 0, 1, 0);
    red += near(color, 1, 0, 0);
    blue += near(color, 0, 0.501960784314, 1);
  }
  EXPECT_EQ(grey, 3);
  EXPECT_EQ(green, 1);
  EXPECT_EQ(red, 1);
  EXPECT_EQ(blue, 1);
  ASSERT_EQ(plc->region_colors.size(), 1u);
  EXPECT_TRUE(near(plc->region_colors.begin()->second, kGrey, kGrey, kGrey));
  // A file without colours leaves the tables empty.
  const Expected<Plc> plain = import_step(test::corpus_dir() / "step" / "occt-screw.step", StepImportOptions{});
  ASSERT_TRUE(plain.has_value()) << plain.error().describe();
  EXPECT_TRUE(plain->facet_marker_colors.empty());
}

TEST(StepImport, ProductNamesBecomeRegionNames) {
  const Expected<Plc> plc = import_step(test::corpus_dir() / "step" / "pocc-eight-cyl.stp", StepImportOptions{});
  ASSERT_TRUE(plc.has_value()) << plc.error().describe();
  EXPECT_EQ(plc->region_names.size(), 8u);
}

TEST(StepImport, GluingOffKeepsEveryFaceId) {
  StepImportOptions options;
  options.glue_assembly = false;
  const Expected<Plc> plc = import_step(test::corpus_dir() / "step" / "gmsh-as1-tu-203.stp", options);
  ASSERT_TRUE(plc.has_value()) << plc.error().describe();
  std::set<int> markers;
  for (const Plc::Facet& facet : plc->facets) markers.insert(facet.marker);
  EXPECT_EQ(markers.size(), 160u);
  EXPECT_EQ(plc->regions.size(), 18u);
}

}  // namespace
}  // namespace delmesh
