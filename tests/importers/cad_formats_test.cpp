// BREP and IGES go through the same CAD importer as STEP (importers/step/): two touching
// unit boxes are glued into two regions sharing one facet; the IGES file's product names
// and colours reach the region and marker tables; OpenCASCADE's reader messages do not
// reach stdout.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <set>
#include <string>

#include "importers/step/step_importer.h"
#include "tests/support/test_paths.h"
#include "toolkit/plc/plc_validate.h"

namespace delmesh {
namespace {

// tests/data/step/two_boxes.{brep,igs}: unit boxes at x in [0, 1] ("left", red) and
// [1, 2] ("right", blue), written with OpenCASCADE (see tests/data/LICENSES.md).
void expect_two_glued_boxes(const Plc& plc) {
  EXPECT_EQ(plc.regions.size(), 2u);
  EXPECT_EQ(plc.points.size(), 12u);
  EXPECT_EQ(plc.facets.size(), 11u);  // 6 + 6 box sides, the shared side once
  std::set<int> markers;
  for (const Plc::Facet& facet : plc.facets) markers.insert(facet.marker);
  EXPECT_EQ(markers.size(), 11u);
  EXPECT_TRUE(validate_plc(plc).empty());
}

TEST(CadFormats, BrepAssemblyIsGlued) {
  const Expected<Plc> plc = import_step(test::test_data_dir() / "step" / "two_boxes.brep", StepImportOptions{});
  ASSERT_TRUE(plc.has_value()) << plc.error().describe();
  expect_two_glued_boxes(*plc);
  EXPECT_TRUE(plc->region_names.empty());  // BREP has no names or colours
  EXPECT_TRUE(plc->facet_marker_colors.empty());
}

TEST(CadFormats, IgesKeepsProductNamesAndColoursAndPrintsNothing) {
  std::fflush(stdout);
  testing::internal::CaptureStdout();
  const Expected<Plc> plc = import_step(test::test_data_dir() / "step" / "two_boxes.igs", StepImportOptions{});
  const std::string printed = testing::internal::GetCapturedStdout();
  EXPECT_EQ(printed, "");
  ASSERT_TRUE(plc.has_value()) << plc.error().describe();
  expect_two_glued_boxes(*plc);
  ASSERT_EQ(plc->region_names.size(), 2u);
  ASSERT_EQ(plc->region_colors.size(), 2u);
  for (const Plc::Region& region : plc->regions) {
    const bool left = region.point.x() < 1.0;
    EXPECT_EQ(plc->region_names.at(region.id), left ? "left" : "right");
    const Plc::Color& c = plc->region_colors.at(region.id);
    EXPECT_NEAR(c.r, left ? 1.0 : 0.0, 1e-9);
    EXPECT_NEAR(c.g, 0.0, 1e-9);
    EXPECT_NEAR(c.b, left ? 0.0 : 1.0, 1e-9);
  }
  // Every side has its box's colour; the shared side keeps one of the two.
  int red = 0, blue = 0;
  for (const Plc::Facet& facet : plc->facets) {
    const Plc::Color& c = plc->facet_marker_colors.at(facet.marker);
    const bool is_red = std::abs(c.r - 1.0) < 1e-9 && std::abs(c.g) < 1e-9 && std::abs(c.b) < 1e-9;
    const bool is_blue = std::abs(c.r) < 1e-9 && std::abs(c.g) < 1e-9 && std::abs(c.b - 1.0) < 1e-9;
    red += is_red;
    blue += is_blue;
  }
  EXPECT_EQ(red + blue, 11);
  EXPECT_GE(red, 5);
  EXPECT_GE(blue, 5);
}

}  // namespace
}  // namespace delmesh
