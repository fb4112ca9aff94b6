// Exact predicates: floating-point filter, then exact expansion evaluation; symbolic
// perturbation for Delaunay degeneracies. Conventions and method: predicates.h.
//
// Filter constants are Shewchuk's stage-A error bounds (1997, §4): with eps = 2^-53,
// a determinant computed in floating point from the rounded coordinate differences has
// absolute error at most errbound * permanent, where the permanent is the same
// expression with every term replaced by its absolute value. When |det| exceeds that
// bound its sign is certain; otherwise the determinant is recomputed exactly from the
// exact differences (Expansion::difference) with the same formula.
#include "toolkit/predicates/predicates.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "toolkit/core/error.h"
#include "toolkit/predicates/expansion.h"

namespace delmesh::predicates {

namespace {

using detail::Expansion;

constexpr double kEps = 0x1p-53;
constexpr double kCcwErrBoundA = (3.0 + 16.0 * kEps) * kEps;
constexpr double kO3dErrBoundA = (7.0 + 56.0 * kEps) * kEps;
constexpr double kIccErrBoundA = (10.0 + 96.0 * kEps) * kEps;
constexpr double kIspErrBoundA = (16.0 + 224.0 * kEps) * kEps;

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

// ---- orient2d: det[a-c, b-c] (= det[b-a, c-a]) --------------------------------------

Sign orient2d_exact(const double* a, const double* b, const double* c) {
  const Expansion acx = Expansion::difference(a[0], c[0]);
  const Expansion acy = Expansion::difference(a[1], c[1]);
  const Expansion bcx = Expansion::difference(b[0], c[0]);
  const Expansion bcy = Expansion::difference(b[1], c[1]);
  return sign_of(acx * bcy - acy * bcx);
}

// ---- orient3d: Shewchuk's det[a-d, b-d, c-d], negated by the caller -----------------

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
  return orient3d_shewchuk_exact(a, b, c, d);
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
  return insphere_shewchuk_exact(a, b, c, d, e);
}

Sign dot_exact(const double* a, const double* b, const double* c, int dim) {
  Expansion sum;
  for (int i = 0; i < dim; ++i) {
    sum = sum + Expansion::difference(a[i], c[i]) * Expansion::difference(b[i], c[i]);
  }
  return sign_of(sum);
}

/// Projection of a 3D point onto the coordinate plane that drops `axis`, right-handed.
inline std::array<double, 2> project(const double* p, Axis axis) {
  switch (axis) {
    case Axis::X: return {p[1], p[2]};
    case Axis::Y: return {p[2], p[0]};
    case Axis::Z: break;
  }
  return {p[0], p[1]};
}

}  // namespace

Sign orient2d(const double* a, const double* b, const double* c) {
  const double detleft = (a[0] - c[0]) * (b[1] - c[1]);
  const double detright = (a[1] - c[1]) * (b[0] - c[0]);
  const double det = detleft - detright;
  Sign s;
  if (filter(det, kCcwErrBoundA * (std::abs(detleft) + std::abs(detright)), s)) return s;
  return orient2d_exact(a, b, c);
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
  return incircle_exact(a, b, c, d);
}

Sign insphere(const double* a, const double* b, const double* c, const double* d, const double* e) {
  // Shewchuk's insphere is positive for e inside when his orient3d(a,b,c,d) > 0, i.e. when
  // ours is negative: negate to obtain our convention.
  return -insphere_shewchuk(a, b, c, d, e);
}

Sign orient2d_projected(const double* a, const double* b, const double* c, Axis axis) {
  const auto pa = project(a, axis), pb = project(b, axis), pc = project(c, axis);
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
  const auto pa = project(a, axis), pb = project(b, axis), pc = project(c, axis), pd = project(d, axis);
  const int k = static_cast<int>(axis);
  // (i, j) as in project(): X -> (y, z), Y -> (z, x), Z -> (x, y)
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
