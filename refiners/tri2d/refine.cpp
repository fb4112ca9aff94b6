// Ruppert's and Chew's Delaunay refinement with concentric shells and the Quitter
// (see refine.h; notes §3.3-3.8).
#include "refiners/tri2d/refine.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <unordered_map>

#include "toolkit/predicates/predicates.h"

namespace delmesh::tri2d {

using mesh2d::kGhost;
using mesh2d::kNone;
using mesh2d::Location;
using mesh2d::next3;
using mesh2d::prev3;
using mesh2d::Triangulation;

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kSixtyDeg = kPi / 3.0;
// cos^2 of asin(1 / (2 sqrt 2)) = 20.7 degrees: 1 - 1/8.
constexpr double kCos2Of20_7 = 0.875;
// Resolution floor: no vertex is inserted closer than 2^-36 times the domain's extent to
// its neighbours (about 10^5 units in the last place of the coordinates). Below that,
// rounded Steiner points no longer lie where the algorithm means them to.
constexpr int kResolutionBits = 36;
// An angle-driven vertex is inserted only if its insertion radius is at least this
// fraction of its anchor (the largest insertion radius along its chain of ancestors):
// 1/2 for bounds up to 30 degrees (Ruppert's own chains never shrink below 1/sqrt(2)),
// 0.7 above, where free-vertex cascades would otherwise spread small triangles.
constexpr double kAnchorFactorUpTo30 = 0.5;
constexpr double kAnchorFactorAbove30 = 0.7;

struct FanEdge {
  std::uint32_t other;
  double angle;          ///< direction of apex->other
  bool wedge_in_domain;  ///< the wedge from this edge counterclockwise to the next subsegment
};

// The subsegments around `apex` in counterclockwise order.
void collect_fan(const Triangulation& tri, std::uint32_t apex, std::vector<FanEdge>& fan) {
  fan.clear();
  const std::uint32_t start = tri.vt[apex];
  if (start == kNone) return;
  std::uint32_t t = start;
  const Point2& pa = tri.points[apex];
  for (std::size_t guard = 0; guard < tri.tf.size() + 3; ++guard) {
    std::uint32_t i = 0;
    while (tri.tv[3 * t + i] != apex) ++i;
    const std::uint32_t e = prev3(i);  // edge apex -> tv[next3(i)]
    const std::uint32_t other = tri.tv[3 * t + next3(i)];
    if (tri.subseg(t, e) && other != kGhost) {
      const Point2& po = tri.points[other];
      fan.push_back({other, std::atan2(po[1] - pa[1], po[0] - pa[0]), tri.in_domain(t)});
    }
    t = tri.tn[3 * t + next3(i)] / 3;
    if (t == start) break;
  }
  // The rotation may have started mid-wedge; wedge flags already refer to the triangle
  // just counterclockwise of each edge, which is what we want.
}

double ccw_gap(double from, double to) {
  double g = to - from;
  while (g <= 0) g += 2 * kPi;
  while (g > 2 * kPi) g -= 2 * kPi;
  return g;
}

bool is_power_of_two_length(double len) {
  const double l = std::log2(len);
  return std::abs(l - std::round(l)) < 1e-9;
}

class Refiner {
 public:
  Refiner(Triangulation& tri, mesh2d::SubsegmentOwners& owners, std::vector<std::uint8_t>& kind,
          const RefineParams& params)
      : tri_(tri), owners_(owners), kind_(kind), params_(params) {
    const double theta = params.min_angle_deg * kPi / 180.0;
    theta_ = theta;
    angle_on_ = params.quality && !params.chew && params.min_angle_deg > 0;
    strict_ = angle_on_ && params.min_angle_deg > 30.0;
    anchor_factor_ = strict_ ? kAnchorFactorAbove30 : kAnchorFactorUpTo30;
    const double c = std::cos(theta);
    cos2_bound_ = c * c;
    size_on_ = params.max_area > 0 || static_cast<bool>(params.max_area_at) ||
               std::any_of(params.region_max_area.begin(), params.region_max_area.end(),
                           [](double a) { return a > 0; });
  }

