// Unit tests of the tessellation of a CAD face as its own surface
// (importers/step/tessellation_surface.h): the piecewise linear map of BRepMesh's triangles
// from the parameter plane to 3D, with the linear continuation of the nearest triangle
// outside the face and triangles collapsed at a pole left out.
#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <vector>

#include "importers/step/tessellation_surface.h"

namespace delmesh::step {
namespace {

// A folded strip: two triangles over the unit square of the parameter plane, bent by 90
// degrees along the diagonal (0,0)-(1,1), as BRepMesh's chords bend round a trailing edge.
struct FoldedStrip {
  std::vector<Point2> uv = {{0.0, 0.0}, {1.0, 0.0}, {1.0, 1.0}, {0.0, 1.0}};
  std::vector<Vec3> points = {Vec3(0.0, 0.0, 0.0), Vec3(1.0, 0.0, 0.0), Vec3(1.0, 1.0, 0.0), Vec3(0.0, 1.0, 1.0)};
  std::vector<std::array<std::uint32_t, 3>> triangles = {{0, 1, 2}, {0, 2, 3}};
};

void expect_near(const Vec3& got, const Vec3& expected) {
  EXPECT_NEAR((got - expected).norm(), 0.0, 1e-12) << got.transpose() << " against " << expected.transpose();
}

TEST(TessellationSurface, NodesMapToTheirPoints) {
  const FoldedStrip strip;
  const TessellationSurface surface(strip.uv, strip.points, strip.triangles);
  ASSERT_FALSE(surface.empty());
  for (std::size_t i = 0; i < strip.uv.size(); ++i) expect_near(surface.point(strip.uv[i]), strip.points[i]);
}

TEST(TessellationSurface, EachTriangleMapsAffinelyOntoItsOwnPlane) {
  const FoldedStrip strip;
  const TessellationSurface surface(strip.uv, strip.points, strip.triangles);
  // Below the diagonal: the flat triangle (z = 0); above it: the bent one (z = v - u).
  expect_near(surface.point({0.75, 0.25}), Vec3(0.75, 0.25, 0.0));
  expect_near(surface.point({0.25, 0.75}), Vec3(0.25, 0.75, 0.5));
  // On the fold line both give the same point.
  expect_near(surface.point({0.5, 0.5}), Vec3(0.5, 0.5, 0.0));
}

TEST(TessellationSurface, OutsideTheFaceTheNearestTriangleContinuesLinearly) {
  const FoldedStrip strip;
  const TessellationSurface surface(strip.uv, strip.points, strip.triangles);
  // Beyond the edge v = 1 of the bent triangle (its smallest barycentric coordinate is the
  // largest there): its plane z = v - u continued.
  expect_near(surface.point({0.25, 1.25}), Vec3(0.25, 1.25, 1.0));
  // Beyond u = 1, next to the flat triangle.
  expect_near(surface.point({1.5, 0.25}), Vec3(1.5, 0.25, 0.0));
}

TEST(TessellationSurface, TrianglesCollapsedInTheParameterPlaneAreLeftOut) {
  FoldedStrip strip;
  // A triangle of zero parameter area (two copies of a pole at one parameter point) whose
  // points would send every parameter on its segment far away if it were used.
  strip.uv.push_back({0.5, 0.0});
  strip.points.push_back(Vec3(0.5, -100.0, 0.0));
  strip.triangles.push_back({0, 4, 1});
  const TessellationSurface surface(strip.uv, strip.points, strip.triangles);
  expect_near(surface.point({0.5, 0.0}), Vec3(0.5, 0.0, 0.0));
  const TessellationSurface collapsed_only(strip.uv, strip.points, {{0, 4, 1}});
  EXPECT_TRUE(collapsed_only.empty());
}

TEST(TessellationSurface, ManyTrianglesAreFoundThroughTheGrid) {
  // A 20 x 10 grid of a cylinder's chords in (u, v): every parameter point inside maps onto
  // the chord plane of its own cell, wherever the grid of cells puts it.
  constexpr int kColumns = 20, kRows = 10;
  std::vector<Point2> uv;
  std::vector<Vec3> points;
  for (int j = 0; j <= kRows; ++j) {
    for (int i = 0; i <= kColumns; ++i) {
      const double u = i * 0.1, v = j * 0.5;
      uv.push_back({u, v});
      points.push_back(Vec3(std::cos(u), std::sin(u), v));
    }
  }
  std::vector<std::array<std::uint32_t, 3>> triangles;
  const auto node = [](int i, int j) { return static_cast<std::uint32_t>(j * (kColumns + 1) + i); };
  for (int j = 0; j < kRows; ++j) {
    for (int i = 0; i < kColumns; ++i) {
      triangles.push_back({node(i, j), node(i + 1, j), node(i + 1, j + 1)});
      triangles.push_back({node(i, j), node(i + 1, j + 1), node(i, j + 1)});
    }
  }
  const TessellationSurface surface(uv, points, triangles);
  for (int i = 0; i < kColumns; ++i) {
    // A point on the chord of column i at a quarter of the way, at height 1.3.
    const double u0 = i * 0.1;
    const Vec3 chord = 0.75 * Vec3(std::cos(u0), std::sin(u0), 0.0) + 0.25 * Vec3(std::cos(u0 + 0.1), std::sin(u0 + 0.1), 0.0);
    expect_near(surface.point({u0 + 0.025, 1.3}), chord + Vec3(0.0, 0.0, 1.3));
  }
}

}  // namespace
}  // namespace delmesh::step
