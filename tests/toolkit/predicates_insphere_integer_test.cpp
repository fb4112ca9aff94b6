// The integer evaluation of insphere (toolkit/predicates/insphere_integer.h) against
// exact rational arithmetic (GMP), on the inputs it is made for: nearby points nearly on
// a sphere, exactly cospherical points, full 53-bit mantissas, and inputs that must fall
// back to the expansion path.
#include <gtest/gtest.h>
#include <gmpxx.h>

#include <array>
#include <cmath>
#include <random>

#include "toolkit/predicates/predicates.h"

namespace delmesh {
namespace {

using Q = mpq_class;
using P3 = std::array<double, 3>;

Sign sign_of(const Q& q) { return static_cast<Sign>(sgn(q)); }

Q det3(const Q m[3][3]) {
  return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
         m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
         m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
}

Q det4(const Q m[4][4]) {
  Q total = 0;
  for (int col = 0; col < 4; ++col) {
    Q minor[3][3];
    for (int r = 1; r < 4; ++r) {
      int k = 0;
      for (int c = 0; c < 4; ++c) {
        if (c != col) minor[r - 1][k++] = m[r][c];
      }
    }
    const Q term = m[0][col] * det3(minor);
    total += (col % 2 == 0) ? term : Q(-term);
  }
  return total;
}

// insphere with the convention of predicates.h, exactly.
Sign exact_insphere(const P3& a, const P3& b, const P3& c, const P3& d, const P3& e) {
  const P3* pts[4] = {&a, &b, &c, &d};
  Q m[4][4];
  for (int r = 0; r < 4; ++r) {
    const Q x = Q((*pts[r])[0]) - Q(e[0]), y = Q((*pts[r])[1]) - Q(e[1]), z = Q((*pts[r])[2]) - Q(e[2]);
    m[r][0] = x;
    m[r][1] = y;
    m[r][2] = z;
    m[r][3] = x * x + y * y + z * z;
  }
  return -sign_of(det4(m));
}

Sign fast(const P3& a, const P3& b, const P3& c, const P3& d, const P3& e) {
  return predicates::insphere(a.data(), b.data(), c.data(), d.data(), e.data());
}

TEST(InsphereInteger, PointsNearlyOnASphereMatchExactArithmetic) {
  std::mt19937_64 rng(99);
  std::normal_distribution<double> g;
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int zero = 0, nonzero = 0;
  for (int trial = 0; trial < 4000; ++trial) {
    // Five points within a small cap of the unit sphere (rounded to doubles): the
    // determinant is tiny and the filter cannot decide.
    P3 centre{g(rng), g(rng), g(rng)};
    const double n = std::sqrt(centre[0] * centre[0] + centre[1] * centre[1] + centre[2] * centre[2]);
    // Small caps: exact differences. The whole sphere: far-apart points, whose
    // differences are inexact but whose coordinates share one integer scale.
    const double cap = trial % 3 == 0 ? 1e-3 : trial % 3 == 1 ? 1e-1 : 10.0;
    std::array<P3, 5> p;
    for (auto& q : p) {
      P3 x{centre[0] / n + cap * u(rng), centre[1] / n + cap * u(rng), centre[2] / n + cap * u(rng)};
      const double r = std::sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
      q = {x[0] / r, x[1] / r, x[2] / r};
    }
    const Sign want = exact_insphere(p[0], p[1], p[2], p[3], p[4]);
    ASSERT_EQ(fast(p[0], p[1], p[2], p[3], p[4]), want) << "trial " << trial;
    (want == Sign::Zero ? zero : nonzero)++;
  }
  EXPECT_GT(nonzero, 3000);
}

TEST(InsphereInteger, CosphericalAndPerturbedGridPoints) {
  // Cube corners are cospherical; moving one by an ulp makes the sign definite.
  const std::array<P3, 8> cube{P3{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1},
                               {1, 1, 0}, {1, 0, 1}, {0, 1, 1}, {1, 1, 1}};
  for (int i = 0; i < 8; ++i) {
    P3 e = cube[7 - i];
    EXPECT_EQ(fast(cube[(i + 1) % 8], cube[(i + 2) % 8], cube[(i + 4) % 8], cube[i], e), Sign::Zero);
    for (int k = 0; k < 3; ++k) {
      for (const double dir : {-1.0, 1.0}) {
        P3 moved = e;
        moved[k] = std::nextafter(moved[k], dir * 2.0);
        const P3 &a = cube[(i + 1) % 8], &b = cube[(i + 2) % 8], &c = cube[(i + 4) % 8], &d = cube[i];
        ASSERT_EQ(fast(a, b, c, d, moved), exact_insphere(a, b, c, d, moved));
      }
    }
  }
}

TEST(InsphereInteger, FullMantissasAndMixedScalesMatchExactArithmetic) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> one_two(1.0, 2.0);
  std::uniform_int_distribution<int> ulps(-4, 4);
  for (int trial = 0; trial < 3000; ++trial) {
    std::array<P3, 5> p;
    // Points in [1, 2)^3 (all differences exact, full 53-bit mantissas), then a
    // cospherical configuration nudged by a few ulps, or points with tiny coordinates
    // beside large ones (the integer path must refuse those and the result still match).
    for (auto& q : p) q = {one_two(rng), one_two(rng), one_two(rng)};
    if (trial % 3 == 1) {
      p = {P3{1, 1, 1}, {1.5, 1, 1}, {1, 1.5, 1}, {1, 1, 1.5}, {1.5, 1.5, 1}};
      for (auto& q : p) {
        for (auto& x : q) {
          const int k = ulps(rng);
          for (int s = 0; s < std::abs(k); ++s) x = std::nextafter(x, k > 0 ? 4.0 : 0.0);
        }
      }
    } else if (trial % 3 == 2) {
      p[trial % 5][trial % 3] = 1e-30 * one_two(rng);
      p[(trial + 1) % 5][(trial + 1) % 3] = -1e-300 * one_two(rng);
    }
    ASSERT_EQ(fast(p[0], p[1], p[2], p[3], p[4]), exact_insphere(p[0], p[1], p[2], p[3], p[4]))
        << "trial " << trial;
  }
}

}  // namespace
}  // namespace delmesh