  RefineOutcome run() {
    anchor_.assign(tri_.points.size(), 0.0f);
    {
      double lo[2] = {1e300, 1e300}, hi[2] = {-1e300, -1e300};
      for (const Point2& p : tri_.points)
        for (int k = 0; k < 2; ++k) {
          lo[k] = std::min(lo[k], p[k]);
          hi[k] = std::max(hi[k], p[k]);
        }
      floor_ = std::ldexp(std::max(hi[0] - lo[0], hi[1] - lo[1]), -kResolutionBits);
    }
    kind_.resize(tri_.points.size(), kInputVertex);
    if (params_.chew) prepare_chew();
    // Initial encroached subsegments, then the initial bad triangles.
    for (std::uint32_t t = 0; t < tri_.num_slots(); ++t) {
      if (!tri_.in_domain(t)) continue;
      for (std::uint32_t i = 0; i < 3; ++i) {
        if (!tri_.subseg(t, i)) continue;
        const std::uint32_t v = tri_.vertex(t, i);
        if (predicates::dot2d(P(tri_.org(t, i)), P(tri_.dest(t, i)), P(v)) != Sign::Positive)
          segq_.push_back({tri_.org(t, i), tri_.dest(t, i), false, -1.0f});
      }
    }
    split_encroached();
    for (std::uint32_t t = 0; t < tri_.num_slots(); ++t)
      if (tri_.in_domain(t)) enqueue(t);
    for (;;) {
      split_encroached();
      if (out_of_budget()) break;
      const std::uint32_t t = pop();
      if (t == kNone) break;
      if (!tri_.in_domain(t)) continue;
      const Eval ev = evaluate(t);
      if (!ev.bad || ev.small_input_angle) continue;
      if (!retry_.empty()) {
        // A triangle requeued after asking for subsegment splits is given up if nothing
        // has been inserted since (the splits failed): no endless retry.
        const auto it = retry_.find(t);
        if (it != retry_.end()) {
          const bool stalled = it->second == tri_.points.size();
          retry_.erase(it);
          if (stalled) continue;
        }
      }
      split_triangle(t, ev);
    }
    for (std::uint32_t t = 0; t < tri_.num_slots(); ++t)
      if (tri_.in_domain(t) && evaluate(t).bad) ++outcome_.unmet_triangles;
    return outcome_;
  }

 private:
  struct Eval {
    bool bad = false;
    bool size_bad = false;
    bool small_input_angle = false;
    int bucket = 64;
    double d2 = 0;  ///< squared shortest edge
    std::uint32_t short_a = kNone, short_b = kNone;
  };
  struct SegWork {
    std::uint32_t a, b;
    bool forced;   ///< split even if no existing vertex encroaches (rejected circumcenter)
    float anchor;  ///< anchor radius inherited from the rejected circumcenter, or -1
  };

  const double* P(std::uint32_t v) const { return tri_.points[v].data(); }

  bool out_of_budget() {
    if (params_.max_steiner_points >= 0 &&
        static_cast<long long>(outcome_.steiner_points) >= params_.max_steiner_points) {
      outcome_.budget_exhausted = true;
      return true;
    }
    return false;
  }

  double area_bound(std::uint32_t t, double cx, double cy) const {
    double bound = params_.max_area;
    if (!tri_.region.empty()) {
      const std::uint32_t r = tri_.region[t];
      if (r < params_.region_max_area.size() && params_.region_max_area[r] > 0 &&
          (bound <= 0 || params_.region_max_area[r] < bound))
        bound = params_.region_max_area[r];
    }
    if (params_.max_area_at) {
      const double local = params_.max_area_at(cx, cy);
      if (local > 0 && (bound <= 0 || local < bound)) bound = local;
    }
    return bound;
  }

