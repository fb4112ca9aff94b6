// Double-double arithmetic with a tracked magnitude, for the intermediate filter stage of
// the predicates (toolkit/predicates/double_double_filter.cpp).
//
// A DoubleDouble is an unevaluated sum hi + lo of two doubles with |lo| <= u |hi|
// (u = 2^-53), i.e. about 106 bits. The operations are the classical ones (Dekker 1971;
// Joldes, Muller and Popescu, "Tight and rigorous error bounds for basic building blocks
// of double-word arithmetic", ACM TOMS 2017: AccurateDWPlusDW and DWTimesDW1), written
// with Two-Sum everywhere instead of Fast-Two-Sum so that each renormalisation is exact
// without any precondition on the operands. The bounds below are derived here for exactly
// these operation sequences, against the *magnitudes* of the operands (not the result),
// which is what a forward error bound of a polynomial needs.
//
// Addition z = x + y (x = xh + xl, y = yh + yl):
//   (sh, sl) = TwoSum(xh, yh); (th, tl) = TwoSum(xl, yl); c = fl(sl + th);
//   (vh, vl) = TwoSum(sh, c);  w = fl(tl + vl);           (zh, zl) = TwoSum(vh, w).
//   All TwoSums are exact, so zh + zl = x + y + e1 + e2 with e1, e2 the roundings of c
//   and w: |e1| <= u |sl + th| <= 2u^2 (|xh| + |yh|)(1 + u)^2 and
//   |e2| <= u |tl + vl| <= u^2 (|xh| + |yh|)(1 + 4u). Hence
//       |z_computed - (x + y)| <= 3 u^2 (|xh| + |yh|) (1 + 3u).
// Multiplication z = x * y:
//   (ch, cl1) = TwoProduct(xh, yh) (Dekker's split, exact); t1 = fl(xh yl);
//   t2 = fl(xl yh); cl2 = fl(t1 + t2); cl3 = fl(cl1 + cl2); (zh, zl) = TwoSum(ch, cl3).
//   Errors, each relative to |xh yh|: the dropped xl yl <= u^2; t1, t2 <= 2u^2 together;
//   cl2 <= u |t1 + t2| <= 2u^2 (1 + u); cl3 <= u (|cl1| + |cl2|) <= 3u^2 (1 + u)^2. Hence
//       |z_computed - x y| <= 8 u^2 |xh| |yh| (1 + 2u).
//   A square uses one split and t = fl(2 xh xl); its bound (6 u^2) is within the same 8u^2.
//   Leaves (the exact differences) are split once for all their products; the results
//   are bit-identical to splitting at every product.
// Both results are normalised (|zl| <= u |zh|) by the final TwoSum.
//
// Propagation: every Tracked value carries the computed value x^ and a magnitude m (a
// double computed alongside from |hi| of the leaves with the same expression, all terms
// positive). If |x^ - x| <= kx u^2 m_x and |y^ - y| <= ky u^2 m_y, with |x| <= m_x,
// then, to first order in u,
//   sum:     |z^ - z| <= (max(kx, ky) + 3) u^2 (m_x + m_y),
//   product: |z^ - z| <= (kx + ky + 8) u^2 m_x m_y.
// Leaves are exact (TwoDiff), k = 0. The constant of a whole expression is obtained by
// walking its tree with these two rules; see double_double_filter.cpp for the predicates.
//
// Requires IEEE double, round-to-nearest-even, no FMA contraction (include only from
// toolkit/predicates/*.cpp, compiled with -ffp-contract=off). Exactness of TwoProduct and
// so the bounds assume no underflow, the same caveat as the other stages (predicates.h).
#pragma once

#include <cmath>

#include "toolkit/predicates/expansion.h"

