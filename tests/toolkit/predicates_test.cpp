// Exact predicates checked against exact rational arithmetic (GMP): random inputs,
// nearly degenerate inputs (rounded collinear/coplanar/cocircular points, last-bit
// neighbours) and exactly degenerate ones (grids, cocircular and cospherical integer
// points). Symbolic perturbation is checked against an explicit tiny perturbation of the
// lifted coordinates evaluated exactly.
#include <gmpxx.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <random>
#include <set>
#include <vector>

#include "toolkit/predicates/predicates.h"

namespace delmesh::predicates {
namespace {

using P3 = std::array<double, 3>;
using Q = mpq_class;

Sign sign_of(const Q& q) { return q > 0 ? Sign::Positive : (q < 0 ? Sign::Negative : Sign::Zero); }

Q det3(const Q m[3][3]) {
  return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
         m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
         m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
}

Q det4(const Q m[4][4]) {
  Q total = 0;
  for (int col = 0; col < 4; ++col) {
    Q minor[3][3];
    for (int r = 1; r < 4; ++r)
      for (int c = 0, k = 0; c < 4; ++c)
        if (c != col) minor[r - 1][k++] = m[r][c];
    const Q term = m[0][col] * det3(minor);
    total += (col % 2 == 0) ? term : Q(-term);
  }
  return total;
}

Sign exact_orient2d(const double* a, const double* b, const double* c) {
  const Q bx = Q(b[0]) - Q(a[0]), by = Q(b[1]) - Q(a[1]);
  const Q cx = Q(c[0]) - Q(a[0]), cy = Q(c[1]) - Q(a[1]);
  return sign_of(bx * cy - by * cx);
}

Sign exact_orient3d(const double* a, const double* b, const double* c, const double* d) {
  Q m[3][3];
  const double* rows[3] = {b, c, d};
  for (int r = 0; r < 3; ++r)
    for (int k = 0; k < 3; ++k) m[r][k] = Q(rows[r][k]) - Q(a[k]);
  return sign_of(det3(m));
}

/// Incircle with lifts |p - d|^2 + extra[i]: positive inside for ccw a, b, c.
Sign exact_incircle(const double* a, const double* b, const double* c, const double* d,
                    const std::array<Q, 4>& extra = {}) {
  const double* pts[4] = {a, b, c, d};
  // 4x4 [x, y, x^2+y^2 (+extra), 1], expanded about d by translation.
  Q m[3][3];
  for (int r = 0; r < 3; ++r) {
    const Q x = Q(pts[r][0]) - Q(d[0]), y = Q(pts[r][1]) - Q(d[1]);
    m[r][0] = x;
    m[r][1] = y;
    m[r][2] = x * x + y * y + extra[r] - extra[3];
  }
  return sign_of(det3(m));
}

/// Insphere with our convention (positive inside when orient3d(a,b,c,d) is positive),
/// with optional extra lifts.
Sign exact_insphere(const double* a, const double* b, const double* c, const double* d,
                    const double* e, const std::array<Q, 5>& extra = {}) {
  const double* pts[5] = {a, b, c, d, e};
  Q m[4][4];
  for (int r = 0; r < 4; ++r) {
    const Q x = Q(pts[r][0]) - Q(e[0]), y = Q(pts[r][1]) - Q(e[1]), z = Q(pts[r][2]) - Q(e[2]);
    m[r][0] = x;
    m[r][1] = y;
    m[r][2] = z;
    m[r][3] = x * x + y * y + z * z + extra[r] - extra[4];
  }
  // det[x y z lift] over rows a..d is positive for e inside when Shewchuk's orientation
  // det[a-d, b-d, c-d] is positive, i.e. when ours is negative: negate.
  return -sign_of(det4(m));
}

class PredicatesTest : public ::testing::Test {
 protected:
  std::mt19937_64 rng{12345};
  double uniform(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng); }
  P3 random_point(double scale = 1.0) {
    return {uniform(-scale, scale), uniform(-scale, scale), uniform(-scale, scale)};
  }
  /// Moves x by k units in the last place.
  static double ulps(double x, int k) {
    for (int i = 0; i < std::abs(k); ++i) x = std::nextafter(x, k > 0 ? INFINITY : -INFINITY);
    return x;
  }
};

TEST_F(PredicatesTest, SignConventionsOnSimplePoints) {
  const double o[3] = {0, 0, 0}, x[3] = {1, 0, 0}, y[3] = {0, 1, 0}, z[3] = {0, 0, 1};
  EXPECT_EQ(orient2d(o, x, y), Sign::Positive);
  EXPECT_EQ(orient2d(o, y, x), Sign::Negative);
  EXPECT_EQ(orient3d(o, x, y, z), Sign::Positive);
  EXPECT_EQ(orient3d(o, y, x, z), Sign::Negative);
  const double inside2[2] = {0.25, 0.25}, outside2[2] = {2, 2};
  EXPECT_EQ(incircle(o, x, y, inside2), Sign::Positive);
  EXPECT_EQ(incircle(o, x, y, outside2), Sign::Negative);
  EXPECT_EQ(incircle(o, y, x, inside2), Sign::Negative);
  const double inside3[3] = {0.2, 0.2, 0.2}, outside3[3] = {2, 2, 2};
  EXPECT_EQ(insphere(o, x, y, z, inside3), Sign::Positive);
  EXPECT_EQ(insphere(o, x, y, z, outside3), Sign::Negative);
  EXPECT_EQ(insphere(o, y, x, z, inside3), Sign::Negative);
  const double one_one[2] = {1, 1};
  EXPECT_EQ(incircle(o, x, y, one_one), Sign::Zero);
  const double far[3] = {1, 1, 0};
  EXPECT_EQ(insphere(o, x, y, z, far), Sign::Zero);
}

TEST_F(PredicatesTest, RandomInputsMatchExactArithmetic) {
  for (int i = 0; i < 20000; ++i) {
    const double scale = std::ldexp(1.0, static_cast<int>(uniform(-30, 30)));
    const P3 a = random_point(scale), b = random_point(scale), c = random_point(scale),
             d = random_point(scale), e = random_point(scale);
    ASSERT_EQ(orient2d(a.data(), b.data(), c.data()), exact_orient2d(a.data(), b.data(), c.data()));
    ASSERT_EQ(orient3d(a.data(), b.data(), c.data(), d.data()),
              exact_orient3d(a.data(), b.data(), c.data(), d.data()));
    ASSERT_EQ(incircle(a.data(), b.data(), c.data(), d.data()),
              exact_incircle(a.data(), b.data(), c.data(), d.data()));
    if (i % 4 == 0) {
      ASSERT_EQ(insphere(a.data(), b.data(), c.data(), d.data(), e.data()),
                exact_insphere(a.data(), b.data(), c.data(), d.data(), e.data()));
    }
  }
}

TEST_F(PredicatesTest, NearlyCollinearAndCoplanarPointsMatchExactArithmetic) {
  int zeros = 0, nonzeros = 0;
  for (int i = 0; i < 20000; ++i) {
    const P3 a = random_point(), b = random_point(), c = random_point();
    const double t = uniform(-2, 3);
    // p on line ab (rounded), then nudged by a few ulps
    P3 p;
    for (int k = 0; k < 3; ++k) p[k] = ulps(a[k] + t * (b[k] - a[k]), static_cast<int>(uniform(-3, 4)));
    const Sign s2 = orient2d(a.data(), b.data(), p.data());
    ASSERT_EQ(s2, exact_orient2d(a.data(), b.data(), p.data()));
    (s2 == Sign::Zero ? zeros : nonzeros)++;
    // q on plane abc (rounded), nudged
    const double u = uniform(-1, 2), v = uniform(-1, 2);
    P3 q;
    for (int k = 0; k < 3; ++k)
      q[k] = ulps(a[k] + u * (b[k] - a[k]) + v * (c[k] - a[k]), static_cast<int>(uniform(-2, 3)));
    ASSERT_EQ(orient3d(a.data(), b.data(), c.data(), q.data()),
              exact_orient3d(a.data(), b.data(), c.data(), q.data()));
  }
  EXPECT_GT(nonzeros, 0);
}

TEST_F(PredicatesTest, NearlyCocircularAndCosphericalPointsMatchExactArithmetic) {
  for (int i = 0; i < 5000; ++i) {
    // points on a circle / sphere, rounded to doubles, then last-bit perturbed
    const double cx = uniform(-1, 1), cy = uniform(-1, 1), cz = uniform(-1, 1), r = uniform(0.1, 10);
    auto on_sphere = [&](bool flat) {
      const double th = uniform(0, 2 * M_PI), ph = flat ? M_PI / 2 : uniform(0, M_PI);
      P3 p{cx + r * std::sin(ph) * std::cos(th), cy + r * std::sin(ph) * std::sin(th),
           cz + r * std::cos(ph)};
      if (flat) p[2] = 0;
      return p;
    };
    const P3 a = on_sphere(true), b = on_sphere(true), c = on_sphere(true);
    P3 d = on_sphere(true);
    d[0] = ulps(d[0], static_cast<int>(uniform(-2, 3)));
    ASSERT_EQ(incircle(a.data(), b.data(), c.data(), d.data()),
              exact_incircle(a.data(), b.data(), c.data(), d.data()));
    const P3 sa = on_sphere(false), sb = on_sphere(false), sc = on_sphere(false),
             sd = on_sphere(false);
    P3 se = on_sphere(false);
    se[1] = ulps(se[1], static_cast<int>(uniform(-2, 3)));
    ASSERT_EQ(insphere(sa.data(), sb.data(), sc.data(), sd.data(), se.data()),
              exact_insphere(sa.data(), sb.data(), sc.data(), sd.data(), se.data()));
  }
}

TEST_F(PredicatesTest, IntegerGridsAreExactlyDegenerateWhereTheyShouldBe) {
  // All triples / quadruples of a 4x4x2 grid, scaled by an inexact factor too.
  for (double scale : {1.0, 0.1, 1e-7, 3e5}) {
    std::vector<P3> grid;
    for (int x = 0; x < 4; ++x)
      for (int y = 0; y < 4; ++y)
        for (int z = 0; z < 2; ++z) grid.push_back({x * scale, y * scale, z * scale});
    const std::size_t n = grid.size();
    int zero2 = 0, zero3 = 0, zeroc = 0;
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = 0; j < n; ++j)
        for (std::size_t k = 0; k < n; k += 3) {
          const Sign s2 = orient2d(grid[i].data(), grid[j].data(), grid[k].data());
          ASSERT_EQ(s2, exact_orient2d(grid[i].data(), grid[j].data(), grid[k].data()));
          zero2 += s2 == Sign::Zero;
          const std::size_t l = (i * 7 + j * 3 + k) % n;
          const Sign s3 = orient3d(grid[i].data(), grid[j].data(), grid[k].data(), grid[l].data());
          ASSERT_EQ(s3, exact_orient3d(grid[i].data(), grid[j].data(), grid[k].data(), grid[l].data()));
          zero3 += s3 == Sign::Zero;
          const Sign sc = incircle(grid[i].data(), grid[j].data(), grid[k].data(), grid[l].data());
          ASSERT_EQ(sc, exact_incircle(grid[i].data(), grid[j].data(), grid[k].data(), grid[l].data()));
          zeroc += sc == Sign::Zero;
          const std::size_t m = (i * 5 + k * 11 + 1) % n;
          ASSERT_EQ(insphere(grid[i].data(), grid[j].data(), grid[k].data(), grid[l].data(), grid[m].data()),
                    exact_insphere(grid[i].data(), grid[j].data(), grid[k].data(), grid[l].data(),
                                   grid[m].data()));
        }
    EXPECT_GT(zero2, 0);
    EXPECT_GT(zero3, 0);
    EXPECT_GT(zeroc, 0);
  }
}

