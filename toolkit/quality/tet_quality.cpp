// Tetrahedron quality measures (see tet_quality.h).
#include "toolkit/quality/tet_quality.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <numbers>
#include <utility>

namespace delmesh {

double signed_volume(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  return (b - a).dot((c - a).cross(d - a)) / 6.0;
}

namespace {

/// circumradius in long double: 11 more bits of mantissa for the determinant of a tet so
/// flat that its double value rounds to zero; infinity if that rounds to zero as well.
double circumradius_long(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  using L = long double;
  const L u[3] = {L(b[0]) - a[0], L(b[1]) - a[1], L(b[2]) - a[2]};
  const L v[3] = {L(c[0]) - a[0], L(c[1]) - a[1], L(c[2]) - a[2]};
  const L w[3] = {L(d[0]) - a[0], L(d[1]) - a[1], L(d[2]) - a[2]};
  auto cross = [](const L* x, const L* y, L* out) {
    out[0] = x[1] * y[2] - x[2] * y[1];
    out[1] = x[2] * y[0] - x[0] * y[2];
    out[2] = x[0] * y[1] - x[1] * y[0];
  };
  L vw[3], wu[3], uv[3];
  cross(v, w, vw);
  cross(w, u, wu);
  cross(u, v, uv);
  const L denom = 2 * (u[0] * vw[0] + u[1] * vw[1] + u[2] * vw[2]);
  if (denom == 0) return std::numeric_limits<double>::infinity();
  const L uu = u[0] * u[0] + u[1] * u[1] + u[2] * u[2], vv = v[0] * v[0] + v[1] * v[1] + v[2] * v[2],
          ww = w[0] * w[0] + w[1] * w[1] + w[2] * w[2];
  L norm2 = 0;
  for (int k = 0; k < 3; ++k) {
    const L x = (uu * vw[k] + vv * wu[k] + ww * uv[k]) / denom;
    norm2 += x * x;
  }
  return static_cast<double>(std::sqrt(norm2));
}

}  // namespace

double circumradius(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  // Center relative to a: (|u|^2 (v x w) + |v|^2 (w x u) + |w|^2 (u x v)) / (2 u.(v x w)).
  const Vec3 u = b - a, v = c - a, w = d - a;
  const double denom = 2.0 * u.dot(v.cross(w));
  if (denom == 0.0) return circumradius_long(a, b, c, d);
  const Vec3 center = (u.squaredNorm() * v.cross(w) + v.squaredNorm() * w.cross(u) +
                       w.squaredNorm() * u.cross(v)) / denom;
  const double r = center.norm();
  return std::isfinite(r) ? r : circumradius_long(a, b, c, d);
}

double shortest_edge(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  const double e2 = std::min({(a - b).squaredNorm(), (a - c).squaredNorm(), (a - d).squaredNorm(),
                              (b - c).squaredNorm(), (b - d).squaredNorm(), (c - d).squaredNorm()});
  return std::sqrt(e2);
}

double radius_edge_ratio(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  const double e = shortest_edge(a, b, c, d);
  if (e == 0.0) return std::numeric_limits<double>::infinity();
  return circumradius(a, b, c, d) / e;
}

std::array<double, 6> dihedral_angles_deg(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  // The dihedral angle at edge pq is pi minus the angle between the outward normals of
  // the two faces that share pq. Face normals opposite each vertex, outward for a
  // positively oriented tet:
  const Vec3 na = (c - b).cross(d - b);  // face bcd, opposite a
  const Vec3 nb = (d - a).cross(c - a);  // face acd, opposite b
  const Vec3 nc = (b - a).cross(d - a);  // face abd, opposite c
  const Vec3 nd = (c - a).cross(b - a);  // face abc, opposite d
  auto angle = [](const Vec3& n1, const Vec3& n2) {
    const double len = n1.norm() * n2.norm();
    if (len == 0.0) return 0.0;
    const double cosine = std::clamp(-n1.dot(n2) / len, -1.0, 1.0);
    return std::acos(cosine) * 180.0 / std::numbers::pi;
  };
  // edge ab is shared by the faces opposite c and d, and so on.
  return {angle(nc, nd), angle(nb, nd), angle(nb, nc), angle(na, nd), angle(na, nc), angle(na, nb)};
}

double min_dihedral_sine(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  const double six_v = (b - a).dot((c - a).cross(d - a));
  const double na = (c - b).cross(d - b).norm();  // face bcd, opposite a
  const double nb = (d - a).cross(c - a).norm();
  const double nc = (b - a).cross(d - a).norm();
  const double nd = (c - a).cross(b - a).norm();
  // Edge ab lies between the faces opposite c and d, and so on.
  const double la = (b - a).norm() / (nc * nd), lac = (c - a).norm() / (nb * nd), lad = (d - a).norm() / (nb * nc);
  const double lbc = (c - b).norm() / (na * nd), lbd = (d - b).norm() / (na * nc), lcd = (d - c).norm() / (na * nb);
  if (!(six_v > 0.0)) return std::min(six_v, 0.0);  // flat or inverted
  return six_v * std::min({la, lac, lad, lbc, lbd, lcd});
}

std::array<double, 6> window_dihedral_sines(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d,
                                            double obtuse_scale) {
  const double six_v = (b - a).dot((c - a).cross(d - a));
  // Outward normals of the faces opposite a, b, c, d (for a positively oriented tet); the
  // angle at an edge is obtuse when the two normals of its faces point the same way.
  const Vec3 n[4] = {(c - b).cross(d - b), (d - a).cross(c - a), (b - a).cross(d - a), (c - a).cross(b - a)};
  const double len[4] = {n[0].norm(), n[1].norm(), n[2].norm(), n[3].norm()};
  constexpr int kPairs[6][2] = {{2, 3}, {1, 3}, {1, 2}, {0, 3}, {0, 2}, {0, 1}};
  const Vec3 edge[6] = {b - a, c - a, d - a, c - b, d - b, d - c};
  std::array<double, 6> s{};
  for (int e = 0; e < 6; ++e) {
    const int i = kPairs[e][0], j = kPairs[e][1];
    double x = six_v * edge[e].norm() / (len[i] * len[j]);
    if (!std::isfinite(x)) x = 0.0;
    if (n[i].dot(n[j]) > 0.0) x *= obtuse_scale;
    s[e] = x;
  }
  return s;
}

double min_window_dihedral_sine(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d, double obtuse_scale) {
  if (obtuse_scale == 1.0) return min_dihedral_sine(a, b, c, d);
  const double six_v = (b - a).dot((c - a).cross(d - a));
  if (!(six_v > 0.0)) return std::min(six_v, 0.0);  // flat or inverted
  const auto s = window_dihedral_sines(a, b, c, d, obtuse_scale);
  return *std::min_element(s.begin(), s.end());
}

double window_obtuse_scale(double low_deg, double high_deg) {
  if (!(low_deg > 0.0) || !(high_deg < 180.0)) return 1.0;
  return std::sin(low_deg * std::numbers::pi / 180.0) / std::sin((180.0 - high_deg) * std::numbers::pi / 180.0);
}

namespace {

/// Is d / sqrt(len2) below c (len2 > 0)? Decided on squares, without a square root.
bool ratio_below(double d, double len2, double c) {
  if (c >= 0.0) return d < 0.0 || d * d < c * c * len2;
  return d < 0.0 && d * d > c * c * len2;
}

}  // namespace

bool dihedral_outside(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d, double low_deg,
                      double high_deg) {
  if (low_deg <= 0.0 && high_deg >= 180.0) return false;
  // Compared through cosines (no acos): angle < low iff cos > cos(low), and so on; each
  // cosine is -n1.n2 / (|n1| |n2|), compared on squares (no square root either).
  // The cosines of the last window asked for (refinement asks for one window millions
  // of times).
  thread_local double last_low = -1.0, last_high = -1.0, cos_low = 1.0, cos_high = -1.0;
  if (low_deg != last_low || high_deg != last_high) {
    last_low = low_deg;
    last_high = high_deg;
    cos_low = std::cos(low_deg * std::numbers::pi / 180.0);
    cos_high = std::cos(high_deg * std::numbers::pi / 180.0);
  }
  const bool check_low = low_deg > 0.0, check_high = high_deg < 180.0;
  const Vec3 n[4] = {(c - b).cross(d - b), (d - a).cross(c - a), (b - a).cross(d - a), (c - a).cross(b - a)};
  const double n2[4] = {n[0].squaredNorm(), n[1].squaredNorm(), n[2].squaredNorm(), n[3].squaredNorm()};
  constexpr int kPairs[6][2] = {{2, 3}, {1, 3}, {1, 2}, {0, 3}, {0, 2}, {0, 1}};
  for (const auto& pair : kPairs) {
    const double len2 = n2[pair[0]] * n2[pair[1]];
    if (len2 == 0.0) return true;
    const double dot = -n[pair[0]].dot(n[pair[1]]);  // cosine times |n1| |n2|
    if (check_low && ratio_below(-dot, len2, -cos_low)) return true;  // cosine above cos(low)
    if (check_high && ratio_below(dot, len2, cos_high)) return true;
  }
  return false;
}

namespace {

/// The extreme dihedral angles of a tet in degrees, as dihedral_extremes_deg gives them,
/// and whether one of the six angles of dihedral_angles_deg is NaN (a NaN cosine, which
/// the extremes may skip).
struct DihedralExtremes {
  double smallest_deg, largest_deg;
  bool nan;
};

DihedralExtremes dihedral_extremes(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  const Vec3 na = (c - b).cross(d - b);
  const Vec3 nb = (d - a).cross(c - a);
  const Vec3 nc = (b - a).cross(d - a);
  const Vec3 nd = (c - a).cross(b - a);
  auto cosine = [](const Vec3& n1, const Vec3& n2) {
    const double len = n1.norm() * n2.norm();
    if (len == 0.0) return 1.0;  // the angle 0 of dihedral_angles_deg
    return std::clamp(-n1.dot(n2) / len, -1.0, 1.0);
  };
  const double cosines[6] = {cosine(nc, nd), cosine(nb, nd), cosine(nb, nc),
                             cosine(na, nd), cosine(na, nc), cosine(na, nb)};
  const auto [lo, hi] = std::minmax_element(std::begin(cosines), std::end(cosines));
  auto degrees = [](double x) { return std::acos(x) * 180.0 / std::numbers::pi; };
  const bool nan = std::any_of(std::begin(cosines), std::end(cosines), [](double x) { return std::isnan(x); });
  return {degrees(*hi), degrees(*lo), nan};
}

/// Is a tet with these extremes outside [low_deg, high_deg] as outside_dihedral_window
/// decides it? Without a NaN angle the smallest and largest of the six angles are the
/// extremes bit for bit (dihedral_extremes_deg), so one of the six leaves the window
/// exactly when one of the extremes does.
bool extremes_outside(const DihedralExtremes& e, double low_deg, double high_deg) {
  if (low_deg <= 0.0 && high_deg >= 180.0) return false;
  return e.nan || !(e.smallest_deg >= low_deg && e.largest_deg <= high_deg);
}

}  // namespace

bool outside_dihedral_window(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d, double low_deg,
                             double high_deg) {
  if (low_deg <= 0.0 && high_deg >= 180.0) return false;
  return extremes_outside(dihedral_extremes(a, b, c, d), low_deg, high_deg);
}

std::pair<double, double> dihedral_extremes_deg(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  const DihedralExtremes e = dihedral_extremes(a, b, c, d);
  return {e.smallest_deg, e.largest_deg};
}

namespace {

/// The report of a set of tets, fed one tet at a time in index order.
class ReportBuilder {
 public:
  ReportBuilder() {
    report_.radius_edge_counts.assign(report_.radius_edge_bounds.size() + 1, 0);
    report_.min_volume = std::numeric_limits<double>::infinity();
    report_.min_dihedral_deg = 180.0;
  }