namespace delmesh::predicates::detail {

struct DoubleDouble {
  double hi;
  double lo;
};

inline DoubleDouble dd_difference(double a, double b) {
  DoubleDouble r;
  two_diff(a, b, r.hi, r.lo);
  return r;
}

inline DoubleDouble dd_negate(DoubleDouble x) { return {-x.hi, -x.lo}; }

inline DoubleDouble dd_add(DoubleDouble x, DoubleDouble y) {
  double sh, sl, th, tl, vh, vl;
  two_sum(x.hi, y.hi, sh, sl);
  two_sum(x.lo, y.lo, th, tl);
  const double c = sl + th;
  two_sum(sh, c, vh, vl);
  const double w = tl + vl;
  DoubleDouble z;
  two_sum(vh, w, z.hi, z.lo);
  return z;
}

inline DoubleDouble dd_mul(DoubleDouble x, DoubleDouble y) {
  double ch, cl1;
  two_product(x.hi, y.hi, ch, cl1);
  const double t1 = x.hi * y.lo;
  const double t2 = x.lo * y.hi;
  const double cl3 = cl1 + (t1 + t2);
  DoubleDouble z;
  two_sum(ch, cl3, z.hi, z.lo);
  return z;
}

/// Dekker's two_product with the operands already split (bit-identical to two_product).
inline void two_product_presplit(double a, double ahi, double alo, double b, double bhi, double blo,
                                 double& x, double& y) {
  x = a * b;
  const double err1 = x - (ahi * bhi);
  const double err2 = err1 - (alo * bhi);
  const double err3 = err2 - (ahi * blo);
  y = (alo * blo) - err3;
}

/// A leaf: an exact difference hi + lo with hi split once (Dekker) for all the products
/// it enters; arithmetic on leaves is the same as on DoubleDouble, bit for bit.
struct Leaf {
  DoubleDouble value;
  double hi_hi, hi_lo;  // split of value.hi
};

inline DoubleDouble dd_mul(const Leaf& x, const Leaf& y) {
  double ch, cl1;
  two_product_presplit(x.value.hi, x.hi_hi, x.hi_lo, y.value.hi, y.hi_hi, y.hi_lo, ch, cl1);
  const double cl3 = cl1 + ((x.value.hi * y.value.lo) + (x.value.lo * y.value.hi));
  DoubleDouble z;
  two_sum(ch, cl3, z.hi, z.lo);
  return z;
}

inline DoubleDouble dd_mul(const Leaf& x, DoubleDouble y) {
  double ch, cl1, yhi, ylo;
  split(y.hi, yhi, ylo);
  two_product_presplit(x.value.hi, x.hi_hi, x.hi_lo, y.hi, yhi, ylo, ch, cl1);
  const double cl3 = cl1 + ((x.value.hi * y.lo) + (x.value.lo * y.hi));
  DoubleDouble z;
  two_sum(ch, cl3, z.hi, z.lo);
  return z;
}

inline DoubleDouble dd_square(const Leaf& x) {
  const double hi = x.hi_hi, lo = x.hi_lo;
  const double ch = x.value.hi * x.value.hi;
  const double err1 = ch - (hi * hi);
  const double err3 = err1 - ((hi + hi) * lo);
  const double cl1 = (lo * lo) - err3;
  const double cl3 = cl1 + ((x.value.hi + x.value.hi) * x.value.lo);
  DoubleDouble z;
  two_sum(ch, cl3, z.hi, z.lo);
  return z;
}

/// A double-double value with the magnitude bound m of the propagation rules above.
struct Tracked {
  DoubleDouble value;
  double magnitude;
};

/// A leaf with its magnitude |fl(a - b)| (error 0).
struct TrackedLeaf {
  Leaf leaf;
  double magnitude;
};

/// The exact difference a - b as a leaf.
inline TrackedLeaf tracked_difference(double a, double b) {
  TrackedLeaf t;
  t.leaf.value = dd_difference(a, b);
  split(t.leaf.value.hi, t.leaf.hi_hi, t.leaf.hi_lo);
  t.magnitude = std::abs(t.leaf.value.hi);
  return t;
}

inline Tracked operator*(const TrackedLeaf& x, const TrackedLeaf& y) {
  return {dd_mul(x.leaf, y.leaf), x.magnitude * y.magnitude};
}
inline Tracked operator*(const TrackedLeaf& x, const Tracked& y) {
  return {dd_mul(x.leaf, y.value), x.magnitude * y.magnitude};
}
inline Tracked square(const TrackedLeaf& x) { return {dd_square(x.leaf), x.magnitude * x.magnitude}; }

inline Tracked operator+(const Tracked& x, const Tracked& y) {
  return {dd_add(x.value, y.value), x.magnitude + y.magnitude};
}
inline Tracked operator-(const Tracked& x, const Tracked& y) {
  return {dd_add(x.value, dd_negate(y.value)), x.magnitude + y.magnitude};
}
inline Tracked operator*(const Tracked& x, const Tracked& y) {
  return {dd_mul(x.value, y.value), x.magnitude * y.magnitude};
}

}  // namespace delmesh::predicates::detail