TEST_F(PredicatesTest, CocircularAndCosphericalIntegerPointsGiveZero) {
  // Integer points on x^2 + y^2 = 25 and on x^2 + y^2 + z^2 = 9.
  const double c0[2] = {5, 0}, c1[2] = {3, 4}, c2[2] = {-4, 3}, c3[2] = {0, -5}, c4[2] = {4, -3};
  EXPECT_EQ(incircle(c0, c1, c2, c3), Sign::Zero);
  EXPECT_EQ(incircle(c0, c1, c2, c4), Sign::Zero);
  const double s0[3] = {3, 0, 0}, s1[3] = {0, 3, 0}, s2[3] = {0, 0, 3}, s3[3] = {1, 2, 2},
               s4[3] = {-2, 1, -2}, s5[3] = {2, -2, 1};
  EXPECT_EQ(insphere(s0, s1, s2, s3, s4), Sign::Zero);
  EXPECT_EQ(insphere(s0, s1, s2, s4, s5), Sign::Zero);
  // one unit in the last place off the circle / sphere is no longer zero
  const double c3_off[2] = {std::nextafter(3.0, 4.0), -4};
  EXPECT_EQ(incircle(c0, c1, c2, c3_off), exact_incircle(c0, c1, c2, c3_off));
  EXPECT_NE(incircle(c0, c1, c2, c3_off), Sign::Zero);
  const double s5_off[3] = {2, -2, std::nextafter(1.0, 2.0)};
  EXPECT_EQ(insphere(s0, s1, s2, s4, s5_off), exact_insphere(s0, s1, s2, s4, s5_off));
  EXPECT_NE(insphere(s0, s1, s2, s4, s5_off), Sign::Zero);
}

