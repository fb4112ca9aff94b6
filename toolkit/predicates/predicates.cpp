// Exact predicates: floating-point filter, then exact expansion evaluation; symbolic
// perturbation for Delaunay degeneracies. Conventions and method: predicates.h.
//
// Filter constants are Shewchuk's stage-A error bounds (1997, §4): with eps = 2^-53,
// a determinant computed in floating point from the rounded coordinate differences has
// absolute error at most errbound * permanent, where the permanent is the same
// expression with every term replaced by its absolute value. When |det| exceeds that
// bound its sign is certain; otherwise the determinant is recomputed exactly from the
// exact differences (Expansion::difference) with the same formula. The hot tests of 3D
// Delaunay insertion get cheaper intermediate stages before Shewchuk's adaptive ones:
// insphere tries the integer evaluation of insphere_integer.h (exact whenever the
// differences share one binary scale; measured faster first on near-cospherical input),
// then, like orient3d, a double-double evaluation with a proven error bound
// (double_double_filter.h).
#include "toolkit/predicates/predicates.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

#include "toolkit/core/error.h"
#include "toolkit/predicates/double_double_filter.h"
#include "toolkit/predicates/expansion.h"
#include "toolkit/predicates/insphere_integer.h"

namespace delmesh::predicates {

namespace {

using detail::Expansion;

constexpr double kEps = 0x1p-53;
constexpr double kCcwErrBoundA = (3.0 + 16.0 * kEps) * kEps;
constexpr double kO3dErrBoundA = (7.0 + 56.0 * kEps) * kEps;
constexpr double kIccErrBoundA = (10.0 + 96.0 * kEps) * kEps;
constexpr double kIspErrBoundA = (16.0 + 224.0 * kEps) * kEps;
constexpr double kCcwErrBoundB = (2.0 + 12.0 * kEps) * kEps;
constexpr double kCcwErrBoundC = (9.0 + 64.0 * kEps) * kEps * kEps;
constexpr double kO3dErrBoundB = (3.0 + 28.0 * kEps) * kEps;
constexpr double kO3dErrBoundC = (26.0 + 288.0 * kEps) * kEps * kEps;
constexpr double kIccErrBoundB = (4.0 + 48.0 * kEps) * kEps;
constexpr double kIccErrBoundC = (44.0 + 576.0 * kEps) * kEps * kEps;
constexpr double kIspErrBoundB = (5.0 + 72.0 * kEps) * kEps;
constexpr double kIspErrBoundC = (71.0 + 1408.0 * kEps) * kEps * kEps;
constexpr double kResultErrBound = (3.0 + 8.0 * kEps) * kEps;

Sign sign_of(const Expansion& e) { return static_cast<Sign>(e.sign()); }

/// Applies the filter: returns the certain sign of det, or Zero with `certain` false.
inline bool filter(double det, double errbound, Sign& out) {
  if (det > errbound) {
    out = Sign::Positive;
    return true;
  }
  if (-det > errbound) {
    out = Sign::Negative;
    return true;
  }
  return false;
}

/// Roundoff tail of the difference a - b (exact: a - b = fl(a - b) + tail).
inline double diff_tail(double a, double b) {
  double x, y;
  detail::two_diff(a, b, x, y);
  return y;
}

inline Sign sign_of_double(double v) {
  return v > 0.0 ? Sign::Positive : (v < 0.0 ? Sign::Negative : Sign::Zero);
}

/// True when every coordinate difference p[k] - apex[k] of the `count` points is exact
/// and all of them are integer multiples n 2^s of one power of two with |n| < 2^bits
/// (zero allowed; subnormals, infinities, NaN and extreme scales refused). Then a
/// polynomial of the differences whose every intermediate stays below 2^53 2^(degree s)
/// in magnitude is computed exactly in floating point (integer grids: the usual exactly
/// degenerate input).
bool differences_are_small_integers(const double* const* points, int count, const double* apex, int bits) {
  int top = std::numeric_limits<int>::min(), low = std::numeric_limits<int>::max();
  for (int i = 0; i < count; ++i) {
    for (int k = 0; k < 3; ++k) {
      double diff, tail;
      detail::two_diff(points[i][k], apex[k], diff, tail);
      if (tail != 0.0) return false;
      if (diff == 0.0) continue;
      std::uint64_t bits_of;
      std::memcpy(&bits_of, &diff, sizeof bits_of);
      const int biased = static_cast<int>((bits_of >> 52) & 0x7ff);
      if (biased == 0 || biased == 0x7ff) return false;
      const std::uint64_t mantissa = (bits_of & ((std::uint64_t{1} << 52) - 1)) | (std::uint64_t{1} << 52);
      top = std::max(top, biased - 1023);  // |diff| < 2^(top + 1)
      low = std::min(low, biased - 1075 + std::countr_zero(mantissa));  // 2^low divides diff
    }
  }
  if (top == std::numeric_limits<int>::min()) return true;
  // Degree at most 5: with 2^-200 <= 2^low and 2^(top + 1) <= 2^200, every nonzero
  // intermediate lies in [2^-1000, 2^1007]: no underflow, no overflow.
  return top + 1 - low <= bits && low >= -200 && top < 200;
}

// ---- orient2d: det[a-c, b-c] (= det[b-a, c-a]) --------------------------------------

Sign orient2d_exact(const double* a, const double* b, const double* c) {
  const Expansion acx = Expansion::difference(a[0], c[0]);
  const Expansion acy = Expansion::difference(a[1], c[1]);
  const Expansion bcx = Expansion::difference(b[0], c[0]);
  const Expansion bcy = Expansion::difference(b[1], c[1]);
  return sign_of(acx * bcy - acy * bcx);
}

// ---- orient3d: Shewchuk's det[a-d, b-d, c-d], negated by the caller -----------------

/// Shewchuk's orient2dadapt stages B and C (see insphere_shewchuk_adapt).
Sign orient2d_adapt(const double* a, const double* b, const double* c, double detsum) {
  using namespace detail;
  const double acx = a[0] - c[0], bcx = b[0] - c[0], acy = a[1] - c[1], bcy = b[1] - c[1];
  double B[4];
  const int n = two_two_diff(acx, bcy, acy, bcx, B);
  double det = estimate(n, B);
  Sign s;
  if (filter(det, kCcwErrBoundB * detsum, s)) return s;
  const double acxt = diff_tail(a[0], c[0]), bcxt = diff_tail(b[0], c[0]);
  const double acyt = diff_tail(a[1], c[1]), bcyt = diff_tail(b[1], c[1]);
  if (acxt == 0.0 && acyt == 0.0 && bcxt == 0.0 && bcyt == 0.0) return sign_of_double(det);
  const double errbound = kCcwErrBoundC * detsum + kResultErrBound * std::abs(det);
  det += (acx * bcyt + bcy * acxt) - (acy * bcxt + bcx * acyt);
  if (filter(det, errbound, s)) return s;
  return orient2d_exact(a, b, c);
}

Sign orient3d_shewchuk_exact(const double* a, const double* b, const double* c, const double* d) {
  const Expansion adx = Expansion::difference(a[0], d[0]);
  const Expansion ady = Expansion::difference(a[1], d[1]);
  const Expansion adz = Expansion::difference(a[2], d[2]);
  const Expansion bdx = Expansion::difference(b[0], d[0]);
  const Expansion bdy = Expansion::difference(b[1], d[1]);
  const Expansion bdz = Expansion::difference(b[2], d[2]);
  const Expansion cdx = Expansion::difference(c[0], d[0]);
  const Expansion cdy = Expansion::difference(c[1], d[1]);
  const Expansion cdz = Expansion::difference(c[2], d[2]);
  const Expansion det = adz * (bdx * cdy - cdx * bdy) + bdz * (cdx * ady - adx * cdy) +
                        cdz * (adx * bdy - bdx * ady);
  return sign_of(det);
}

/// Shewchuk's orient3dadapt stages B and C (see insphere_shewchuk_adapt).
Sign orient3d_shewchuk_adapt(const double* a, const double* b, const double* c, const double* d,
                             double permanent) {
  using namespace detail;
  const double adx = a[0] - d[0], bdx = b[0] - d[0], cdx = c[0] - d[0];
  const double ady = a[1] - d[1], bdy = b[1] - d[1], cdy = c[1] - d[1];
  const double adz = a[2] - d[2], bdz = b[2] - d[2], cdz = c[2] - d[2];
  double bc[4], ca[4], ab[4], adet[8], bdet[8], cdet[8], abdet[16], fin[24];
  const int bcn = two_two_diff(bdx, cdy, cdx, bdy, bc);
  const int can = two_two_diff(cdx, ady, adx, cdy, ca);
  const int abn = two_two_diff(adx, bdy, bdx, ady, ab);
  const int an = scale_into(bcn, bc, adz, adet);
  const int bn = scale_into(can, ca, bdz, bdet);
  const int cn = scale_into(abn, ab, cdz, cdet);
  const int abl = sum_into(an, adet, bn, bdet, abdet);
  const int finn = sum_into(abl, abdet, cn, cdet, fin);
  double det = estimate(finn, fin);
  Sign s;
  if (filter(det, kO3dErrBoundB * permanent, s)) return s;
  const double adxt = diff_tail(a[0], d[0]), bdxt = diff_tail(b[0], d[0]), cdxt = diff_tail(c[0], d[0]);
  const double adyt = diff_tail(a[1], d[1]), bdyt = diff_tail(b[1], d[1]), cdyt = diff_tail(c[1], d[1]);
  const double adzt = diff_tail(a[2], d[2]), bdzt = diff_tail(b[2], d[2]), cdzt = diff_tail(c[2], d[2]);
  if (adxt == 0.0 && bdxt == 0.0 && cdxt == 0.0 && adyt == 0.0 && bdyt == 0.0 && cdyt == 0.0 &&
      adzt == 0.0 && bdzt == 0.0 && cdzt == 0.0)
    return sign_of_double(det);
  const double errbound = kO3dErrBoundC * permanent + kResultErrBound * std::abs(det);
  det += (adz * ((bdx * cdyt + cdy * bdxt) - (bdy * cdxt + cdx * bdyt)) + adzt * (bdx * cdy - bdy * cdx)) +
         (bdz * ((cdx * adyt + ady * cdxt) - (cdy * adxt + adx * cdyt)) + bdzt * (cdx * ady - cdy * adx)) +
         (cdz * ((adx * bdyt + bdy * adxt) - (ady * bdxt + bdx * adyt)) + cdzt * (adx * bdy - ady * bdx));
  if (filter(det, errbound, s)) return s;
  return orient3d_shewchuk_exact(a, b, c, d);
}

Sign orient3d_shewchuk(const double* a, const double* b, const double* c, const double* d) {
  const double adx = a[0] - d[0], bdx = b[0] - d[0], cdx = c[0] - d[0];
  const double ady = a[1] - d[1], bdy = b[1] - d[1], cdy = c[1] - d[1];
  const double adz = a[2] - d[2], bdz = b[2] - d[2], cdz = c[2] - d[2];
  const double bdxcdy = bdx * cdy, cdxbdy = cdx * bdy;
  const double cdxady = cdx * ady, adxcdy = adx * cdy;
  const double adxbdy = adx * bdy, bdxady = bdx * ady;
  const double det = adz * (bdxcdy - cdxbdy) + bdz * (cdxady - adxcdy) + cdz * (adxbdy - bdxady);
  const double permanent = (std::abs(bdxcdy) + std::abs(cdxbdy)) * std::abs(adz) +
                           (std::abs(cdxady) + std::abs(adxcdy)) * std::abs(bdz) +
                           (std::abs(adxbdy) + std::abs(bdxady)) * std::abs(cdz);
  Sign s;
  if (filter(det, kO3dErrBoundA * permanent, s)) return s;
  // With differences n 2^s, |n| < 2^16: products < 2^32, minors < 2^33, the three terms
  // < 2^49 and their sum < 2^51 (times 2^3s): det was computed exactly.
  const double* const points[3] = {a, b, c};
  if (differences_are_small_integers(points, 3, d, 16)) return sign_of_double(det);
  Sign ours = Sign::Zero;
  if (detail::orient3d_double_double(a, b, c, d, ours)) return -ours;
  return orient3d_shewchuk_adapt(a, b, c, d, permanent);
}

// ---- incircle: Shewchuk's, positive when d is inside ccw abc ------------------------

Sign incircle_exact(const double* a, const double* b, const double* c, const double* d) {
  const Expansion adx = Expansion::difference(a[0], d[0]);
  const Expansion ady = Expansion::difference(a[1], d[1]);
  const Expansion bdx = Expansion::difference(b[0], d[0]);
  const Expansion bdy = Expansion::difference(b[1], d[1]);
  const Expansion cdx = Expansion::difference(c[0], d[0]);
  const Expansion cdy = Expansion::difference(c[1], d[1]);
  const Expansion alift = adx * adx + ady * ady;
  const Expansion blift = bdx * bdx + bdy * bdy;
  const Expansion clift = cdx * cdx + cdy * cdy;
  const Expansion det = alift * (bdx * cdy - cdx * bdy) + blift * (cdx * ady - adx * cdy) +
                        clift * (adx * bdy - bdx * ady);
  return sign_of(det);
}

/// Shewchuk's incircleadapt stages B and C (see insphere_shewchuk_adapt).
Sign incircle_adapt(const double* a, const double* b, const double* c, const double* d, double permanent) {
  using namespace detail;
  const double adx = a[0] - d[0], bdx = b[0] - d[0], cdx = c[0] - d[0];
  const double ady = a[1] - d[1], bdy = b[1] - d[1], cdy = c[1] - d[1];
  double bc[4], ca[4], ab[4];
  const int bcn = two_two_diff(bdx, cdy, cdx, bdy, bc);
  const int can = two_two_diff(cdx, ady, adx, cdy, ca);
  const int abn = two_two_diff(adx, bdy, bdx, ady, ab);
  // (x^2 + y^2) * minor, at most 32 terms
  auto lifted = [](int n, const double* m, double x, double y, double* out) {
    double t8[8], xx[16], yy[16];
    int l = scale_into(n, m, x, t8);
    const int lx = scale_into(l, t8, x, xx);
    l = scale_into(n, m, y, t8);
    const int ly = scale_into(l, t8, y, yy);
    return sum_into(lx, xx, ly, yy, out);
  };
  double adet[32], bdet[32], cdet[32], abdet[64], fin[96];
  const int an = lifted(bcn, bc, adx, ady, adet);
  const int bn = lifted(can, ca, bdx, bdy, bdet);
  const int cn = lifted(abn, ab, cdx, cdy, cdet);
  const int abl = sum_into(an, adet, bn, bdet, abdet);
  const int finn = sum_into(abl, abdet, cn, cdet, fin);
  double det = estimate(finn, fin);
  Sign s;
  if (filter(det, kIccErrBoundB * permanent, s)) return s;
  const double adxt = diff_tail(a[0], d[0]), bdxt = diff_tail(b[0], d[0]), cdxt = diff_tail(c[0], d[0]);
  const double adyt = diff_tail(a[1], d[1]), bdyt = diff_tail(b[1], d[1]), cdyt = diff_tail(c[1], d[1]);
  if (adxt == 0.0 && bdxt == 0.0 && cdxt == 0.0 && adyt == 0.0 && bdyt == 0.0 && cdyt == 0.0)
    return sign_of_double(det);
  const double errbound = kIccErrBoundC * permanent + kResultErrBound * std::abs(det);
  det += ((adx * adx + ady * ady) * ((bdx * cdyt + cdy * bdxt) - (bdy * cdxt + cdx * bdyt)) +
          2.0 * (adx * adxt + ady * adyt) * (bdx * cdy - bdy * cdx)) +
         ((bdx * bdx + bdy * bdy) * ((cdx * adyt + ady * cdxt) - (cdy * adxt + adx * cdyt)) +
          2.0 * (bdx * bdxt + bdy * bdyt) * (cdx * ady - cdy * adx)) +
         ((cdx * cdx + cdy * cdy) * ((adx * bdyt + bdy * adxt) - (ady * bdxt + bdx * adyt)) +
          2.0 * (cdx * cdxt + cdy * cdyt) * (adx * bdy - ady * bdx));
  if (filter(det, errbound, s)) return s;
  return incircle_exact(a, b, c, d);
}

// ---- insphere: Shewchuk's, positive when e is inside and Shewchuk-orient3d(abcd) > 0 --

Sign insphere_shewchuk_exact(const double* a, const double* b, const double* c, const double* d,
                             const double* e) {
  const Expansion aex = Expansion::difference(a[0], e[0]);
  const Expansion aey = Expansion::difference(a[1], e[1]);
  const Expansion aez = Expansion::difference(a[2], e[2]);
  const Expansion bex = Expansion::difference(b[0], e[0]);
  const Expansion bey = Expansion::difference(b[1], e[1]);
  const Expansion bez = Expansion::difference(b[2], e[2]);
  const Expansion cex = Expansion::difference(c[0], e[0]);
  const Expansion cey = Expansion::difference(c[1], e[1]);
  const Expansion cez = Expansion::difference(c[2], e[2]);
  const Expansion dex = Expansion::difference(d[0], e[0]);
  const Expansion dey = Expansion::difference(d[1], e[1]);
  const Expansion dez = Expansion::difference(d[2], e[2]);
  const Expansion ab = aex * bey - bex * aey;
  const Expansion bc = bex * cey - cex * bey;
  const Expansion cd = cex * dey - dex * cey;
  const Expansion da = dex * aey - aex * dey;
  const Expansion ac = aex * cey - cex * aey;
  const Expansion bd = bex * dey - dex * bey;
  const Expansion abc = aez * bc - bez * ac + cez * ab;
  const Expansion bcd = bez * cd - cez * bd + dez * bc;
  const Expansion cda = cez * da + dez * ac + aez * cd;
  const Expansion dab = dez * ab + aez * bd + bez * da;
  const Expansion alift = aex * aex + aey * aey + aez * aez;
  const Expansion blift = bex * bex + bey * bey + bez * bez;
  const Expansion clift = cex * cex + cey * cey + cez * cez;
  const Expansion dlift = dex * dex + dey * dey + dez * dez;
  const Expansion det = (dlift * abc - clift * dab) + (blift * cda - alift * bcd);
  return sign_of(det);
}

/// Shewchuk's adaptive stages B and C of insphere (1997, §4 and insphereadapt): stage B
/// evaluates the determinant exactly from the rounded differences, in fixed-size
/// expansions; stage C adds the first-order effect of the differences' roundoff tails in
/// floating point. Only when both are inconclusive is the full exact evaluation run.
Sign insphere_shewchuk_adapt(const double* pa, const double* pb, const double* pc, const double* pd,
                             const double* pe, double permanent) {
  using namespace detail;
  const double aex = pa[0] - pe[0], bex = pb[0] - pe[0], cex = pc[0] - pe[0], dex = pd[0] - pe[0];
  const double aey = pa[1] - pe[1], bey = pb[1] - pe[1], cey = pc[1] - pe[1], dey = pd[1] - pe[1];
  const double aez = pa[2] - pe[2], bez = pb[2] - pe[2], cez = pc[2] - pe[2], dez = pd[2] - pe[2];

  double ab[4], bc[4], cd[4], da[4], ac[4], bd[4];
  const int abn = two_two_diff(aex, bey, bex, aey, ab);
  const int bcn = two_two_diff(bex, cey, cex, bey, bc);
  const int cdn = two_two_diff(cex, dey, dex, cey, cd);
  const int dan = two_two_diff(dex, aey, aex, dey, da);
  const int acn = two_two_diff(aex, cey, cex, aey, ac);
  const int bdn = two_two_diff(bex, dey, dex, bey, bd);

  // det = (dlift * abc - clift * dab) + (blift * cda - alift * bcd), each 3x3 minor a
  // combination of the 2x2 minors scaled by z differences.
  auto minor3 = [](int n1, const double* m1, double z1, int n2, const double* m2, double z2, int n3,
                   const double* m3, double z3, double* out) {
    double t1[8], t2[8], t3[8], t12[16];
    const int l1 = scale_into(n1, m1, z1, t1);
    const int l2 = scale_into(n2, m2, z2, t2);
    const int l3 = scale_into(n3, m3, z3, t3);
    const int l12 = sum_into(l1, t1, l2, t2, t12);
    return sum_into(l12, t12, l3, t3, out);
  };
  // lifted term: sign * (x^2 + y^2 + z^2) * minor, at most 3 * 2 * 2 * 24 = 288 terms
  auto lifted = [](int n, const double* m, double x, double y, double z, double sign, double* out) {
    double t48[48], xx[96], yy[96], zz[96], xy[192];
    int l = scale_into(n, m, x, t48);
    const int lx = scale_into(l, t48, sign * x, xx);
    l = scale_into(n, m, y, t48);
    const int ly = scale_into(l, t48, sign * y, yy);
    l = scale_into(n, m, z, t48);
    const int lz = scale_into(l, t48, sign * z, zz);
    const int lxy = sum_into(lx, xx, ly, yy, xy);
    return sum_into(lxy, xy, lz, zz, out);
  };
  double bcd[24], cda[24], dab[24], abc[24];
  const int bcdn = minor3(cdn, cd, bez, bdn, bd, -cez, bcn, bc, dez, bcd);
  const int cdan = minor3(dan, da, cez, acn, ac, dez, cdn, cd, aez, cda);
  const int dabn = minor3(abn, ab, dez, bdn, bd, aez, dan, da, bez, dab);
  const int abcn = minor3(bcn, bc, aez, acn, ac, -bez, abn, ab, cez, abc);
  double adet[288], bdet[288], cdet[288], ddet[288], abdet[576], cddet[576], fin[1152];
  const int an = lifted(bcdn, bcd, aex, aey, aez, -1.0, adet);
  const int bn = lifted(cdan, cda, bex, bey, bez, 1.0, bdet);
  const int cn = lifted(dabn, dab, cex, cey, cez, -1.0, cdet);
  const int dn = lifted(abcn, abc, dex, dey, dez, 1.0, ddet);
  const int abl = sum_into(an, adet, bn, bdet, abdet);
  const int cdl = sum_into(cn, cdet, dn, ddet, cddet);
  const int finn = sum_into(abl, abdet, cdl, cddet, fin);
  double det = estimate(finn, fin);
  Sign s;
  if (filter(det, kIspErrBoundB * permanent, s)) return s;

  double aext, bext, cext, dext, aeyt, beyt, ceyt, deyt, aezt, bezt, cezt, dezt, unused;
  two_diff(pa[0], pe[0], unused, aext);
  two_diff(pa[1], pe[1], unused, aeyt);
  two_diff(pa[2], pe[2], unused, aezt);
  two_diff(pb[0], pe[0], unused, bext);
  two_diff(pb[1], pe[1], unused, beyt);
  two_diff(pb[2], pe[2], unused, bezt);
  two_diff(pc[0], pe[0], unused, cext);
  two_diff(pc[1], pe[1], unused, ceyt);
  two_diff(pc[2], pe[2], unused, cezt);
  two_diff(pd[0], pe[0], unused, dext);
  two_diff(pd[1], pe[1], unused, deyt);
  two_diff(pd[2], pe[2], unused, dezt);
  if (aext == 0.0 && aeyt == 0.0 && aezt == 0.0 && bext == 0.0 && beyt == 0.0 && bezt == 0.0 &&
      cext == 0.0 && ceyt == 0.0 && cezt == 0.0 && dext == 0.0 && deyt == 0.0 && dezt == 0.0) {
    return sign_of_double(det);  // stage B was exact
  }

  const double errbound = kIspErrBoundC * permanent + kResultErrBound * std::abs(det);
  const double ab3 = ab[abn - 1], bc3 = bc[bcn - 1], cd3 = cd[cdn - 1];
  const double da3 = da[dan - 1], ac3 = ac[acn - 1], bd3 = bd[bdn - 1];
  const double abeps = (aex * beyt + bey * aext) - (aey * bext + bex * aeyt);
  const double bceps = (bex * ceyt + cey * bext) - (bey * cext + cex * beyt);
  const double cdeps = (cex * deyt + dey * cext) - (cey * dext + dex * ceyt);
  const double daeps = (dex * aeyt + aey * dext) - (dey * aext + aex * deyt);
  const double aceps = (aex * ceyt + cey * aext) - (aey * cext + cex * aeyt);
  const double bdeps = (bex * deyt + dey * bext) - (bey * dext + dex * beyt);
  det += (((bex * bex + bey * bey + bez * bez) * ((cez * daeps + dez * aceps + aez * cdeps) +
                                                  (cezt * da3 + dezt * ac3 + aezt * cd3)) +
           (dex * dex + dey * dey + dez * dez) * ((aez * bceps - bez * aceps + cez * abeps) +
                                                  (aezt * bc3 - bezt * ac3 + cezt * ab3))) -
          ((aex * aex + aey * aey + aez * aez) * ((bez * cdeps - cez * bdeps + dez * bceps) +
                                                  (bezt * cd3 - cezt * bd3 + dezt * bc3)) +
           (cex * cex + cey * cey + cez * cez) * ((dez * abeps + aez * bdeps + bez * daeps) +
                                                  (dezt * ab3 + aezt * bd3 + bezt * da3)))) +
         2.0 * (((bex * bext + bey * beyt + bez * bezt) * (cez * da3 + dez * ac3 + aez * cd3) +
                 (dex * dext + dey * deyt + dez * dezt) * (aez * bc3 - bez * ac3 + cez * ab3)) -
                ((aex * aext + aey * aeyt + aez * aezt) * (bez * cd3 - cez * bd3 + dez * bc3) +
                 (cex * cext + cey * ceyt + cez * cezt) * (dez * ab3 + aez * bd3 + bez * da3)));
  if (filter(det, errbound, s)) return s;
  return insphere_shewchuk_exact(pa, pb, pc, pd, pe);
}

Sign insphere_shewchuk(const double* a, const double* b, const double* c, const double* d,
                       const double* e) {
  const double aex = a[0] - e[0], bex = b[0] - e[0], cex = c[0] - e[0], dex = d[0] - e[0];
  const double aey = a[1] - e[1], bey = b[1] - e[1], cey = c[1] - e[1], dey = d[1] - e[1];
  const double aez = a[2] - e[2], bez = b[2] - e[2], cez = c[2] - e[2], dez = d[2] - e[2];

  const double aexbey = aex * bey, bexaey = bex * aey;
  const double bexcey = bex * cey, cexbey = cex * bey;
  const double cexdey = cex * dey, dexcey = dex * cey;
  const double dexaey = dex * aey, aexdey = aex * dey;
  const double aexcey = aex * cey, cexaey = cex * aey;
  const double bexdey = bex * dey, dexbey = dex * bey;
  const double ab = aexbey - bexaey, bc = bexcey - cexbey, cd = cexdey - dexcey;
  const double da = dexaey - aexdey, ac = aexcey - cexaey, bd = bexdey - dexbey;

  const double abc = aez * bc - bez * ac + cez * ab;
  const double bcd = bez * cd - cez * bd + dez * bc;
  const double cda = cez * da + dez * ac + aez * cd;
  const double dab = dez * ab + aez * bd + bez * da;

  const double alift = aex * aex + aey * aey + aez * aez;
  const double blift = bex * bex + bey * bey + bez * bez;
  const double clift = cex * cex + cey * cey + cez * cez;
  const double dlift = dex * dex + dey * dey + dez * dez;

  const double det = (dlift * abc - clift * dab) + (blift * cda - alift * bcd);

  const double aezp = std::abs(aez), bezp = std::abs(bez), cezp = std::abs(cez), dezp = std::abs(dez);
  const double aexbeyp = std::abs(aexbey), bexaeyp = std::abs(bexaey);
  const double bexceyp = std::abs(bexcey), cexbeyp = std::abs(cexbey);
  const double cexdeyp = std::abs(cexdey), dexceyp = std::abs(dexcey);
  const double dexaeyp = std::abs(dexaey), aexdeyp = std::abs(aexdey);
  const double aexceyp = std::abs(aexcey), cexaeyp = std::abs(cexaey);
  const double bexdeyp = std::abs(bexdey), dexbeyp = std::abs(dexbey);
  const double permanent =
      ((cexdeyp + dexceyp) * bezp + (dexbeyp + bexdeyp) * cezp + (bexceyp + cexbeyp) * dezp) * alift +
      ((dexaeyp + aexdeyp) * cezp + (aexceyp + cexaeyp) * dezp + (cexdeyp + dexceyp) * aezp) * blift +
      ((aexbeyp + bexaeyp) * dezp + (bexdeyp + dexbeyp) * aezp + (dexaeyp + aexdeyp) * bezp) * clift +
      ((bexceyp + cexbeyp) * aezp + (cexaeyp + aexceyp) * bezp + (aexbeyp + bexaeyp) * cezp) * dlift;
  Sign s;
  if (filter(det, kIspErrBoundA * permanent, s)) return s;
  // With differences n 2^s, |n| < 2^9: 2x2 minors < 2^19, 3x3 minors < 2^30, lifts
  // < 2^20, their products < 2^50 and the final sums < 2^52 (times 2^5s): det was
  // computed exactly.
  const double* const points[4] = {a, b, c, d};
  if (differences_are_small_integers(points, 4, e, 9)) return sign_of_double(det);
  // Exact in integers whenever the differences share one binary scale (nearly always in
  // Delaunay insertion, exact zeros included): before the expansion stages.
  int exact = 0;
  if (detail::insphere_integer(a, b, c, d, e, exact)) return static_cast<Sign>(exact);
  // Double-double evaluation with a proven error bound: decides nearly every
  // near-cospherical case whose determinant is not exactly zero.
  Sign ours = Sign::Zero;
  if (detail::insphere_double_double(a, b, c, d, e, ours)) return -ours;
  return insphere_shewchuk_adapt(a, b, c, d, e, permanent);
}

Sign dot_exact(const double* a, const double* b, const double* c, int dim) {
  Expansion sum;
  for (int i = 0; i < dim; ++i) {
    sum = sum + Expansion::difference(a[i], c[i]) * Expansion::difference(b[i], c[i]);
  }
  return sign_of(sum);
}

}  // namespace

Sign orient2d(const double* a, const double* b, const double* c) {
  const double detleft = (a[0] - c[0]) * (b[1] - c[1]);
  const double detright = (a[1] - c[1]) * (b[0] - c[0]);
  const double det = detleft - detright;
  Sign s;
  const double detsum = std::abs(detleft) + std::abs(detright);
  if (filter(det, kCcwErrBoundA * detsum, s)) return s;
  return orient2d_adapt(a, b, c, detsum);
}

Sign orient3d(const double* a, const double* b, const double* c, const double* d) {
  return -orient3d_shewchuk(a, b, c, d);
}

Sign incircle(const double* a, const double* b, const double* c, const double* d) {
  const double adx = a[0] - d[0], bdx = b[0] - d[0], cdx = c[0] - d[0];
  const double ady = a[1] - d[1], bdy = b[1] - d[1], cdy = c[1] - d[1];
  const double bdxcdy = bdx * cdy, cdxbdy = cdx * bdy;
  const double alift = adx * adx + ady * ady;
  const double cdxady = cdx * ady, adxcdy = adx * cdy;
  const double blift = bdx * bdx + bdy * bdy;
  const double adxbdy = adx * bdy, bdxady = bdx * ady;
  const double clift = cdx * cdx + cdy * cdy;
  const double det = alift * (bdxcdy - cdxbdy) + blift * (cdxady - adxcdy) + clift * (adxbdy - bdxady);
  const double permanent = (std::abs(bdxcdy) + std::abs(cdxbdy)) * alift +
                           (std::abs(cdxady) + std::abs(adxcdy)) * blift +
                           (std::abs(adxbdy) + std::abs(bdxady)) * clift;
  Sign s;
  if (filter(det, kIccErrBoundA * permanent, s)) return s;
  return incircle_adapt(a, b, c, d, permanent);
}

Sign insphere(const double* a, const double* b, const double* c, const double* d, const double* e) {
  // Shewchuk's insphere is positive for e inside when his orient3d(a,b,c,d) > 0, i.e. when
  // ours is negative: negate to obtain our convention.
  return -insphere_shewchuk(a, b, c, d, e);
}

Sign orient2d_projected(const double* a, const double* b, const double* c, Axis axis) {
  const auto pa = project_onto_axis_plane(a, axis), pb = project_onto_axis_plane(b, axis),
             pc = project_onto_axis_plane(c, axis);
  return orient2d(pa.data(), pb.data(), pc.data());
}

Sign incircle_coplanar(const double* a, const double* b, const double* c, const double* d,
                       Axis axis) {
  const Sign orientation = orient2d_projected(a, b, c, axis);
  if (orientation == Sign::Zero) return Sign::Zero;
  // Any point e off the common plane: the sphere through a, b, c, e meets the plane in
  // the circle through a, b, c, so for coplanar d, "inside the sphere" is "inside the
  // circle". Moving a along the plane's dominant normal axis leaves the plane exactly.
  const int k = static_cast<int>(axis);
  double e[3] = {a[0], a[1], a[2]};
  e[k] = a[k] + std::max(1.0, std::abs(a[k]));
  const Sign side = orient3d(a, b, c, e);
  DELMESH_CHECK(side != Sign::Zero, "incircle_coplanar: lifted point stayed in the plane");
  return insphere(a, b, c, e, d) * side * orientation;
}

Sign incircle_in_plane(const double* a, const double* b, const double* c, const double* d,
                       Axis axis, const double* normal) {
  const auto pa = project_onto_axis_plane(a, axis), pb = project_onto_axis_plane(b, axis),
             pc = project_onto_axis_plane(c, axis), pd = project_onto_axis_plane(d, axis);
  const int k = static_cast<int>(axis);
  // (i, j) as in project_onto_axis_plane(): X -> (y, z), Y -> (z, x), Z -> (x, y)
  const int i = (k + 1) % 3, j = (k + 2) % 3;
  const double ni = normal[i], nj = normal[j], nk = normal[k];
  // Filter: translate to d, evaluate in floating point with a generous error bound.
  const double adx = pa[0] - pd[0], ady = pa[1] - pd[1];
  const double bdx = pb[0] - pd[0], bdy = pb[1] - pd[1];
  const double cdx = pc[0] - pd[0], cdy = pc[1] - pd[1];
  const double nk2 = nk * nk;
  auto lift = [&](double x, double y) {
    const double s = ni * x + nj * y;
    return nk2 * (x * x + y * y) + s * s;
  };
  auto lift_bound = [&](double x, double y) {
    const double s = std::abs(ni * x) + std::abs(nj * y);
    return nk2 * (x * x + y * y) + s * s;
  };
  const double alift = lift(adx, ady), blift = lift(bdx, bdy), clift = lift(cdx, cdy);
  const double m1 = bdx * cdy - cdx * bdy, m2 = cdx * ady - adx * cdy, m3 = adx * bdy - bdx * ady;
  const double det = alift * m1 + blift * m2 + clift * m3;
  const double permanent = lift_bound(adx, ady) * (std::abs(bdx * cdy) + std::abs(cdx * bdy)) +
                           lift_bound(bdx, bdy) * (std::abs(cdx * ady) + std::abs(adx * cdy)) +
                           lift_bound(cdx, cdy) * (std::abs(adx * bdy) + std::abs(bdx * ady));
  // Each lift carries at most ~8 roundings and each minor ~3, all relative to the
  // permanent's terms; 32 eps covers them with a wide margin.
  Sign s;
  if (filter(det, 32.0 * kEps * permanent, s)) return s;
  // Exact: the lift of a difference vector (x, y) is a polynomial in exact expansions.
  const Expansion eni(ni), enj(nj), enk2 = Expansion(nk) * Expansion(nk);
  auto exact_lift = [&](const Expansion& x, const Expansion& y) {
    const Expansion t = eni * x + enj * y;
    return enk2 * (x * x + y * y) + t * t;
  };
  const Expansion ax = Expansion::difference(pa[0], pd[0]), ay = Expansion::difference(pa[1], pd[1]);
  const Expansion bx = Expansion::difference(pb[0], pd[0]), by = Expansion::difference(pb[1], pd[1]);
  const Expansion cx = Expansion::difference(pc[0], pd[0]), cy = Expansion::difference(pc[1], pd[1]);
  const Expansion exact = exact_lift(ax, ay) * (bx * cy - cx * by) + exact_lift(bx, by) * (cx * ay - ax * cy) +
                          exact_lift(cx, cy) * (ax * by - bx * ay);
  return sign_of(exact);
}

Sign incircle_sos(const double* a, const double* b, const double* c, const double* d,
                  std::uint32_t ia, std::uint32_t ib, std::uint32_t ic, std::uint32_t id) {
  const Sign exact = incircle(a, b, c, d);
  if (exact != Sign::Zero) return exact;
  // Perturb the lifted coordinate |p|^2 of every point by an infinitesimal whose size
  // decreases with the point's rank: the larger the id, the larger the perturbation, and
  // each dominates all smaller ones. The sign is then that of the first nonzero
  // coefficient, taken in decreasing id order. The coefficient of d's lift is
  // -orient2d(a,b,c) (lifting d moves it outside); swapping rows gives the others.
  const std::uint32_t ids[4] = {ia, ib, ic, id};
  int order[4] = {0, 1, 2, 3};
  std::sort(order, order + 4, [&](int x, int y) { return ids[x] > ids[y]; });
  for (int which : order) {
    Sign s = Sign::Zero;
    switch (which) {
      case 3: s = -orient2d(a, b, c); break;
      case 2: s = orient2d(a, b, d); break;
      case 1: s = orient2d(a, d, c); break;
      case 0: s = orient2d(d, b, c); break;
    }
    if (s != Sign::Zero) return s;
  }
  return Sign::Zero;  // only when all four points are collinear
}

Sign insphere_sos(const double* a, const double* b, const double* c, const double* d,
                  const double* e, std::uint32_t ia, std::uint32_t ib, std::uint32_t ic,
                  std::uint32_t id, std::uint32_t ie) {
  const Sign exact = insphere(a, b, c, d, e);
  if (exact != Sign::Zero) return exact;
  // Same scheme as incircle_sos, one dimension up (Devillers and Teillaud 2011): the
  // coefficient of e's lift is -orient3d(a,b,c,d); those of d, c, b, a are the
  // orientations with that point replaced by e.
  const std::uint32_t ids[5] = {ia, ib, ic, id, ie};
  int order[5] = {0, 1, 2, 3, 4};
  std::sort(order, order + 5, [&](int x, int y) { return ids[x] > ids[y]; });
  for (int which : order) {
    Sign s = Sign::Zero;
    switch (which) {
      case 4: s = -orient3d(a, b, c, d); break;
      case 3: s = orient3d(a, b, c, e); break;
      case 2: s = orient3d(a, b, e, d); break;
      case 1: s = orient3d(a, e, c, d); break;
      case 0: s = orient3d(e, b, c, d); break;
    }
    if (s != Sign::Zero) return s;
  }
  return Sign::Zero;  // only when all five points are coplanar
}

namespace {

/// A floating-point value with a bound on the magnitudes it was computed from: for an
/// expression tree of depth k, |computed - exact| <= (k + 1) eps * magnitude.
struct Bounded {
  double value;
  double magnitude;
};
Bounded operator+(Bounded x, Bounded y) { return {x.value + y.value, x.magnitude + y.magnitude}; }
Bounded operator-(Bounded x, Bounded y) { return {x.value - y.value, x.magnitude + y.magnitude}; }
Bounded operator*(Bounded x, Bounded y) { return {x.value * y.value, x.magnitude * y.magnitude}; }

template <class T>
struct Triple {
  T x, y, z;
};
template <class T>
Triple<T> cross(const Triple<T>& a, const Triple<T>& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
template <class T>
T dot(const Triple<T>& a, const Triple<T>& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
template <class T>
Triple<T> scaled(const T& s, const Triple<T>& a) {
  return {s * a.x, s * a.y, s * a.z};
}
template <class T>
Triple<T> minus(const Triple<T>& a, const Triple<T>& b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}

/// D |w|^2 - 2 w . N with u = b - a, v = c - a, w = p - a, D = 2 |u x v|^2 and
/// N = (|u|^2 v - |v|^2 u) x (u x v): the power of p with respect to the equatorial
/// sphere times D > 0 (its center is a + N / D).
template <class T>
T equatorial_power(const Triple<T>& u, const Triple<T>& v, const Triple<T>& w) {
  const Triple<T> n = cross(u, v);
  const T uu = dot(u, u), vv = dot(v, v), ww = dot(w, w);
  const Triple<T> big = cross(minus(scaled(uu, v), scaled(vv, u)), n);
  const T nn = dot(n, n);
  const T wn = dot(w, big);
  return (nn + nn) * ww - (wn + wn);
}

}  // namespace

Sign in_equatorial_sphere(const double* a, const double* b, const double* c, const double* p) {
  auto diff = [](double x, double y) { return Bounded{x - y, std::abs(x - y)}; };
  const Triple<Bounded> u{diff(b[0], a[0]), diff(b[1], a[1]), diff(b[2], a[2])};
  const Triple<Bounded> v{diff(c[0], a[0]), diff(c[1], a[1]), diff(c[2], a[2])};
  const Triple<Bounded> w{diff(p[0], a[0]), diff(p[1], a[1]), diff(p[2], a[2])};
  const Bounded power = equatorial_power(u, v, w);
  // The expression tree has depth 17 (differences, squares, sums, two cross products,
  // a dot product); 32 eps bounds its relative error against the magnitude.
  Sign s;
  if (filter(power.value, 32.0 * kEps * power.magnitude, s)) return -s;
  auto ediff = [](double x, double y) { return Expansion::difference(x, y); };
  const Triple<Expansion> eu{ediff(b[0], a[0]), ediff(b[1], a[1]), ediff(b[2], a[2])};
  const Triple<Expansion> ev{ediff(c[0], a[0]), ediff(c[1], a[1]), ediff(c[2], a[2])};
  const Triple<Expansion> ew{ediff(p[0], a[0]), ediff(p[1], a[1]), ediff(p[2], a[2])};
  return -sign_of(equatorial_power(eu, ev, ew));
}

Sign dot2d(const double* a, const double* b, const double* c) {
  const double p0 = (a[0] - c[0]) * (b[0] - c[0]);
  const double p1 = (a[1] - c[1]) * (b[1] - c[1]);
  Sign s;
  if (filter(p0 + p1, kCcwErrBoundA * (std::abs(p0) + std::abs(p1)), s)) return s;
  return dot_exact(a, b, c, 2);
}

Sign dot3d(const double* a, const double* b, const double* c) {
  const double p0 = (a[0] - c[0]) * (b[0] - c[0]);
  const double p1 = (a[1] - c[1]) * (b[1] - c[1]);
  const double p2 = (a[2] - c[2]) * (b[2] - c[2]);
  Sign s;
  if (filter(p0 + p1 + p2, kO3dErrBoundA * (std::abs(p0) + std::abs(p1) + std::abs(p2)), s)) return s;
  return dot_exact(a, b, c, 3);
}

}  // namespace delmesh::predicates
