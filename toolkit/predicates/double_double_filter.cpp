// Double-double filter stage of orient3d and insphere (see double_double_filter.h).
//
// Error bound. The determinant is Shewchuk's expression of orient3d / insphere (the same
// tree as stage A in predicates.cpp) evaluated on Tracked values whose leaves are the
// exact differences (TwoDiff). With the rules of double_double.h (leaf k = 0; a sum adds
// 3 to the larger k of its operands; a product adds 8 to the sum of its operands' k):
//   orient3d: products of differences 8; 2x2 minors 11; z-difference times minor 19;
//             sum of three such terms 22, 25.                              K = 25.
//   insphere: 2x2 minors 11; 3x3 minors 19, 22, 25; lifts (squares 8, two sums) 14;
//             lift times 3x3 minor 14 + 25 + 8 = 47; the four products summed
//             pairwise 50, then 53.                                        K = 53.
// So |computed - exact| <= K u^2 m (1 + O(u)) with u = 2^-53 and m the permanent (the
// same expression on absolute values of the exact differences). The magnitude is
// computed in floating point from |fl(difference)|, which is within a factor
// (1 + u)^5 of the exact difference's, by at most ~10 roundings of positive terms, so
// m <= m_computed (1 + 20u). The tests use 32 and 64 in place of 25 and 53, which
// covers all the (1 + O(u)) factors by a wide margin; since |hi| (1 - u) <= |hi + lo|,
// |hi| > bound implies that the exact determinant has the sign of hi.
// Overflow or NaN makes the comparison false: the caller then falls through to the
// exact stages. As everywhere in the predicates, underflow of intermediate products is
// outside the guarantee (predicates.h).
#include "toolkit/predicates/double_double_filter.h"

#include "toolkit/predicates/double_double.h"

namespace delmesh::predicates::detail {

namespace {

constexpr double kU = 0x1p-53;
constexpr double kO3dDoubleDoubleBound = 32.0 * kU * kU;
constexpr double kIspDoubleDoubleBound = 64.0 * kU * kU;

/// Sign of a Tracked determinant when |value| exceeds factor * magnitude.
inline bool decide(const Tracked& det, double factor, Sign& out) {
  const double bound = factor * det.magnitude;
  if (det.value.hi > bound) {
    out = Sign::Positive;
    return true;
  }
  if (-det.value.hi > bound) {
    out = Sign::Negative;
    return true;
  }
  return false;
}

}  // namespace

bool orient3d_double_double(const double* a, const double* b, const double* c, const double* d,
                            Sign& out) {
  const TrackedLeaf adx = tracked_difference(a[0], d[0]), bdx = tracked_difference(b[0], d[0]),
                cdx = tracked_difference(c[0], d[0]);
  const TrackedLeaf ady = tracked_difference(a[1], d[1]), bdy = tracked_difference(b[1], d[1]),
                cdy = tracked_difference(c[1], d[1]);
  const TrackedLeaf adz = tracked_difference(a[2], d[2]), bdz = tracked_difference(b[2], d[2]),
                cdz = tracked_difference(c[2], d[2]);
  // Shewchuk's orient3d, det[a-d, b-d, c-d]: the negative of ours.
  const Tracked det = adz * (bdx * cdy - cdx * bdy) + bdz * (cdx * ady - adx * cdy) +
                      cdz * (adx * bdy - bdx * ady);
  Sign s = Sign::Zero;
  if (!decide(det, kO3dDoubleDoubleBound, s)) return false;
  out = -s;
  return true;
}

bool insphere_double_double(const double* a, const double* b, const double* c, const double* d,
                            const double* e, Sign& out) {
  const TrackedLeaf aex = tracked_difference(a[0], e[0]), bex = tracked_difference(b[0], e[0]),
                cex = tracked_difference(c[0], e[0]), dex = tracked_difference(d[0], e[0]);
  const TrackedLeaf aey = tracked_difference(a[1], e[1]), bey = tracked_difference(b[1], e[1]),
                cey = tracked_difference(c[1], e[1]), dey = tracked_difference(d[1], e[1]);
  const TrackedLeaf aez = tracked_difference(a[2], e[2]), bez = tracked_difference(b[2], e[2]),
                cez = tracked_difference(c[2], e[2]), dez = tracked_difference(d[2], e[2]);

  const Tracked ab = aex * bey - bex * aey, bc = bex * cey - cex * bey;
  const Tracked cd = cex * dey - dex * cey, da = dex * aey - aex * dey;
  const Tracked ac = aex * cey - cex * aey, bd = bex * dey - dex * bey;

  const Tracked abc = aez * bc - bez * ac + cez * ab;
  const Tracked bcd = bez * cd - cez * bd + dez * bc;
  const Tracked cda = cez * da + dez * ac + aez * cd;
  const Tracked dab = dez * ab + aez * bd + bez * da;

  const Tracked alift = square(aex) + square(aey) + square(aez);
  const Tracked blift = square(bex) + square(bey) + square(bez);
  const Tracked clift = square(cex) + square(cey) + square(cez);
  const Tracked dlift = square(dex) + square(dey) + square(dez);

  // Shewchuk's insphere: positive for e inside when his orient3d(a,b,c,d) is positive,
  // the negative of ours.
  const Tracked det = (dlift * abc - clift * dab) + (blift * cda - alift * bcd);
  Sign s = Sign::Zero;
  if (!decide(det, kIspDoubleDoubleBound, s)) return false;
  out = -s;
  return true;
}

}  // namespace delmesh::predicates::detail