TEST_F(PredicatesTest, PointsDifferingInTheLastBit) {
  for (int i = 0; i < 5000; ++i) {
    const P3 a = random_point(1e3);
    P3 b = a, c = a, d = a, e = a;
    for (int k = 0; k < 3; ++k) {
      b[k] = ulps(a[k], static_cast<int>(uniform(-2, 3)));
      c[k] = ulps(a[k], static_cast<int>(uniform(-2, 3)));
      d[k] = ulps(a[k], static_cast<int>(uniform(-2, 3)));
      e[k] = ulps(a[k], static_cast<int>(uniform(-2, 3)));
    }
    ASSERT_EQ(orient2d(a.data(), b.data(), c.data()), exact_orient2d(a.data(), b.data(), c.data()));
    ASSERT_EQ(orient3d(a.data(), b.data(), c.data(), d.data()),
              exact_orient3d(a.data(), b.data(), c.data(), d.data()));
    ASSERT_EQ(incircle(a.data(), b.data(), c.data(), d.data()),
              exact_incircle(a.data(), b.data(), c.data(), d.data()));
    ASSERT_EQ(insphere(a.data(), b.data(), c.data(), d.data(), e.data()),
              exact_insphere(a.data(), b.data(), c.data(), d.data(), e.data()));
  }
}

