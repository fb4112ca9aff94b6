// Dihedral measures of toolkit/quality used by sliver removal: the minimum dihedral sine
// and the dihedral window test.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "toolkit/predicates/predicates.h"
#include "toolkit/quality/tet_quality.h"

namespace delmesh {
namespace {

TEST(TetQualityDihedral, MinSineAndWindowTest) {
  const Vec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0), d(0, 0, 1);
  // Right-corner tet: dihedral angles 90 (three), and arccos(1/sqrt3) ~ 54.7 (three).
  EXPECT_NEAR(min_dihedral_sine(a, b, c, d), std::sin(std::acos(1.0 / std::sqrt(3.0))), 1e-12);
  EXPECT_FALSE(dihedral_outside(a, b, c, d, 50.0, 100.0));
  EXPECT_TRUE(dihedral_outside(a, b, c, d, 55.0, 180.0));
  EXPECT_TRUE(dihedral_outside(a, b, c, d, 0.0, 89.0));
  // A flat sliver: four points near a square, one lifted slightly.
  const Vec3 s0(0, 0, 0), s1(1, 0, 0), s2(1, 1, 0.01), s3(0, 1, 0);
  const Vec3& lo = predicates::orient3d(s0.data(), s1.data(), s2.data(), s3.data()) == Sign::Positive ? s2 : s3;
  const Vec3& hi = &lo == &s2 ? s3 : s2;
  EXPECT_LT(min_dihedral_sine(s0, s1, lo, hi), 0.05);
  EXPECT_LT(min_dihedral_sine(s0, s1, hi, lo), 0.0);  // inverted
  EXPECT_TRUE(dihedral_outside(s0, s1, lo, hi, 20.0, 150.0));
}

TEST(TetQualityDihedral, WindowTestAgreesWithTheAngles) {
  // dihedral_outside decides on squared cosines; it must agree with the angles themselves
  // on random tets (nearly flat ones included) for windows of every kind.
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double windows[][2] = {{20.0, 150.0}, {0.0, 120.0}, {35.0, 180.0}, {10.0, 80.0}, {15.0, 100.0}};
  int outside = 0, inside = 0;
  for (int i = 0; i < 20000; ++i) {
    const Vec3 a(u(rng), u(rng), u(rng)), b(u(rng), u(rng), u(rng)), c(u(rng), u(rng), u(rng));
    Vec3 d(u(rng), u(rng), u(rng));
    if (i % 4 == 0) d = (a + b + c) / 3.0 + 0.01 * Vec3(u(rng), u(rng), u(rng));  // near-flat
    const auto angles = dihedral_angles_deg(a, b, c, d);
    const double lo = *std::min_element(angles.begin(), angles.end());
    const double hi = *std::max_element(angles.begin(), angles.end());
    for (const auto& w : windows) {
      // Angles within 1e-9 degrees of a bound may round either way.
      bool borderline = false;
      for (const double x : angles) borderline |= std::abs(x - w[0]) < 1e-9 || std::abs(x - w[1]) < 1e-9;
      if (borderline) continue;
      const bool expected = (w[0] > 0.0 && lo < w[0]) || (w[1] < 180.0 && hi > w[1]);
      EXPECT_EQ(dihedral_outside(a, b, c, d, w[0], w[1]), expected) << "tet " << i << " window " << w[0];
      (expected ? outside : inside) += 1;
    }
  }
  EXPECT_GT(outside, 1000);
  EXPECT_GT(inside, 1000);
}

}  // namespace
}  // namespace delmesh