  /// The measures of one tet, computed once and added to every report the tet belongs to.
  struct Measures {
    double volume = 0.0, ratio = 0.0, lo = 0.0, hi = 0.0;
    bool outside_window = false;
  };

  static Measures measure(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d, double dihedral_low_deg,
                          double dihedral_high_deg) {
    Measures m;
    m.volume = signed_volume(a, b, c, d);
    m.ratio = radius_edge_ratio(a, b, c, d);
    const DihedralExtremes extremes = dihedral_extremes(a, b, c, d);
    m.lo = extremes.smallest_deg;
    m.hi = extremes.largest_deg;
    m.outside_window = extremes_outside(extremes, dihedral_low_deg, dihedral_high_deg);
    return m;
  }

  void add(const Measures& m, double radius_edge_bound) {
    TetQualityReport& r = report_;
    ++r.tets;
    r.total_volume += m.volume;
    r.min_volume = std::min(r.min_volume, m.volume);
    if (std::isfinite(m.ratio)) {
      sum_ratio_ += m.ratio;
      ++finite_ratios_;
      r.max_radius_edge = std::max(r.max_radius_edge, m.ratio);
    } else {
      ++r.flat_ratio_tets;
    }
    const auto bin = std::lower_bound(r.radius_edge_bounds.begin(), r.radius_edge_bounds.end(), m.ratio) -
                     r.radius_edge_bounds.begin();
    ++r.radius_edge_counts[static_cast<std::size_t>(bin)];
    if (!(m.ratio <= radius_edge_bound)) ++r.above_radius_edge;
    r.min_dihedral_deg = std::min(r.min_dihedral_deg, m.lo);
    r.max_dihedral_deg = std::max(r.max_dihedral_deg, m.hi);
    ++r.min_dihedral_counts[std::min<std::size_t>(7, static_cast<std::size_t>(std::max(0.0, m.lo) / 10.0))];
    ++r.max_dihedral_counts[std::min<std::size_t>(10, static_cast<std::size_t>(std::max(70.0, m.hi) / 10.0) - 7)];
    if (m.outside_window) ++r.outside_dihedral_window;
  }