TEST_F(PredicatesTest, DotProductSignsMatchExactArithmetic) {
  for (int i = 0; i < 20000; ++i) {
    const P3 a = random_point(), b = random_point();
    // c on the diametral sphere of ab (rounded): the right-angle boundary case
    const P3 mid{(a[0] + b[0]) / 2, (a[1] + b[1]) / 2, (a[2] + b[2]) / 2};
    const double r = std::sqrt((a[0] - mid[0]) * (a[0] - mid[0]) + (a[1] - mid[1]) * (a[1] - mid[1]) +
                               (a[2] - mid[2]) * (a[2] - mid[2]));
    const double th = uniform(0, 2 * M_PI);
    const P3 c{mid[0] + r * std::cos(th), mid[1] + r * std::sin(th), mid[2]};
    Q exact3 = 0, exact2 = 0;
    for (int k = 0; k < 3; ++k) {
      const Q term = (Q(a[k]) - Q(c[k])) * (Q(b[k]) - Q(c[k]));
      exact3 += term;
      if (k < 2) exact2 += term;
    }
    ASSERT_EQ(dot3d(a.data(), b.data(), c.data()), sign_of(exact3));
    ASSERT_EQ(dot2d(a.data(), b.data(), c.data()), sign_of(exact2));
  }
  const double u[2] = {0, 0}, v[2] = {2, 0}, w[2] = {1, 1};
  EXPECT_EQ(dot2d(u, v, w), Sign::Zero);  // right angle at w exactly
}