  Eval evaluate(std::uint32_t t) const {
    Eval ev;
    const std::uint32_t v[3] = {tri_.tv[3 * t], tri_.tv[3 * t + 1], tri_.tv[3 * t + 2]};
    const double* p[3] = {P(v[0]), P(v[1]), P(v[2])};
    double l[3];
    for (int i = 0; i < 3; ++i) {
      const double* a = p[(i + 1) % 3];
      const double* b = p[(i + 2) % 3];
      l[i] = (b[0] - a[0]) * (b[0] - a[0]) + (b[1] - a[1]) * (b[1] - a[1]);
    }
    int k = 0;
    if (l[1] < l[k]) k = 1;
    if (l[2] < l[k]) k = 2;
    ev.d2 = l[k];
    ev.short_a = v[(k + 1) % 3];
    ev.short_b = v[(k + 2) % 3];
    const double* apex = p[k];
    const double* x = p[(k + 1) % 3];
    const double* y = p[(k + 2) % 3];
    const double ux = x[0] - apex[0], uy = x[1] - apex[1];
    const double wx = y[0] - apex[0], wy = y[1] - apex[1];
    const double dot = ux * wx + uy * wy;
    const double cross = ux * wy - uy * wx;  // twice the area
    const double lu = l[(k + 2) % 3], lw = l[(k + 1) % 3];
    const double cos2 = dot > 0 ? dot * dot / (lu * lw) : 0.0;
    bool angle_bad = false;
    if (angle_on_ && cos2 > cos2_bound_) {
      angle_bad = true;
      // §3.6, first strategy: a triangle with a vertex inside a segment only needs
      // circumradius / shortest edge <= sqrt(2) (20.7 degrees).
      if (params_.relaxed_boundary && cos2 <= kCos2Of20_7 &&
          ((kind_[v[0]] | kind_[v[1]] | kind_[v[2]]) & kSegmentVertex))
        angle_bad = false;
    }
    if (params_.chew) {
      // Chew's first algorithm: circumradius above h. R^2 = l0 l1 l2 / (4 cross^2).
      if (l[0] * l[1] * l[2] > 4.0 * cross * cross * chew_h2_) angle_bad = true;
    }
    if (size_on_) {
      const double cx = (p[0][0] + p[1][0] + p[2][0]) / 3.0;
      const double cy = (p[0][1] + p[1][1] + p[2][1]) / 3.0;
      const double bound = area_bound(t, cx, cy);
      if (bound > 0 && 0.5 * cross > bound) ev.size_bad = true;
    }
    if (!angle_bad && !ev.size_bad) return ev;
    ev.bad = true;
    if (angle_bad && !ev.size_bad) {
      // Both edges at the smallest angle are subsegments: an input angle, not fixable.
      ev.small_input_angle = tri_.subseg(t, next3(static_cast<std::uint32_t>(k))) &&
                             tri_.subseg(t, prev3(static_cast<std::uint32_t>(k)));
    }
    // Circumradius-to-shortest-edge ratio: rho^2 = 1 / (4 sin^2) = 1 / (4 (1 - cos^2)).
    const double sin2 = 1.0 - cos2;
    const double rho2 = sin2 > 0 ? 0.25 / sin2 : 1e300;
    if (ev.size_bad) {
      ev.bucket = 64;
    } else if (rho2 > 0.64) {
      const int b = static_cast<int>(std::log2(rho2 / 0.64) * 4.0);
      ev.bucket = 63 - std::clamp(b, 0, 63);
    } else {
      ev.bucket = 64;
    }
    return ev;
  }

  void retry(std::uint32_t t, int bucket) {
    retry_[t] = tri_.points.size();
    push(t, bucket);
  }

  void enqueue(std::uint32_t t) {
    const Eval ev = evaluate(t);
    if (!ev.bad || ev.small_input_angle) return;
    push(t, ev.bucket);
  }

  void push(std::uint32_t t, int bucket) {
    buckets_[bucket].push_back(t);
    if (bucket < 64) nonempty_ |= (1ull << bucket);
  }