  TetQualityReport finish() {
    if (report_.tets == 0) {
      report_.min_volume = 0.0;
      report_.min_dihedral_deg = 0.0;
      return report_;
    }
    if (finite_ratios_ > 0) report_.mean_radius_edge = sum_ratio_ / static_cast<double>(finite_ratios_);
    return report_;
  }

 private:
  TetQualityReport report_;
  double sum_ratio_ = 0.0;
  std::size_t finite_ratios_ = 0;
};

bool is_selected(const std::vector<std::uint8_t>& selection, std::size_t i) {
  return i < selection.size() && selection[i] != 0;
}

TetQualityReport quality_report(const TetraMesh& mesh, const std::vector<std::uint8_t>* selection, bool selected,
                                double radius_edge_bound, double dihedral_low_deg, double dihedral_high_deg) {
  ReportBuilder builder;
  for (std::size_t i = 0; i < mesh.tets.size(); ++i) {
    if (selection && is_selected(*selection, i) != selected) continue;
    const auto& t = mesh.tets[i];
    builder.add(ReportBuilder::measure(mesh.points[t[0]], mesh.points[t[1]], mesh.points[t[2]], mesh.points[t[3]],
                                       dihedral_low_deg, dihedral_high_deg),
                radius_edge_bound);
  }
  return builder.finish();
}

}  // namespace

TetQualityReport tet_quality_report(const TetraMesh& mesh, double radius_edge_bound, double dihedral_low_deg,
                                    double dihedral_high_deg) {
  return quality_report(mesh, nullptr, true, radius_edge_bound, dihedral_low_deg, dihedral_high_deg);
}

TetQualityReport tet_quality_report(const TetraMesh& mesh, const std::vector<std::uint8_t>& selection, bool selected,
                                    double radius_edge_bound, double dihedral_low_deg, double dihedral_high_deg) {
  return quality_report(mesh, &selection, selected, radius_edge_bound, dihedral_low_deg, dihedral_high_deg);
}

TetQualitySplit tet_quality_split(const TetraMesh& mesh, const std::vector<std::uint8_t>& selection,
                                  double radius_edge_bound, double dihedral_low_deg, double dihedral_high_deg) {
  ReportBuilder all, in, out;
  for (std::size_t i = 0; i < mesh.tets.size(); ++i) {
    const auto& t = mesh.tets[i];
    const auto m = ReportBuilder::measure(mesh.points[t[0]], mesh.points[t[1]], mesh.points[t[2]],
                                          mesh.points[t[3]], dihedral_low_deg, dihedral_high_deg);
    all.add(m, radius_edge_bound);
    (is_selected(selection, i) ? in : out).add(m, radius_edge_bound);
  }
  return {all.finish(), in.finish(), out.finish()};
}

}  // namespace delmesh
