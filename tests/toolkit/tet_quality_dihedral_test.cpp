// Dihedral measures of toolkit/quality used by sliver removal: the minimum dihedral sine
// and the dihedral window test.
#include <gtest/gtest.h>

#include <cmath>

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

}  // namespace
}  // namespace delmesh