  std::uint32_t pop() {
    // Too-large triangles first, then skinny ones, worst bucket first: splitting for
    // size first leaves fewer triangles and lets angle-driven vertices start at the final
    // scale. The size bucket is a stack: depth-first splitting stays in cache (30% faster
    // on A.poly than a FIFO, same triangle count).
    if (!buckets_[64].empty()) {
      const std::uint32_t t = buckets_[64].back();
      buckets_[64].pop_back();
      return t;
    }
    if (nonempty_ == 0) return kNone;
    const int b = __builtin_ctzll(nonempty_);
    auto& q = buckets_[b];
    std::size_t& h = heads_[b];
    if (h >= q.size()) return kNone;
    const std::uint32_t t = q[h++];
    if (h == q.size()) {
      q.clear();
      h = 0;
      nonempty_ &= ~(1ull << b);
    }
    return t;
  }

  // ---- subsegments -------------------------------------------------------------

  bool corner(std::uint32_t v) const {
    return (kind_[v] & (kInputVertex | kCornerVertex)) == (kInputVertex | kCornerVertex);
  }

  // Fraction of a->b at which the subsegment is split (concentric shells at corners).
  double split_fraction(std::uint32_t a, std::uint32_t b) const {
    const bool ca = corner(a), cb = corner(b);
    if (!ca && !cb) return 0.5;
    const double dx = P(b)[0] - P(a)[0], dy = P(b)[1] - P(a)[1];
    const double len = std::sqrt(dx * dx + dy * dy);
    double p2 = 1.0;
    while (len > 3.0 * p2) p2 *= 2.0;
    while (len < 1.5 * p2) p2 *= 0.5;
    const double f = p2 / len;
    return cb ? 1.0 - f : f;
  }

  void split_encroached() {
    while (!segq_.empty()) {
      const SegWork w = segq_.back();
      segq_.pop_back();
      if (out_of_budget()) {
        segq_.clear();
        return;
      }
      split_subsegment(w.a, w.b, w.forced, -1.0, w.anchor);
    }
  }

  bool encroached_now(std::uint32_t e) const {
    const std::uint32_t t = e / 3, i = e % 3;
    const std::uint32_t o = tri_.tn[e];
    const double* a = P(tri_.org(t, i));
    const double* b = P(tri_.dest(t, i));
    if (tri_.in_domain(t) && predicates::dot2d(a, b, P(tri_.vertex(t, i))) != Sign::Positive)
      return true;
    const std::uint32_t u = o / 3;
    return tri_.in_domain(u) && predicates::dot2d(a, b, P(tri_.tv[o])) != Sign::Positive;
  }

  // Splits subsegment a-b at `fraction` (negative: shells / midpoint). Returns the new
  // vertex or kNone.
  std::uint32_t split_subsegment(std::uint32_t a, std::uint32_t b, bool forced, double fraction,
                                 float anchor) {
    const std::uint32_t e = tri_.find_edge(a, b);
    if (e == kNone || !tri_.subseg(e / 3, e % 3)) return kNone;
    if (!forced && !encroached_now(e)) return kNone;
    const double f = fraction > 0 ? fraction : split_fraction(a, b);
    const Point2 pa = tri_.points[a], pb = tri_.points[b];
    const Point2 pv = {pa[0] + f * (pb[0] - pa[0]), pa[1] + f * (pb[1] - pa[1])};
    if (pv == pa || pv == pb) return kNone;  // floating-point collapse: give up
    const auto v = static_cast<std::uint32_t>(tri_.points.size());
    tri_.points.push_back(pv);
    const std::uint32_t seeds[2] = {e / 3, tri_.tn[e] / 3};
    if (!tri_.find_cavity(v, seeds, 2, true)) {
      tri_.points.pop_back();
      return kNone;
    }
    const auto radius = static_cast<float>(nearest_boundary_distance(v));
    if (radius < floor_ || (!forced && anchor > 0 && radius < anchor_factor_ * anchor)) {
      // Below the resolution floor, or would shrink its encroacher's chain (bounds above
      // 30 degrees).
      tri_.abandon_cavity();
      tri_.points.pop_back();
      return kNone;
    }
    const std::uint32_t owner = owners_.get(a, b);
    anchor_.push_back(std::max(anchor, radius));
    kind_.push_back(kSegmentVertex);
    interpolate_attributes(v, {a, b, a}, {1.0 - f, f, 0.0});
    tri_.commit_cavity(v);
    ++outcome_.steiner_points;
    owners_.erase(a, b);
    owners_.set(a, v, owner);
    owners_.set(v, b, owner);
    for (std::uint32_t t : tri_.new_tris()) {
      // t = (x, y, v): edge 0 = y->v, edge 1 = v->x.
      const std::uint32_t x = tri_.tv[3 * t], y = tri_.tv[3 * t + 1];
      if (y == a || y == b) tri_.set_subseg(t, 0, true);
      if (x == a || x == b) tri_.set_subseg(t, 1, true);
    }
    after_insert(true);
    return v;
  }