TEST_F(PredicatesTest, ProjectedOrientationUsesARightHandedFrame) {
  for (int i = 0; i < 5000; ++i) {
    const P3 a = random_point(), b = random_point(), c = random_point();
    const double ax[2] = {a[1], a[2]}, bx[2] = {b[1], b[2]}, cx[2] = {c[1], c[2]};
    const double ay[2] = {a[2], a[0]}, by[2] = {b[2], b[0]}, cy[2] = {c[2], c[0]};
    const double az[2] = {a[0], a[1]}, bz[2] = {b[0], b[1]}, cz[2] = {c[0], c[1]};
    ASSERT_EQ(orient2d_projected(a.data(), b.data(), c.data(), Axis::X), exact_orient2d(ax, bx, cx));
    ASSERT_EQ(orient2d_projected(a.data(), b.data(), c.data(), Axis::Y), exact_orient2d(ay, by, cy));
    ASSERT_EQ(orient2d_projected(a.data(), b.data(), c.data(), Axis::Z), exact_orient2d(az, bz, cz));
  }
  // a counterclockwise triangle seen from +x projects counterclockwise when dropping X
  const double p0[3] = {0, 0, 0}, p1[3] = {0, 1, 0}, p2[3] = {0, 0, 1};
  EXPECT_EQ(orient2d_projected(p0, p1, p2, Axis::X), Sign::Positive);
  const double q0[3] = {0, 0, 0}, q1[3] = {0, 0, 1}, q2[3] = {1, 0, 0};
  EXPECT_EQ(orient2d_projected(q0, q1, q2, Axis::Y), Sign::Positive);
}

TEST_F(PredicatesTest, CoplanarIncircleMatchesExactInPlaneCircleTest) {
  // Points on the plane z = x + 2y (integer coordinates, exact), normal (-1,-2,1): the
  // dominant axis is Y.
  std::uniform_int_distribution<int> coord(-6, 6);
  int zeros = 0;
  for (int i = 0; i < 20000; ++i) {
    auto pt = [&]() {
      const double x = coord(rng), y = coord(rng);
      return P3{x, y, x + 2 * y};
    };
    const P3 a = pt(), b = pt(), c = pt(), d = pt();
    // exact: d = a + s u + t v in the (u, v) basis, inside iff Q(s,t) - uu s - vv t < 0
    const Q ux = Q(b[0]) - a[0], uy = Q(b[1]) - a[1], uz = Q(b[2]) - a[2];
    const Q vx = Q(c[0]) - a[0], vy = Q(c[1]) - a[1], vz = Q(c[2]) - a[2];
    const Q wx = Q(d[0]) - a[0], wy = Q(d[1]) - a[1];
    const Q det = ux * vy - uy * vx;  // the x,y parametrisation is exact on this plane
    const Sign orientation = orient2d_projected(a.data(), b.data(), c.data(), Axis::Y);
    if (det == 0) {
      ASSERT_EQ(incircle_coplanar(a.data(), b.data(), c.data(), d.data(), Axis::Y), Sign::Zero);
      continue;
    }
    const Q s = (wx * vy - wy * vx) / det, t = (ux * wy - uy * wx) / det;
    const Q uu = ux * ux + uy * uy + uz * uz, vv = vx * vx + vy * vy + vz * vz;
    const Q uv = ux * vx + uy * vy + uz * vz;
    const Q value = s * s * uu + 2 * s * t * uv + t * t * vv - uu * s - vv * t;
    const Sign inside = -sign_of(value);
    zeros += inside == Sign::Zero;
    ASSERT_EQ(incircle_coplanar(a.data(), b.data(), c.data(), d.data(), Axis::Y), inside * orientation)
        << i;
  }
  EXPECT_GT(zeros, 0);
}

TEST_F(PredicatesTest, InPlaneIncircleMatchesExactLiftedDeterminant) {
  // Against the exact determinant with the quadratic-form lift, on random and
  // near-degenerate points (off-plane by roundoff), for every axis.
  for (int i = 0; i < 20000; ++i) {
    const Axis axis = static_cast<Axis>(i % 3);
    const P3 n = random_point(), a = random_point(), b = random_point(), c = random_point();
    P3 d = random_point();
    if (i % 2) {  // d near the projected circle: reuse a with last-bit moves
      for (int k = 0; k < 3; ++k) d[k] = ulps(a[k], static_cast<int>(uniform(-2, 3)));
    }
    const int k = static_cast<int>(axis), ii = (k + 1) % 3, jj = (k + 2) % 3;
    auto lifted = [&](const P3& p) {
      const Q x = Q(p[ii]) - Q(d[ii]), y = Q(p[jj]) - Q(d[jj]);
      const Q t = Q(n[ii]) * x + Q(n[jj]) * y;
      return std::array<Q, 3>{x, y, Q(n[k]) * Q(n[k]) * (x * x + y * y) + t * t};
    };
    Q m[3][3];
    const P3* rows[3] = {&a, &b, &c};
    for (int r = 0; r < 3; ++r) {
      const auto l = lifted(*rows[r]);
      for (int col = 0; col < 3; ++col) m[r][col] = l[col];
    }
    ASSERT_EQ(incircle_in_plane(a.data(), b.data(), c.data(), d.data(), axis, n.data()), sign_of(det3(m))) << i;
  }
}

