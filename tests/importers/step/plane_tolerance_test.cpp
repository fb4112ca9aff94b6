// The plane tolerance of the CAD importer (StepImportOptions::relative_plane_tolerance,
// importers/step/coordinate_planes.h) on tests/data/step/ulp_planes.step: an assembly of a
// base box whose top is z = 0.3 and a block stood on it, modelled from z = 0.1 and placed
// 0.2 higher, so its bottom lies at 0.1 + 0.2 = 0.30000000000000004, one unit in the last
// place above the base's top. Gluing makes the contact one face on the block's plane (the
// block is the first solid) inside the base's top; the vertices of its loop are asked for
// both values, and without merging both faces fall back to triangles. With the default
// tolerance every face is a polygonal facet.
#include <gtest/gtest.h>

#include <set>
#include <string>
#include <vector>

#include "importers/step/step_importer.h"
#include "tests/support/test_paths.h"
#include "toolkit/plc/plc_validate.h"

namespace delmesh {
namespace {

class WarningLog final : public LogSink {
 public:
  void write(LogLevel level, std::string_view message) override {
    if (level == LogLevel::Warning) warnings.emplace_back(message);
  }
  std::vector<std::string> warnings;
};

std::filesystem::path ulp_planes() { return test::test_data_dir() / "step" / "ulp_planes.step"; }

/// Distinct z of the vertices at the contact (z about 0.3).
std::set<double> contact_heights(const Plc& plc) {
  std::set<double> heights;
  for (const Vec3& p : plc.points) {
    if (p.z() > 0.29 && p.z() < 0.31) heights.insert(p.z());
  }
  return heights;
}

int triangle_facets(const Plc& plc) {
  int triangles = 0;
  for (const Plc::Facet& facet : plc.facets) {
    if (facet.polygons.size() == 1 && facet.polygons.front().size() == 3) ++triangles;
  }
  return triangles;
}

bool mentions(const std::vector<std::string>& lines, const std::string& text) {
  for (const std::string& line : lines) {
    if (line.find(text) != std::string::npos) return true;
  }
  return false;
}

TEST(StepPlaneTolerance, PlanesUlpsApartBecomeOnePlaneOfPolygonalFacets) {
  ASSERT_NE(0.1 + 0.2, 0.3);  // the premise of the test file
  WarningLog log;
  StepImportOptions options;
  options.log = &log;
  const Expected<Plc> plc = import_step(ulp_planes(), options);
  ASSERT_TRUE(plc.has_value()) << plc.error().describe();
  EXPECT_EQ(triangle_facets(*plc), 0);
  EXPECT_TRUE(validate_plc(*plc).empty());
  EXPECT_EQ(plc->regions.size(), 2u);
  EXPECT_EQ(contact_heights(*plc).size(), 1u);
  EXPECT_TRUE(mentions(log.warnings, "1 coordinate-plane value(s) merged")) << ::testing::PrintToString(log.warnings);
}

TEST(StepPlaneTolerance, WithoutMergingTheFacesAtTheContactAreTriangulated) {
  WarningLog log;
  StepImportOptions options;
  options.log = &log;
  options.relative_plane_tolerance = 0.0;
  const Expected<Plc> plc = import_step(ulp_planes(), options);
  ASSERT_TRUE(plc.has_value()) << plc.error().describe();
  EXPECT_GT(triangle_facets(*plc), 0);
  EXPECT_EQ(contact_heights(*plc).size(), 2u);
  EXPECT_TRUE(validate_plc(*plc).empty());
  EXPECT_FALSE(mentions(log.warnings, "merged")) << ::testing::PrintToString(log.warnings);
}

TEST(StepPlaneTolerance, OutOfRangeToleranceIsRefused) {
  StepImportOptions options;
  options.relative_plane_tolerance = 0.01;
  const Expected<Plc> plc = import_step(ulp_planes(), options);
  ASSERT_FALSE(plc.has_value());
  EXPECT_EQ(plc.error().code, ErrorCode::InvalidOption);
}

}  // namespace
}  // namespace delmesh