  // Appends the attributes of new vertex v as a weighted sum of those of `from`.
  void interpolate_attributes(std::uint32_t v, const std::array<std::uint32_t, 3>& from,
                              const std::array<double, 3>& weight) {
    std::vector<double>* attr = params_.attributes;
    const auto n = static_cast<std::size_t>(params_.num_attributes);
    if (attr == nullptr || n == 0) return;
    attr->resize((static_cast<std::size_t>(v) + 1) * n, 0.0);
    for (std::size_t k = 0; k < n; ++k) {
      double value = 0;
      for (int i = 0; i < 3; ++i) value += weight[i] * (*attr)[from[i] * n + k];
      (*attr)[v * n + k] = value;
    }
  }

  double nearest_boundary_distance(std::uint32_t v) const {
    double best = 1e300;
    const double* pv = P(v);
    for (const auto& e : tri_.cavity_boundary()) {
      if (e.a == kGhost) continue;
      const double* q = P(e.a);
      const double d = (q[0] - pv[0]) * (q[0] - pv[0]) + (q[1] - pv[1]) * (q[1] - pv[1]);
      best = std::min(best, d);
    }
    return std::sqrt(best);
  }

  void after_insert(bool check_encroachment) {
    for (std::uint32_t t : tri_.new_tris()) {
      if (!tri_.in_domain(t)) continue;
      if (check_encroachment) {
        for (std::uint32_t i = 0; i < 3; ++i) {
          if (!tri_.subseg(t, i)) continue;
          const std::uint32_t a = tri_.org(t, i), b = tri_.dest(t, i);
          const std::uint32_t w = tri_.vertex(t, i);
          if (predicates::dot2d(P(a), P(b), P(w)) != Sign::Positive)
            segq_.push_back({a, b, false, strict_ ? anchor_[w] : -1.0f});
        }
      }
      enqueue(t);
    }
  }

  // ---- the Quitter ----------------------------------------------------------------

