// Radius-edge ratios of nearly flat tets (toolkit/quality): a tet whose orientation is
// positive but whose double determinant rounds to zero gets its circumradius from the
// long double fallback, checked against the exact rational value; a tet flat to that
// precision as well is reported apart (TetQualityReport::flat_ratio_tets), not as an
// infinite max or mean.
#include <gtest/gtest.h>
#include <gmpxx.h>

#include <array>
#include <cmath>

#include "toolkit/predicates/predicates.h"
#include "toolkit/quality/tet_quality.h"

namespace delmesh {
namespace {

/// The exact squared circumradius of abcd, in rationals.
mpq_class exact_circumradius2(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  using V = std::array<mpq_class, 3>;
  auto sub = [](const Vec3& p, const Vec3& q) { return V{mpq_class(p[0]) - q[0], mpq_class(p[1]) - q[1], mpq_class(p[2]) - q[2]}; };
  auto cross = [](const V& x, const V& y) {
    return V{x[1] * y[2] - x[2] * y[1], x[2] * y[0] - x[0] * y[2], x[0] * y[1] - x[1] * y[0]};
  };
  auto dot = [](const V& x, const V& y) { return mpq_class(x[0] * y[0] + x[1] * y[1] + x[2] * y[2]); };
  const V u = sub(b, a), v = sub(c, a), w = sub(d, a);
  const V vw = cross(v, w), wu = cross(w, u), uv = cross(u, v);
  const mpq_class denom = 2 * dot(u, vw);
  mpq_class r2 = 0;
  for (int k = 0; k < 3; ++k) {
    const mpq_class x = (dot(u, u) * vw[k] + dot(v, v) * wu[k] + dot(w, w) * uv[k]) / denom;
    r2 += x * x;
  }
  return r2;
}

TEST(TetQualityFlat, PositiveTetWhoseDoubleDeterminantIsZero) {
  // det[b-a, c-a, d-a] = (1 + 2^-30)^2 - (1 + 2^-29) = 2^-60: the double product rounds
  // the 2^-60 away.
  const double e = std::ldexp(1.0, -30);
  const Vec3 a(0, 0, 0), b(1, 0, 0), c(0, 1 + e, 1 + 2 * e), d(0, 1, 1 + e);
  ASSERT_EQ(predicates::orient3d(a.data(), b.data(), c.data(), d.data()), Sign::Positive);
  ASSERT_EQ((b - a).dot((c - a).cross(d - a)), 0.0);
  const double r = circumradius(a, b, c, d);
  ASSERT_TRUE(std::isfinite(r));
  const double exact = std::sqrt(exact_circumradius2(a, b, c, d).get_d());
  EXPECT_NEAR(r, exact, 1e-8 * exact);
  EXPECT_TRUE(std::isfinite(radius_edge_ratio(a, b, c, d)));
}

TEST(TetQualityFlat, ExactlyFlatTetIsCountedApart) {
  TetraMesh mesh;
  mesh.points = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1), Vec3(1, 1, 0)};
  mesh.tets = {{0, 1, 2, 3}, {0, 1, 4, 2}};  // the second is flat: all in z = 0
  const double ratio = radius_edge_ratio(mesh.points[0], mesh.points[1], mesh.points[2], mesh.points[3]);
  const TetQualityReport q = tet_quality_report(mesh, 1.0);
  EXPECT_EQ(q.tets, 2u);
  EXPECT_EQ(q.flat_ratio_tets, 1u);
  EXPECT_DOUBLE_EQ(q.max_radius_edge, ratio);
  EXPECT_DOUBLE_EQ(q.mean_radius_edge, ratio);
  EXPECT_EQ(q.above_radius_edge, 1u);  // the flat tet is above every bound
  EXPECT_EQ(q.radius_edge_counts.back(), 1u);
}

}  // namespace
}  // namespace delmesh
