// Dihedral measures of toolkit/quality used by sliver removal: the minimum dihedral sine
// and the dihedral window test.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>
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

TEST(TetQualityDihedral, WindowSinesBalanceTheTwoEndsOfTheWindow) {
  // For the window [20, 150] an angle of 150 degrees must score as an angle of 20: the
  // plain sine ranks it with 30 degrees.
  const double scale = window_obtuse_scale(20.0, 150.0);
  EXPECT_NEAR(scale, std::sin(20.0 * std::numbers::pi / 180.0) / 0.5, 1e-15);
  EXPECT_EQ(window_obtuse_scale(10.0, 180.0), 1.0);
  EXPECT_EQ(window_obtuse_scale(0.0, 150.0), 1.0);
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int obtuse_worst = 0;
  for (int i = 0; i < 5000; ++i) {
    Vec3 a(u(rng), u(rng), u(rng)), b(u(rng), u(rng), u(rng)), c(u(rng), u(rng), u(rng)), d(u(rng), u(rng), u(rng));
    if (predicates::orient3d(a.data(), b.data(), c.data(), d.data()) != Sign::Positive) std::swap(c, d);
    const auto angles = dihedral_angles_deg(a, b, c, d);
    const auto sines = window_dihedral_sines(a, b, c, d, scale);
    double lowest = 2.0;
    for (int e = 0; e < 6; ++e) {
      const double radians = angles[e] * std::numbers::pi / 180.0;
      const double expected = std::sin(radians) * (angles[e] > 90.0 ? scale : 1.0);
      EXPECT_NEAR(sines[e], expected, 1e-9) << "tet " << i << " edge " << e;
      lowest = std::min(lowest, expected);
    }
    EXPECT_NEAR(min_window_dihedral_sine(a, b, c, d, scale), lowest, 1e-9);
    // Below sin(20) exactly when an angle leaves [20, 150] (away from the ends).
    const double lo = *std::min_element(angles.begin(), angles.end());
    const double hi = *std::max_element(angles.begin(), angles.end());
    if (std::abs(lo - 20.0) > 1e-6 && std::abs(hi - 150.0) > 1e-6) {
      EXPECT_EQ(lowest < std::sin(20.0 * std::numbers::pi / 180.0), lo < 20.0 || hi > 150.0) << "tet " << i;
    }
    obtuse_worst += hi > 150.0 && lo > 20.0;
    // Scale 1: the minimum dihedral sine, bit for bit.
    EXPECT_EQ(min_window_dihedral_sine(a, b, c, d, 1.0), min_dihedral_sine(a, b, c, d));
  }
  EXPECT_GT(obtuse_worst, 10);  // tets whose only fault is a large angle were met
  // Inverted: negative, as the minimum sine.
  const Vec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0), d(0, 0, 1);
  EXPECT_LT(min_window_dihedral_sine(a, b, d, c, scale), 0.0);
}

}  // namespace
}  // namespace delmesh
