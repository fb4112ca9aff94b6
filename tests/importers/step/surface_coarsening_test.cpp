// Unit tests of the collapses of crowded inner nodes after surface refinement
// (importers/step/surface_coarsening.h) on synthetic planar faces.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <set>
#include <vector>

#include "importers/step/surface_coarsening.h"
#include "importers/step/surface_smoothing.h"
#include "toolkit/predicates/predicates.h"
#include "tests/importers/step/face_angles.h"

namespace delmesh::step {
namespace {

const SurfacePoint kPlane = [](std::size_t, const Point2& uv) { return Vec3(uv[0], uv[1], 0.0); };
const SurfaceNormal kUp = [](std::size_t, const Point2&) { return Vec3(0.0, 0.0, 1.0); };

/// gmsh-fusee-rocket's face 107 in small: a strip 11 long and 2.83 wide in the plane z = 0
/// (u = x, v = y) whose long lower side is one CAD segment A-B (0-1), its upper side two
/// segments C-M-D (2-3-4) and its ends B-C and D-A; an inner node N (5) stands 0.75 above
/// the middle of A-B, fanned to the boundary. Triangle A-B-N is a 7.8-degree needle that no
/// position of N mends within its fan (it needs N near M, where N-C-M and N-M-D go flat);
/// collapsing N into M leaves A-B-M, B-C-M and M-D-A, all over 27 degrees.
struct Strip {
  std::vector<Vec3> points{{0, 0, 0}, {11, 0, 0}, {11, 2.83, 0}, {5.5, 2.83, 0}, {0, 2.83, 0}, {5.5, 0.75, 0}};
  SurfaceMeshes meshes;

  Strip() {
    SurfaceMeshes::Face face;
    for (std::uint32_t k = 0; k < points.size(); ++k) {
      face.node_vertex.push_back(k);
      face.uv.push_back({points[k].x(), points[k].y()});
    }
    for (std::uint32_t k = 0; k < 5; ++k) face.triangles.push_back({k, (k + 1) % 5, 5});
    meshes.faces = {face};
    for (std::uint32_t k = 0; k < 5; ++k) meshes.edges.push_back({{0.0, 1.0}, {k, (k + 1) % 5}});
  }
};

TEST(SurfaceCoarsening, NodeMovesAloneLeaveTheStripsNeedle) {
  Strip strip;
  ASSERT_LT(face_min_angle_deg(strip.meshes, 0, strip.points), 8.0);
  smooth_surface_meshes(strip.meshes, strip.points, SurfaceSmoothingOptions{}, kPlane, kUp);
  EXPECT_LT(face_min_angle_deg(strip.meshes, 0, strip.points), 20.0);
}

TEST(SurfaceCoarsening, CrowdedInnerNodeIsCollapsedIntoTheNeighbourThatMendsItsStar) {
  Strip strip;
  const std::vector<Vec3> before = strip.points;
  const std::size_t removed =
      coarsen_surface_meshes(strip.meshes, strip.points, SurfaceCoarseningOptions{}, kPlane, kUp);
  EXPECT_EQ(removed, 1u);
  EXPECT_EQ(strip.points, before);  // no point moves
  const SurfaceMeshes::Face& face = strip.meshes.faces[0];
  ASSERT_EQ(face.triangles.size(), 3u);
  std::set<std::uint32_t> used;
  for (const auto& t : face.triangles) {
    used.insert(t.begin(), t.end());
    EXPECT_EQ(predicates::orient2d(face.uv[t[0]].data(), face.uv[t[1]].data(), face.uv[t[2]].data()), Sign::Positive);
  }
  EXPECT_EQ(used, (std::set<std::uint32_t>{0, 1, 2, 3, 4}));
  EXPECT_GT(face_min_angle_deg(strip.meshes, 0, strip.points), 27.0);
}

TEST(SurfaceCoarsening, NodesOnCadEdgesAndFacesNotRefinedStay) {
  Strip on_edge;
  on_edge.meshes.edges.push_back({{0.0}, {5}});  // N on a CAD edge
  EXPECT_EQ(coarsen_surface_meshes(on_edge.meshes, on_edge.points, SurfaceCoarseningOptions{}, kPlane, kUp), 0u);
  EXPECT_EQ(on_edge.meshes.faces[0].triangles.size(), 5u);
  Strip unrefined;
  unrefined.meshes.faces[0].refine = false;
  EXPECT_EQ(coarsen_surface_meshes(unrefined.meshes, unrefined.points, SurfaceCoarseningOptions{}, kPlane, kUp), 0u);
  EXPECT_EQ(unrefined.meshes.faces[0].triangles.size(), 5u);
}

TEST(SurfaceCoarsening, CollapseThatLeavesATriangleFarFromTheSurfaceIsRefused) {
  // The surface bulges 1 unit above the plane at mid-strip: A-B-M's centre would lie about
  // that far from it, over a deflection bound of 0.1 (the fan's triangles, through N on
  // the bulge, stay closer).
  Strip strip;
  const SurfacePoint bulge = [](std::size_t, const Point2& uv) {
    return Vec3(uv[0], uv[1], std::sin(std::numbers::pi * uv[0] / 11.0) * std::sin(std::numbers::pi * uv[1] / 2.83));
  };
  for (std::size_t k = 0; k < strip.points.size(); ++k) strip.points[k] = bulge(0, strip.meshes.faces[0].uv[k]);
  SurfaceCoarseningOptions options;
  options.max_deflection = 0.1;
  EXPECT_EQ(coarsen_surface_meshes(strip.meshes, strip.points, options, bulge, {}), 0u);
  options.max_deflection = 0.0;  // off
  EXPECT_EQ(coarsen_surface_meshes(strip.meshes, strip.points, options, bulge, {}), 1u);
}

}  // namespace
}  // namespace delmesh::step