TEST_F(PredicatesTest, InPlaneIncircleEqualsCoplanarIncircleOnAnExactPlane) {
  // Plane z = x + 2y, exact normal (-1, -2, 1): dominant axis Y.
  std::uniform_int_distribution<int> coord(-6, 6);
  const double normal[3] = {-1, -2, 1};
  for (int i = 0; i < 20000; ++i) {
    auto pt = [&]() {
      const double x = coord(rng), y = coord(rng);
      return P3{x, y, x + 2 * y};
    };
    const P3 a = pt(), b = pt(), c = pt(), d = pt();
    if (orient2d_projected(a.data(), b.data(), c.data(), Axis::Y) == Sign::Zero) continue;
    ASSERT_EQ(incircle_in_plane(a.data(), b.data(), c.data(), d.data(), Axis::Y, normal),
              incircle_coplanar(a.data(), b.data(), c.data(), d.data(), Axis::Y));
  }
}

Sign exact_in_equatorial_sphere(const P3& a, const P3& b, const P3& c, const P3& p) {
  Q u[3], v[3], w[3];
  for (int k = 0; k < 3; ++k) {
    u[k] = Q(b[k]) - Q(a[k]);
    v[k] = Q(c[k]) - Q(a[k]);
    w[k] = Q(p[k]) - Q(a[k]);
  }
  const Q n[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
  const Q nn = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
  if (nn == 0) return Sign::Zero;
  const Q uu = u[0] * u[0] + u[1] * u[1] + u[2] * u[2], vv = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
  Q t[3];
  for (int k = 0; k < 3; ++k) t[k] = uu * v[k] - vv * u[k];
  const Q center[3] = {(t[1] * n[2] - t[2] * n[1]) / (2 * nn), (t[2] * n[0] - t[0] * n[2]) / (2 * nn),
                       (t[0] * n[1] - t[1] * n[0]) / (2 * nn)};  // relative to a
  Q r2 = 0, d2 = 0;
  for (int k = 0; k < 3; ++k) {
    r2 += center[k] * center[k];
    d2 += (w[k] - center[k]) * (w[k] - center[k]);
  }
  return sign_of(r2 - d2);
}

TEST_F(PredicatesTest, EquatorialSphereMatchesExactArithmetic) {
  const P3 a{1, 0, 0}, b{0, 1, 0}, c{-1, 0, 0};
  EXPECT_EQ(in_equatorial_sphere(a.data(), b.data(), c.data(), P3{0, 0, 1}.data()), Sign::Zero);
  EXPECT_EQ(in_equatorial_sphere(a.data(), b.data(), c.data(), P3{0, 0, 0.5}.data()), Sign::Positive);
  EXPECT_EQ(in_equatorial_sphere(a.data(), b.data(), c.data(), P3{0, 0.8, 0.8}.data()), Sign::Negative);
  EXPECT_EQ(in_equatorial_sphere(a.data(), P3{2, 0, 0}.data(), P3{3, 0, 0}.data(), P3{0, 0, 0}.data()), Sign::Zero);
  int zeros = 0;
  std::uniform_int_distribution<int> coord(-3, 3);
  for (int i = 0; i < 8000; ++i) {
    P3 pa = random_point(), pb = random_point(), pc = random_point(), pp = random_point();
    if (i % 3 == 1) {  // near the sphere: a vertex moved by a few ulps
      for (int k = 0; k < 3; ++k) pp[k] = ulps(pb[k], static_cast<int>(uniform(-3, 4)));
    } else if (i % 3 == 2) {  // small integers: exact degeneracies
      for (auto* q : {&pa, &pb, &pc, &pp}) *q = {double(coord(rng)), double(coord(rng)), double(coord(rng))};
    }
    const Sign expected = exact_in_equatorial_sphere(pa, pb, pc, pp);
    zeros += expected == Sign::Zero;
    ASSERT_EQ(in_equatorial_sphere(pa.data(), pb.data(), pc.data(), pp.data()), expected) << i;
  }
  EXPECT_GT(zeros, 100);
}

/// Ranks by id: the largest id gets the largest perturbation delta^1, the next delta^2...
template <std::size_t N>
std::array<Q, N> sos_lifts(const std::array<std::uint32_t, N>& ids) {
  const Q delta = Q(1, 1) / (Q(mpz_class(1) << 120));
  std::array<Q, N> extra;
  for (std::size_t i = 0; i < N; ++i) {
    int rank = 1;  // 1 for the largest id
    for (std::size_t j = 0; j < N; ++j) rank += ids[j] > ids[i];
    Q p = 1;
    for (int r = 0; r < rank; ++r) p *= delta;
    extra[i] = p;
  }
  return extra;
}

TEST_F(PredicatesTest, SymbolicPerturbationMatchesExplicitTinyPerturbation) {
  // Cospherical/cocircular small-integer configurations: the explicit perturbation with
  // delta = 2^-120 is small enough to behave like the infinitesimal one.
  std::uniform_int_distribution<int> coord(-2, 2);
  std::uniform_int_distribution<std::uint32_t> idgen(0, 1000000);
  int degenerate3 = 0, degenerate2 = 0;
  for (int i = 0; i < 20000; ++i) {
    P3 p[5];
    for (auto& q : p) q = {double(coord(rng)), double(coord(rng)), double(coord(rng))};
    std::array<std::uint32_t, 5> ids;
    for (auto& id : ids) id = idgen(rng);
    if (std::set<std::uint32_t>(ids.begin(), ids.end()).size() < 5) continue;
    if (orient3d(p[0].data(), p[1].data(), p[2].data(), p[3].data()) != Sign::Zero) {
      const Sign got = insphere_sos(p[0].data(), p[1].data(), p[2].data(), p[3].data(), p[4].data(),
                                    ids[0], ids[1], ids[2], ids[3], ids[4]);
      ASSERT_NE(got, Sign::Zero);
      ASSERT_EQ(got, exact_insphere(p[0].data(), p[1].data(), p[2].data(), p[3].data(), p[4].data(),
                                    sos_lifts(ids)));
      degenerate3 += insphere(p[0].data(), p[1].data(), p[2].data(), p[3].data(), p[4].data()) == Sign::Zero;
    }
    if (orient2d(p[0].data(), p[1].data(), p[2].data()) != Sign::Zero) {
      const std::array<std::uint32_t, 4> ids4{ids[0], ids[1], ids[2], ids[3]};
      const Sign got = incircle_sos(p[0].data(), p[1].data(), p[2].data(), p[3].data(), ids[0], ids[1],
                                    ids[2], ids[3]);
      ASSERT_NE(got, Sign::Zero);
      ASSERT_EQ(got, exact_incircle(p[0].data(), p[1].data(), p[2].data(), p[3].data(), sos_lifts(ids4)));
      degenerate2 += incircle(p[0].data(), p[1].data(), p[2].data(), p[3].data()) == Sign::Zero;
    }
  }
  EXPECT_GT(degenerate3, 100);
  EXPECT_GT(degenerate2, 100);
}

TEST_F(PredicatesTest, PerturbedInsphereIsConsistentUnderPermutation) {
  // sign(insphere_sos) * orient3d(a,b,c,d) is a property of the point set, not of the
  // order in which the tetrahedron's vertices are listed.
  const double pts[6][3] = {{3, 0, 0}, {0, 3, 0}, {0, 0, 3}, {1, 2, 2}, {-2, 1, -2}, {2, -2, 1}};
  std::array<int, 4> tet{0, 1, 2, 3};
  for (int query = 4; query < 6; ++query) {
    std::optional<int> reference;
    std::array<int, 4> perm = tet;
    std::sort(perm.begin(), perm.end());
    do {
      const Sign o = orient3d(pts[perm[0]], pts[perm[1]], pts[perm[2]], pts[perm[3]]);
      const Sign s = insphere_sos(pts[perm[0]], pts[perm[1]], pts[perm[2]], pts[perm[3]], pts[query],
                                  perm[0], perm[1], perm[2], perm[3], query);
      const int value = to_int(s * o);
      if (!reference) reference = value;
      ASSERT_EQ(value, *reference);
      ASSERT_NE(value, 0);
    } while (std::next_permutation(perm.begin(), perm.end()));
  }
}

}  // namespace
}  // namespace delmesh::predicates
