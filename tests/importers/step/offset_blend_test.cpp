// Unit tests of the blend of a loose face's edge offsets into the face
// (importers/step/offset_blend.h): the boundary's own offsets on the boundary, linear
// along each piece, fading as (1 - d / reach)^2 with the distance to the boundary and zero
// beyond the reach.
#include <gtest/gtest.h>

#include <vector>

#include "importers/step/offset_blend.h"

namespace delmesh::step {
namespace {

void expect_near(const Vec3& got, const Vec3& expected, double tolerance = 1e-12) {
  EXPECT_NEAR((got - expected).norm(), 0.0, tolerance) << got.transpose() << " against " << expected.transpose();
}

// gmsh-t106-blade's trailing edge in miniature: the surface is the plane y = 0 (x along
// the edge, z up the face), the edge is the x axis moved 0.5 away from it in y, except
// that its offset grows linearly from 0 at x = 0 to 0.5 at x = 1 over one piece.
OffsetBlend bulging_edge() {
  const OffsetBlend::Sample start{Vec3(0.0, 0.0, 0.0), Vec3(0.0, 0.0, 0.0)};
  const OffsetBlend::Sample middle{Vec3(1.0, 0.0, 0.0), Vec3(0.0, 0.5, 0.0)};
  const OffsetBlend::Sample end{Vec3(3.0, 0.0, 0.0), Vec3(0.0, 0.5, 0.0)};
  return OffsetBlend({{start, middle}, {middle, end}}, 1.0);
}

TEST(OffsetBlend, TheBoundaryKeepsItsOwnOffsetsLinearAlongEachPiece) {
  const OffsetBlend blend = bulging_edge();
  expect_near(blend.offset(Vec3(0.0, 0.0, 0.0)), Vec3(0.0, 0.0, 0.0));
  expect_near(blend.offset(Vec3(1.0, 0.0, 0.0)), Vec3(0.0, 0.5, 0.0));
  // Between the samples, on the piece: the interpolated offset (a blend of the samples
  // alone, by distance to them, gave 0.25 / (1 + 0.25) of the way at a quarter: 0.1).
  expect_near(blend.offset(Vec3(0.25, 0.0, 0.0)), Vec3(0.0, 0.125, 0.0));
  expect_near(blend.offset(Vec3(2.0, 0.0, 0.0)), Vec3(0.0, 0.5, 0.0));
}

TEST(OffsetBlend, OffsetsFadeWithTheDistanceFromTheBoundaryOverTheReach) {
  const OffsetBlend blend = bulging_edge();
  // Above the second piece, its nearest point at (2, 0, 0) has offset 0.5; the first
  // piece, whose offsets are smaller, lies farther and weighs less, so the blend lies
  // between 0.5 (1 - d)^2 times the smallest and the largest offsets.
  for (const double d : {0.1, 0.25, 0.5, 0.9}) {
    const Vec3 got = blend.offset(Vec3(2.0, 0.0, d));
    const double fade = (1.0 - d) * (1.0 - d);
    EXPECT_GT(got.y(), 0.4 * fade) << d;
    EXPECT_LE(got.y(), 0.5 * fade + 1e-12) << d;
    EXPECT_NEAR(got.x(), 0.0, 1e-12);
    EXPECT_NEAR(got.z(), 0.0, 1e-12);
  }
  // Near the boundary the surface point takes almost the whole offset: no lip of
  // BRepMesh's first row (the face's points go from the edge onto the surface over the
  // reach, not over that row).
  EXPECT_GT(blend.offset(Vec3(2.0, 0.0, 0.01)).y(), 0.49);
  expect_near(blend.offset(Vec3(2.0, 0.0, 1.0)), Vec3(0.0, 0.0, 0.0));
  expect_near(blend.offset(Vec3(2.0, 0.0, 5.0)), Vec3(0.0, 0.0, 0.0));
}

TEST(OffsetBlend, TheBlendIsContinuousAlongTheBoundary) {
  // A close row of points 0.01 above the edge: neighbouring offsets differ by at most what
  // the edge's own offsets do over the step (no stairs between samples).
  const OffsetBlend blend = bulging_edge();
  Vec3 last = blend.offset(Vec3(0.0, 0.0, 0.01));
  for (int k = 1; k <= 300; ++k) {
    const Vec3 next = blend.offset(Vec3(0.01 * k, 0.0, 0.01));
    EXPECT_LT((next - last).norm(), 0.006) << k;  // the edge's offsets change by 0.005 per step at most
    last = next;
  }
}

TEST(OffsetBlend, NoPiecesNoOffset) {
  const OffsetBlend blend({}, 1.0);
  expect_near(blend.offset(Vec3(1.0, 2.0, 3.0)), Vec3(0.0, 0.0, 0.0));
}

}  // namespace
}  // namespace delmesh::step
