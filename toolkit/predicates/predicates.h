// Exact geometric predicates: the only place in delmesh that decides the sign of a
// determinant.
//
// Method (Shewchuk, "Adaptive Precision Floating-Point Arithmetic and Fast Robust
// Geometric Predicates", 1997; notes §2.1.1 and §2.1.3 for the tests themselves):
//   1. evaluate the determinant in floating point together with a forward error bound;
//      if |det| exceeds the bound the sign is certain (the filter, almost every call);
//   2. otherwise evaluate the determinant exactly as a floating-point expansion
//      (toolkit/predicates/expansion.h) and return the sign of its most significant term.
// orient3d and insphere have two intermediate stages between 1 and 2: when all
// coordinate differences are small integers (times one power of two) the floating-point
// value of step 1 is exact; otherwise a double-double evaluation from the exact
// differences with a proven error bound of order eps^2 times the permanent
// (toolkit/predicates/double_double_filter.h) decides almost every case that is
// degenerate only up to rounding, e.g. points rounded onto a sphere or a plane. The
// rest goes through Shewchuk's adaptive stages and, if needed, step 2.
// Inputs are IEEE doubles; results are exact for all finite inputs whose intermediate
// products do not overflow or underflow (coordinates within about 1e-140 .. 1e+140 in
// magnitude, or zero). This file is compiled with -ffp-contract=off and no fast-math.
//
// Sign conventions (written once, used everywhere):
//   orient2d(a,b,c)      Positive  <=> a, b, c are in counterclockwise order.
//                        = sign det[b-a, c-a].
//   orient3d(a,b,c,d)    Positive  <=> seen from d, a, b, c are counterclockwise, i.e.
//                        d lies on the side of plane abc that the right-hand normal
//                        (b-a)x(c-a) points to. = sign det[b-a, c-a, d-a].
//                        (This is the negative of Shewchuk's orient3d.)
//   incircle(a,b,c,d)    Positive  <=> d lies inside the circle through a, b, c when
//                        orient2d(a,b,c) is Positive (the sign flips with orientation).
//   insphere(a,b,c,d,e)  Positive  <=> e lies inside the sphere through a, b, c, d when
//                        orient3d(a,b,c,d) is Positive (flips with orientation).
//
// Symbolic perturbation (simulation of simplicity): the *_sos variants never return
// Zero for a non-degenerate simplex. Each point carries a distinct integer id; the lifted
// coordinate |p|^2 of every point is raised by an infinitesimal that is larger for larger
// ids, each dominating all smaller ones. A cocircular/cospherical query is then decided by
// the first nonzero lower-dimensional orientation, taken in decreasing id order (Devillers
// and Teillaud, "Perturbations for Delaunay and weighted Delaunay 3D triangulations",
// 2011). The perturbed point set is fixed by the ids, so all queries agree with one
// another: a triangulation built with these tests is the Delaunay triangulation of the
// perturbed points, and a Delaunay triangulation of the real points.
#pragma once

#include <array>
#include <cstdint>