  // May subsegment a-b, encroached by the rejected circumcenter of a triangle with
  // evaluation `ev`, be split?
  bool may_split(std::uint32_t a, std::uint32_t b, const Eval& ev, double anchor) {
    const double dx = P(b)[0] - P(a)[0], dy = P(b)[1] - P(a)[1];
    const double len = std::sqrt(dx * dx + dy * dy);
    const double f = split_fraction(a, b);
    const double rv = len * std::min(f, 1.0 - f);
    if (rv < floor_) return false;
    if (ev.size_bad) return true;
    if (rv < anchor_factor_ * anchor) return false;
    const bool sa = (kind_[a] & kSmallAngleVertex) != 0;
    const bool sb = (kind_[b] & kSmallAngleVertex) != 0;
    if (sa == sb) return true;
    const std::uint32_t apex = sa ? a : b;
    const std::uint32_t far = sa ? b : a;
    collect_fan(tri_, apex, fan_);
    const std::size_t n = fan_.size();
    std::size_t k = n;
    for (std::size_t i = 0; i < n; ++i)
      if (fan_[i].other == far) k = i;
    if (k == n || n < 2) return true;
    // The cluster: neighbours reachable through in-domain wedges narrower than 60 deg.
    std::vector<std::size_t>& cl = cluster_;
    cl.assign(1, k);
    double min_gap = 2 * kPi;
    for (std::size_t step = 1, i = k; step < n; ++step) {  // counterclockwise
      const std::size_t j = (i + 1) % n;
      const double g = ccw_gap(fan_[i].angle, fan_[j].angle);
      if (!fan_[i].wedge_in_domain || g >= kSixtyDeg) break;
      min_gap = std::min(min_gap, g);
      cl.push_back(j);
      i = j;
    }
    for (std::size_t step = 1, i = k; step < n; ++step) {  // clockwise
      const std::size_t j = (i + n - 1) % n;
      const double g = ccw_gap(fan_[j].angle, fan_[i].angle);
      if (!fan_[j].wedge_in_domain || g >= kSixtyDeg) break;
      if (std::find(cl.begin(), cl.end(), j) != cl.end()) break;
      min_gap = std::min(min_gap, g);
      cl.push_back(j);
      i = j;
    }
    double rmin = 1e300;
    const double* pa = P(apex);
    for (std::size_t idx : cl) {
      const double* q = P(fan_[idx].other);
      const double l = std::sqrt((q[0] - pa[0]) * (q[0] - pa[0]) + (q[1] - pa[1]) * (q[1] - pa[1]));
      if (!is_power_of_two_length(l)) return true;
      if (l >= len * (1 - 1e-12)) rmin = std::min(rmin, 0.5 * l);
    }
    if (cl.size() > 1) rmin *= std::min(1.0, 2.0 * std::sin(0.5 * min_gap));
    return rmin * rmin >= ev.d2;
  }

  // ---- triangles --------------------------------------------------------------------

