// Unit tests of the node moves and flips after surface refinement
// (importers/step/surface_smoothing.h) on synthetic planar faces.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "importers/step/surface_smoothing.h"
#include "toolkit/predicates/predicates.h"
#include "tests/importers/step/face_angles.h"

namespace delmesh::step {
namespace {

/// A regular hexagon of radius 10 in the plane z = 0 (u = x, v = y), its six sides CAD
/// edges, fanned from one inner node placed 0.5 from corner 0: the fan's triangles at
/// that corner are slivers.
struct Hexagon {
  std::vector<Vec3> points;
  SurfaceMeshes meshes;

  Hexagon() {
    SurfaceMeshes::Face face;
    for (int k = 0; k < 6; ++k) {
      const double a = k * std::numbers::pi / 3.0;
      points.emplace_back(10.0 * std::cos(a), 10.0 * std::sin(a), 0.0);
    }
    points.emplace_back(9.5, 0.0, 0.0);
    for (std::uint32_t k = 0; k < 7; ++k) {
      face.node_vertex.push_back(k);
      face.uv.push_back({points[k].x(), points[k].y()});
    }
    for (std::uint32_t k = 0; k < 6; ++k) face.triangles.push_back({k, (k + 1) % 6, 6});
    meshes.faces = {face};
    for (std::uint32_t k = 0; k < 6; ++k) {
      meshes.edges.push_back({{0.0, 10.0}, {k, (k + 1) % 6}});
    }
  }
};

const SurfacePoint kPlane = [](std::size_t, const Point2& uv) { return Vec3(uv[0], uv[1], 0.0); };
const SurfaceNormal kUp = [](std::size_t, const Point2&) { return Vec3(0.0, 0.0, 1.0); };

TEST(SurfaceSmoothing, InnerNodeMovesToLiftTheSmallestAngle) {
  Hexagon hexagon;
  const std::vector<Vec3> before = hexagon.points;
  ASSERT_LT(face_min_angle_deg(hexagon.meshes, 0, hexagon.points), 5.0);
  const SurfaceSmoothingStats stats =
      smooth_surface_meshes(hexagon.meshes, hexagon.points, SurfaceSmoothingOptions{}, kPlane, kUp);
  EXPECT_GT(stats.moves, 0u);
  // The fan's best centre is the hexagon's: every angle 60 degrees there.
  EXPECT_GE(face_min_angle_deg(hexagon.meshes, 0, hexagon.points), 50.0);
  // Nodes on CAD edges stay; the moved node lies on the surface at its parameters.
  for (std::size_t k = 0; k < 6; ++k) EXPECT_EQ(hexagon.points[k], before[k]);
  const SurfaceMeshes::Face& face = hexagon.meshes.faces[0];
  EXPECT_EQ(hexagon.points[6], kPlane(0, face.uv[6]));
  for (const auto& t : face.triangles) {
    EXPECT_EQ(predicates::orient2d(face.uv[t[0]].data(), face.uv[t[1]].data(), face.uv[t[2]].data()), Sign::Positive);
  }
}

TEST(SurfaceSmoothing, FacesNotRefinedAreLeftAlone) {
  Hexagon hexagon;
  hexagon.meshes.faces[0].refine = false;
  const std::vector<Vec3> before = hexagon.points;
  const SurfaceSmoothingStats stats =
      smooth_surface_meshes(hexagon.meshes, hexagon.points, SurfaceSmoothingOptions{}, kPlane, kUp);
  EXPECT_EQ(stats.moves + stats.flips, 0u);
  EXPECT_EQ(hexagon.points, before);
}

/// A convex quad of two triangles, its four sides CAD edges, whose diagonal 0-2 leaves a
/// 4.6-degree sliver; the other diagonal gives two triangles over 30 degrees: it is
/// flipped.
TEST(SurfaceSmoothing, SliverPairIsFlippedByTheMaxMinAngle) {
  std::vector<Vec3> points{{0, 0, 0}, {10, -0.8, 0}, {20, 0, 0}, {10, 6, 0}};
  SurfaceMeshes meshes;
  SurfaceMeshes::Face face;
  face.node_vertex = {0, 1, 2, 3};
  for (const Vec3& p : points) face.uv.push_back({p.x(), p.y()});
  face.triangles = {{0, 1, 2}, {0, 2, 3}};
  meshes.faces = {face};
  for (std::uint32_t k = 0; k < 4; ++k) meshes.edges.push_back({{0.0, 1.0}, {k, (k + 1) % 4}});
  ASSERT_LT(face_min_angle_deg(meshes, 0, points), 5.0);
  const SurfaceSmoothingStats stats = smooth_surface_meshes(meshes, points, SurfaceSmoothingOptions{}, kPlane, kUp);
  EXPECT_EQ(stats.flips, 1u);
  EXPECT_GT(face_min_angle_deg(meshes, 0, points), 30.0);
}

}  // namespace
}  // namespace delmesh::step