namespace delmesh {

enum class Sign : std::int8_t { Negative = -1, Zero = 0, Positive = 1 };

inline constexpr Sign operator-(Sign s) { return static_cast<Sign>(-static_cast<int>(s)); }
inline constexpr Sign operator*(Sign a, Sign b) {
  return static_cast<Sign>(static_cast<int>(a) * static_cast<int>(b));
}
inline constexpr int to_int(Sign s) { return static_cast<int>(s); }

/// Coordinate axis dropped by a projection onto a coordinate plane.
enum class Axis : std::uint8_t { X = 0, Y = 1, Z = 2 };

namespace predicates {

/// sign det[b-a, c-a] for 2D points (x, y).
Sign orient2d(const double* a, const double* b, const double* c);

/// sign det[b-a, c-a, d-a] for 3D points (x, y, z).
Sign orient3d(const double* a, const double* b, const double* c, const double* d);

/// Is d inside (Positive), on (Zero) or outside (Negative) the circle through a, b, c,
/// for counterclockwise a, b, c? Sign multiplied by orient2d(a,b,c) in general.
Sign incircle(const double* a, const double* b, const double* c, const double* d);

/// Is e inside (Positive), on (Zero) or outside (Negative) the sphere through a, b, c, d,
/// for orient3d(a,b,c,d) Positive? Sign multiplied by orient3d(a,b,c,d) in general.
Sign insphere(const double* a, const double* b, const double* c, const double* d,
              const double* e);

/// The 3D point p projected onto the coordinate plane that drops `axis`, in the
/// right-handed frame orient2d_projected uses: dropping Z gives (x, y), dropping X gives
/// (y, z), dropping Y gives (z, x).
inline std::array<double, 2> project_onto_axis_plane(const double* p, Axis axis) {
  switch (axis) {
    case Axis::X: return {p[1], p[2]};
    case Axis::Y: return {p[2], p[0]};
    case Axis::Z: break;
  }
  return {p[0], p[1]};
}

/// orient2d of 3D points projected onto the coordinate plane that drops `axis`, keeping
/// a right-handed frame: dropping Z uses (x, y), dropping X uses (y, z), dropping Y uses
/// (z, x). For points on a plane whose normal n has its largest component along `axis`,
/// the result is the orientation seen from the side n[axis] > 0 points to.
Sign orient2d_projected(const double* a, const double* b, const double* c, Axis axis);

/// incircle of four exactly coplanar 3D points, inside their common plane (no
/// projection, which would distort circles). `axis` is the dominant axis of the plane's
/// normal. Positive: d inside the circle through a, b, c when orient2d_projected(a,b,c,
/// axis) is Positive. The result is exact; it uses a sphere through a, b, c and a point
/// lifted off the plane along `axis`, whose intersection with the plane is the circle.
Sign incircle_coplanar(const double* a, const double* b, const double* c, const double* d,
                       Axis axis);

/// In-plane incircle for the points of one facet, consistent even for points that are off
/// the plane by roundoff (Steiner points): the points are projected by dropping `axis`,
/// and the lifting |p|^2 is replaced by the squared in-plane length of the projection,
/// L(p) = n_k^2 (p_i^2 + p_j^2) + (n_i p_i + n_j p_j)^2 (k = axis, (i, j) the kept
/// coordinates, n the facet normal as given). L is a positive definite quadratic form,
/// so this is the incircle test of a fixed metric: flips terminate and triangulations are
/// well defined. For exactly coplanar points and the exact normal it is the true in-plane
/// circle test. Positive: d inside when orient2d_projected(a,b,c,axis) is Positive.
Sign incircle_in_plane(const double* a, const double* b, const double* c, const double* d,
                       Axis axis, const double* normal);

/// incircle with symbolic perturbation: never Zero when a, b, c are not collinear.
/// ia..id are distinct global ids of the four points.
Sign incircle_sos(const double* a, const double* b, const double* c, const double* d,
                  std::uint32_t ia, std::uint32_t ib, std::uint32_t ic, std::uint32_t id);

/// insphere with symbolic perturbation: never Zero when a, b, c, d are not coplanar.
Sign insphere_sos(const double* a, const double* b, const double* c, const double* d,
                  const double* e, std::uint32_t ia, std::uint32_t ib, std::uint32_t ic,
                  std::uint32_t id, std::uint32_t ie);

/// Is p inside (Positive), on (Zero) or outside (Negative) the equatorial sphere of the
/// 3D triangle abc: the smallest sphere through a, b, c, centered in their plane (notes
/// §4.2.1, subfacet encroachment)? Undefined for collinear a, b, c
/// (returns Zero then).
Sign in_equatorial_sphere(const double* a, const double* b, const double* c, const double* p);

/// Exact sign of the dot product (a - c) . (b - c) of 2D points: the test "does c see
/// segment ab at an angle greater than 90 degrees" (Negative) used for encroachment.
Sign dot2d(const double* a, const double* b, const double* c);

/// Exact sign of (a - c) . (b - c) for 3D points.
Sign dot3d(const double* a, const double* b, const double* c);

}  // namespace predicates
}  // namespace delmesh