  void split_triangle(std::uint32_t t, const Eval& ev) {
    const double* pa = P(tri_.tv[3 * t]);
    const double* pb = P(tri_.tv[3 * t + 1]);
    const double* pc = P(tri_.tv[3 * t + 2]);
    const double xa = pb[0] - pa[0], ya = pb[1] - pa[1];
    const double xb = pc[0] - pa[0], yb = pc[1] - pa[1];
    const double den = 2.0 * (xa * yb - ya * xb);
    if (!(den > 0)) return;
    const double la = xa * xa + ya * ya, lb = xb * xb + yb * yb;
    const double ox = (yb * la - ya * lb) / den, oy = (xa * lb - xb * la) / den;
    Point2 c = {pa[0] + ox, pa[1] + oy};
    if (!std::isfinite(c[0]) || !std::isfinite(c[1])) return;
    double radius = std::sqrt(ox * ox + oy * oy);
    if (params_.off_centers && angle_on_ && !ev.size_bad) {
      // Off-center (Üngör 2004): on the bisector of the shortest edge pq, no farther from
      // pq than the point that makes pq's new triangle meet the angle bound exactly.
      const double* p = P(ev.short_a);
      const double* q = P(ev.short_b);
      const double mx = 0.5 * (p[0] + q[0]), my = 0.5 * (p[1] + q[1]);
      const double dx = c[0] - mx, dy = c[1] - my;
      const double dist = std::sqrt(dx * dx + dy * dy);
      const double h = 0.5 * std::sqrt(ev.d2) / std::tan(0.5 * theta_);
      if (dist > h && dist > 0) {
        c = {mx + dx * h / dist, my + dy * h / dist};
        radius = std::sqrt((c[0] - p[0]) * (c[0] - p[0]) + (c[1] - p[1]) * (c[1] - p[1]));
      }
    }
    // Size-driven vertices are roots (anchor 0): their radii are bounded by the area bounds.
    // A subsegment split for this circumcenter continues the parent's chain.
    float anchor = ev.size_bad ? 0.0f : static_cast<float>(radius);
    float split_anchor = -1.0f;
    if (!ev.size_bad) {
      const float parent = anchor_[std::max(ev.short_a, ev.short_b)];
      if (radius < anchor_factor_ * parent) return;  // would shrink the chain: give up
      anchor = std::max(anchor, parent);
      split_anchor = parent;
    }
    const Location loc = tri_.locate(c, t, true);
    if (loc.kind == Location::OnVertex) return;
    if (loc.kind == Location::Blocked) {
      const std::uint32_t a = tri_.org(loc.tri, loc.edge), b = tri_.dest(loc.tri, loc.edge);
      if (params_.chew) {
        if (chew_may_split(a, b)) {
          segq_.push_back({a, b, true, -1.0f});
          retry(t, ev.bucket);
        }
        return;
      }
      if (may_split(a, b, ev, split_anchor)) {
        segq_.push_back({a, b, true, split_anchor});
        retry(t, ev.bucket);
      }
      return;
    }
    const auto v = static_cast<std::uint32_t>(tri_.points.size());
    tri_.points.push_back(c);
    if (!tri_.find_cavity(v, &loc.tri, 1, true)) {
      tri_.points.pop_back();
      return;
    }
    if (!params_.chew) {
      encroached_.clear();
      for (const auto& e : tri_.cavity_boundary()) {
        const std::uint32_t o = e.outer;
        if (!((tri_.tf[o / 3] >> (o % 3)) & 1u)) continue;
        if (predicates::dot2d(P(e.a), P(e.b), P(v)) != Sign::Positive) encroached_.push_back({e.a, e.b});
      }
      if (!encroached_.empty()) {
        tri_.abandon_cavity();
        tri_.points.pop_back();
        bool any = false;
        for (const auto& s : encroached_) {
          if (may_split(s[0], s[1], ev, split_anchor)) {
            segq_.push_back({s[0], s[1], true, split_anchor});
            any = true;
          }
        }
        if (any) retry(t, ev.bucket);
        return;
      }
    }
    // The actual insertion radius (distance to the new vertex's Delaunay neighbours),
    // which rounding can make much smaller than the circumradius in degenerate spots.
    const double actual = nearest_boundary_distance(v);
    if (actual < floor_ || (!ev.size_bad && actual < anchor_factor_ * split_anchor)) {
      tri_.abandon_cavity();
      tri_.points.pop_back();
      return;
    }
    if (!ev.size_bad) anchor = std::max(split_anchor, static_cast<float>(actual));
    anchor_.push_back(anchor);
    kind_.push_back(kFreeVertex);
    if (params_.attributes != nullptr) {
      // Linear interpolation in the triangle that contains the new vertex.
      const std::uint32_t tc = loc.tri;
      const std::array<std::uint32_t, 3> w = {tri_.tv[3 * tc], tri_.tv[3 * tc + 1],
                                              tri_.tv[3 * tc + 2]};
      const auto area2 = [&](const double* x, const double* y, const double* z) {
        return (y[0] - x[0]) * (z[1] - x[1]) - (y[1] - x[1]) * (z[0] - x[0]);
      };
      const double whole = area2(P(w[0]), P(w[1]), P(w[2]));
      const double* pn = c.data();
      interpolate_attributes(v, w,
                             {area2(pn, P(w[1]), P(w[2])) / whole,
                              area2(P(w[0]), pn, P(w[2])) / whole,
                              area2(P(w[0]), P(w[1]), pn) / whole});
    }
    tri_.commit_cavity(v);
    ++outcome_.steiner_points;
    after_insert(params_.chew);
  }

  // ---- Chew's first algorithm ---------------------------------------------------------

  bool chew_may_split(std::uint32_t a, std::uint32_t b) const {
    const double dx = P(b)[0] - P(a)[0], dy = P(b)[1] - P(a)[1];
    return dx * dx + dy * dy >= 4.0 * chew_h2_;
  }

  // h = shortest edge of the initial triangulation; subsegments are divided into pieces
  // of length between h and sqrt(3) h.
  void prepare_chew() {
    double h2 = 1e300;
    std::vector<std::array<std::uint32_t, 2>> subsegs;
    for (std::uint32_t t = 0; t < tri_.num_slots(); ++t) {
      if (!tri_.in_domain(t)) continue;
      for (std::uint32_t i = 0; i < 3; ++i) {
        const double* a = P(tri_.org(t, i));
        const double* b = P(tri_.dest(t, i));
        h2 = std::min(h2, (b[0] - a[0]) * (b[0] - a[0]) + (b[1] - a[1]) * (b[1] - a[1]));
        if (tri_.subseg(t, i) && (!tri_.in_domain(tri_.tn[3 * t + i] / 3) ||
                                  tri_.org(t, i) < tri_.dest(t, i)))
          subsegs.push_back({tri_.org(t, i), tri_.dest(t, i)});
      }
    }
    chew_h2_ = h2;
    const double h = std::sqrt(h2);
    for (auto [a, b] : subsegs) {
      const double dx = P(b)[0] - P(a)[0], dy = P(b)[1] - P(a)[1];
      const double len = std::sqrt(dx * dx + dy * dy);
      auto pieces = static_cast<long long>(std::ceil(len / (std::sqrt(3.0) * h)));
      while (pieces > 1) {
        const std::uint32_t v =
            split_subsegment(a, b, true, 1.0 / static_cast<double>(pieces), -1.0f);
        if (v == kNone) break;
        a = v;
        --pieces;
      }
    }
  }

  Triangulation& tri_;
  mesh2d::SubsegmentOwners& owners_;
  std::vector<std::uint8_t>& kind_;
  const RefineParams& params_;
  RefineOutcome outcome_;
  bool angle_on_ = false;
  bool strict_ = false;  ///< bound above 30 degrees: encroachment splits inherit anchors
  double anchor_factor_ = kAnchorFactorUpTo30;
  double theta_ = 0;
  bool size_on_ = false;
  double cos2_bound_ = 1.0;
  double chew_h2_ = 0.0;
  std::unordered_map<std::uint32_t, std::size_t> retry_;  ///< triangle -> vertex count
  double floor_ = 0.0;
  std::vector<float> anchor_;  ///< per vertex: largest insertion radius along its ancestors
  std::vector<SegWork> segq_;
  std::array<std::vector<std::uint32_t>, 65> buckets_;  ///< 64 FIFO buckets + size stack
  std::array<std::size_t, 64> heads_{};
  std::uint64_t nonempty_ = 0;
  std::vector<std::array<std::uint32_t, 2>> encroached_;
  std::vector<FanEdge> fan_;
  std::vector<std::size_t> cluster_;
};

}  // namespace

void classify_input_vertices(const Triangulation& tri, std::vector<std::uint8_t>& kind) {
  std::vector<FanEdge> fan;
  for (std::uint32_t v = 0; v < kind.size() && v < tri.points.size(); ++v) {
    if (!(kind[v] & kInputVertex)) continue;
    collect_fan(tri, v, fan);
    if (fan.size() < 2) continue;
    kind[v] |= kCornerVertex;
    for (std::size_t i = 0; i < fan.size(); ++i) {
      const FanEdge& e = fan[i];
      const FanEdge& nx = fan[(i + 1) % fan.size()];
      if (e.wedge_in_domain && ccw_gap(e.angle, nx.angle) < kSixtyDeg) kind[v] |= kSmallAngleVertex;
    }
  }
}

RefineOutcome refine(Triangulation& tri, mesh2d::SubsegmentOwners& owners,
                     std::vector<std::uint8_t>& kind, const RefineParams& params) {
  Refiner refiner(tri, owners, kind, params);
  return refiner.run();
}

}  // namespace delmesh::tri2d
