// Joint move of the two vertices of a tet's worst edge (see joint_move.h; notes §2.2.4).
#include "refiners/tet3d/joint_move.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Core>

#include "toolkit/predicates/predicates.h"
#include "toolkit/quality/tet_quality.h"
#include "toolkit/tetmesh/tet_mesh.h"

namespace delmesh::tet3d {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
/// Iterations of Gilbert's algorithm for the minimum-norm point of the gradients' hull.
constexpr int kMinNormIterations = 64;

using Vec6 = Eigen::Matrix<double, 6, 1>;
constexpr std::size_t kNoWall = std::numeric_limits<std::size_t>::max();

/// What a wall of the ascent keeps (JointAscent::wall_at): a tet's radius-edge ratio under
/// the bound, its window dihedral sine above its floor (and its angles within their
/// limits), or an outside tet's orientation.
enum class WallKind : std::uint8_t { Bound, Angles, Orientation };

struct Wall {
  std::size_t tet = kNoWall;  ///< index into the union
  WallKind kind = WallKind::Bound;
  friend bool operator==(const Wall&, const Wall&) = default;
};

enum class Freedom { Free, Plane, Line };

/// The set a vertex moves in and the facets whose subfacets surround it.
struct Constraint {
  Freedom freedom = Freedom::Free;
  Vec3 origin = Vec3::Zero(), direction = Vec3::Zero(), span = Vec3::Zero();
  int axis_aligned = -1;
  std::vector<std::uint32_t> facets;
};

/// How a tet of the union enters the move (joint_move.h).
enum class Role : std::uint8_t {
  Outside,  ///< not in the domain: must stay positively oriented
  Free,     ///< touches no small angle: makes the objective
  Breaker,  ///< touches no small angle, inside the window, breaks a bound: stays inside
  Traded    ///< touches a small angle: the trade's floor, extremes and bounds
};

struct UnionTet {
  std::uint32_t tet = 0;
  int region = 0;
  std::array<Vec3, 4> p;
  int la = -1, lb = -1;  ///< local indices of a and b, -1 where absent
  Role role = Role::Free;
  bool kept_bounds = true;  ///< Role::Traded: kept the bounds before the move
  double lo_deg = 0.0, hi_deg = 180.0;  ///< Role::Traded: the angles it must stay within
};

Vec3 constrain(const Constraint& c, const Vec3& x) {
  switch (c.freedom) {
    case Freedom::Free:
      return x;
    case Freedom::Plane: {
      if (c.axis_aligned >= 0) {
        Vec3 p = x;
        p[c.axis_aligned] = c.origin[c.axis_aligned];
        return p;
      }
      return x - (x - c.origin).dot(c.direction) * c.direction;
    }
    case Freedom::Line: {
      const double t = (x - c.origin).dot(c.span) / c.span.squaredNorm();
      return c.origin + t * c.span;
    }
  }
  return x;
}

Vec3 tangent(const Constraint& c, const Vec3& g) {
  switch (c.freedom) {
    case Freedom::Free:
      return g;
    case Freedom::Plane:
      return g - g.dot(c.direction) * c.direction;
    case Freedom::Line:
      return g.dot(c.direction) * c.direction;
  }
  return g;
}

/// Minimum-norm point of the convex hull of the gradients (Gilbert's algorithm).
Vec6 min_norm_point(const std::vector<Vec6>& g) {
  Vec6 x = g.front();
  for (const Vec6& y : g)
    if (y.squaredNorm() < x.squaredNorm()) x = y;
  for (int iter = 0; iter < kMinNormIterations; ++iter) {
    const Vec6* best = &g.front();
    for (const Vec6& y : g)
      if (y.dot(x) < best->dot(x)) best = &y;
    const Vec6 step = *best - x;
    const double gap = -x.dot(step);
    if (gap <= 1e-12 * x.squaredNorm() || step.squaredNorm() == 0.0) break;
    x += std::clamp(gap / step.squaredNorm(), 0.0, 1.0) * step;
  }
  return x;
}

class JointAscent {
 public:
  JointAscent(RefineState& state, const JointMoveRules& rules, std::uint32_t a, std::uint32_t b)
      : state_(state), mesh_(state.mesh), rules_(rules), a_(a), b_(b) {}

  bool run(JointMove& move) {
    if (!movable(a_) || !movable(b_)) return false;
    if (!gather(a_, ca_, true) || !gather(b_, cb_, false)) return false;
    if (!classify()) return false;
    Vec3 pa = mesh_.point(a_), pb = mesh_.point(b_);
    const double start = objective(pa, pb);
    if (!(start > -kInf)) return false;
    const double end = ascend(pa, pb, start);
    if (!(end > start + rules_.min_gain) || !counts_kept(pa, pb)) return false;
    move.a = a_;
    move.b = b_;
    move.pa = pa;
    move.pb = pb;
    move.tets.clear();
    for (const UnionTet& u : tets_) move.tets.push_back(u.tet);
    return true;
  }

 private:
  bool touches_small_angle(std::uint32_t v) const {
    const std::vector<std::uint8_t>& small = *rules_.at_small_angle;
    return v < small.size() && small[v] != 0;
  }

  bool movable(std::uint32_t v) const {
    const VertexKind kind = state_.vertices[v].kind;
    return (kind == VertexKind::Interior || kind == VertexKind::OnFacet || kind == VertexKind::OnSegment) &&
           !touches_small_angle(v);
  }

  /// The star of v into tets_ (with `first`, anew) and its constraint into c; false when
  /// v may not move (as smoothing's gather_star in sliver_improvement.cpp, and a hull face
  /// that is not a subfacet).
  bool gather(std::uint32_t v, Constraint& c, bool first) {
    if (first) tets_.clear();
    c.facets.clear();
    mesh_.star(v, star_);
    for (const std::uint32_t t : star_) {
      const TetRecord& r = mesh_.tet(t);
      const int k = mesh_.infinite_index(t);
      if (k >= 0) {
        const auto& o = kFaceVertex[k];
        if (!subface_of(state_, r.v[o[0]], r.v[o[1]], r.v[o[2]])) return false;
        continue;
      }
      const int local = mesh_.local_index(t, v);
      for (int f = 0; f < 4; ++f) {
        if (f == local) continue;
        const auto& o = kFaceVertex[f];
        const std::uint32_t* facet = subface_of(state_, r.v[o[0]], r.v[o[1]], r.v[o[2]]);
        if (facet && std::find(c.facets.begin(), c.facets.end(), *facet) == c.facets.end())
          c.facets.push_back(*facet);
      }
      auto it = std::find_if(tets_.begin(), tets_.end(), [t](const UnionTet& u) { return u.tet == t; });
      if (it == tets_.end()) {
        UnionTet u;
        u.tet = t;
        u.region = t < state_.tet_region.size() ? state_.tet_region[t] : kRegionUnknown;
        for (int i = 0; i < 4; ++i) u.p[i] = mesh_.point(r.v[i]);
        tets_.push_back(u);
        it = tets_.end() - 1;
      }
      (first ? it->la : it->lb) = local;
    }
    const VertexInfo& info = state_.vertices[v];
    if (info.kind == VertexKind::Interior) {
      c.freedom = Freedom::Free;
      return c.facets.empty();
    }
    if (info.kind == VertexKind::OnFacet) {
      if (c.facets.size() != 1 || c.facets.front() != info.owner) return false;
      c.freedom = Freedom::Plane;
      const FacetTriangulation& facet = state_.facets[info.owner];
      c.direction = facet.normal().normalized();
      c.origin = state_.plc.points[state_.plc.facets[info.owner].polygons.front().front()];
      c.axis_aligned = -1;
      const Vec3& n = facet.normal();
      for (int i = 0; i < 3; ++i)
        if (n[i] != 0.0 && n[(i + 1) % 3] == 0.0 && n[(i + 2) % 3] == 0.0) c.axis_aligned = i;
      return true;
    }
    c.freedom = Freedom::Line;
    const SegmentData& seg = state_.segments[info.owner];
    c.origin = mesh_.point(seg.a);
    c.span = mesh_.point(seg.b) - c.origin;
    c.direction = c.span.normalized();
    return true;
  }

  /// The roles of the union's tets and the floors of the trade rules; false where no tet
  /// touching none makes an objective or a tet touching a small angle is flat.
  bool classify() {
    double held_sine = kInf;
    least_free_sine_ = kInf;
    bool any_free = false;
    for (UnionTet& u : tets_) {
      if (!in_domain(u.region)) {
        u.role = Role::Outside;
        continue;
      }
      const auto& p = u.p;
      const double sine = min_window_dihedral_sine(p[0], p[1], p[2], p[3], rules_.obtuse_scale);
      bool small = false;
      for (const std::uint32_t x : mesh_.tet(u.tet).v) small = small || touches_small_angle(x);
      if (small) {
        u.role = Role::Traded;
        held_sine = std::min(held_sine, sine);
        u.kept_bounds = !rules_.breaks_bounds(u.region, p[0], p[1], p[2], p[3]);
        const auto [smallest, largest] = dihedral_extremes_deg(p[0], p[1], p[2], p[3]);
        u.lo_deg = std::min(rules_.trade_min_deg, smallest);
        u.hi_deg = std::max(rules_.trade_max_deg, largest);
      } else if (rules_.quality(u.region, p[0], p[1], p[2], p[3]) < 0.0 && sine > 0.0 &&
                 !dihedral_outside(p[0], p[1], p[2], p[3], rules_.low_deg, rules_.high_deg)) {
        u.role = Role::Breaker;
      } else {
        u.role = Role::Free;
        u.kept_bounds = !rules_.breaks_bounds(u.region, p[0], p[1], p[2], p[3]);
        any_free = true;
        least_free_sine_ = std::min(least_free_sine_, sine);
      }
    }
    if (!any_free || !(held_sine > 0.0)) return false;
    traded_floor_ = held_sine < kInf ? rules_.trade_fraction * held_sine : 0.0;
    return true;
  }

  static std::array<Vec3, 4> at(const UnionTet& u, const Vec3& pa, const Vec3& pb) {
    std::array<Vec3, 4> q = u.p;
    if (u.la >= 0) q[u.la] = pa;
    if (u.lb >= 0) q[u.lb] = pb;
    return q;
  }

  /// A union tet's value with a at pa and b at pb: +inf for a tet outside the domain or a
  /// held tet keeping its rule, -inf for one breaking it (or flat), else the objective.
  double value(const UnionTet& u, const std::array<Vec3, 4>& q) const {
    if (u.role == Role::Outside) return signed_volume(q[0], q[1], q[2], q[3]) > 0.0 ? kInf : -kInf;
    const double sine = min_window_dihedral_sine(q[0], q[1], q[2], q[3], rules_.obtuse_scale);
    if (!(sine > 0.0)) return -kInf;
    switch (u.role) {
      case Role::Traded: {
        if (sine < traded_floor_) return -kInf;
        const auto [smallest, largest] = dihedral_extremes_deg(q[0], q[1], q[2], q[3]);
        if (smallest < u.lo_deg || largest > u.hi_deg) return -kInf;
        if (u.kept_bounds && rules_.breaks_bounds(u.region, q[0], q[1], q[2], q[3])) return -kInf;
        return kInf;
      }
      case Role::Breaker:
        return dihedral_outside(q[0], q[1], q[2], q[3], rules_.low_deg, rules_.high_deg) ? -kInf : kInf;
      case Role::Free:
        if (sine < least_free_sine_) return -kInf;
        if (u.kept_bounds && rules_.breaks_bounds(u.region, q[0], q[1], q[2], q[3])) return -kInf;
        return rules_.quality(u.region, q[0], q[1], q[2], q[3]);
      case Role::Outside:
        break;
    }
    return kInf;
  }

  /// The worst value over the union, into values_; -inf at the first tet breaking a rule.
  double objective(const Vec3& pa, const Vec3& pb) {
    values_.resize(tets_.size());
    double worst = kInf;
    for (std::size_t k = 0; k < tets_.size(); ++k) {
      values_[k] = value(tets_[k], at(tets_[k], pa, pb));
      if (values_[k] == -kInf) {
        broken_ = k;
        return -kInf;
      }
      worst = std::min(worst, values_[k]);
    }
    return worst;
  }

  /// Every tet of the union positively oriented and every subfacet around a and b
  /// counterclockwise in its facet, with a at pa and b at pb (exact predicates).
  bool valid(const Vec3& pa, const Vec3& pb) {
    for (const UnionTet& u : tets_) {
      const std::array<Vec3, 4> q = at(u, pa, pb);
      if (predicates::orient3d(q[0].data(), q[1].data(), q[2].data(), q[3].data()) != Sign::Positive) return false;
    }
    for (const std::uint32_t f : ca_.facets)
      if (!state_.facets[f].can_move_vertex(a_, pa)) return false;
    const Vec3 old_a = mesh_.point(a_);
    mesh_.move_point(a_, pa);  // the facet triangulations read the shared coordinates
    bool ok = true;
    for (const std::uint32_t f : cb_.facets) ok = ok && state_.facets[f].can_move_vertex(b_, pb);
    mesh_.move_point(a_, old_a);
    return ok;
  }

  /// Steepest ascent of the objective over both positions from (pa, pb), whose objective
  /// is `start`; on return the best point found; returns its objective.
  double ascend(Vec3& pa, Vec3& pb, double start) {
    double length = kInf;
    for (const UnionTet& u : tets_)
      for (int i = 0; i < 4; ++i) {
        if (u.la >= 0 && i != u.la) length = std::min(length, (u.p[i] - pa).norm());
        if (u.lb >= 0 && i != u.lb) length = std::min(length, (u.p[i] - pb).norm());
      }
    if (!(length > 0.0) || !std::isfinite(length)) return start;
    const double h = 1e-7 * length;
    double current = start;
    std::vector<double> current_values = values_;
    walls_.clear();
    for (int iter = 0; iter < kJointIterations; ++iter) {
      gradients_.clear();
      for (const Wall& w : walls_) gradients_.push_back(wall_gradient(w, pa, pb, h, length));
      for (std::size_t k = 0; k < tets_.size(); ++k) {
        const UnionTet& u = tets_[k];
        if (u.role != Role::Free) continue;
        if (current_values[k] > current + 0.02 * std::abs(current) + 1e-9) continue;
        gradients_.push_back(gradient(u, pa, pb, h, [this](const std::array<Vec3, 4>& q) {
          return min_window_dihedral_sine(q[0], q[1], q[2], q[3], rules_.obtuse_scale);
        }));
      }
      if (gradients_.empty()) break;
      const Vec6 d = min_norm_point(gradients_);
      const double norm = d.norm();
      if (!(norm > 0.0) || !std::isfinite(norm)) break;
      double alpha = 0.25 * length / norm;
      bool moved = false;
      Wall wall;
      for (int k = 0; k < kJointHalvings; ++k, alpha *= 0.5) {
        const Vec3 qa = constrain(ca_, pa + alpha * Vec3(d.segment<3>(0)));
        const Vec3 qb = constrain(cb_, pb + alpha * Vec3(d.segment<3>(3)));
        if (qa == pa && qb == pb) break;
        const double v = objective(qa, qb);
        wall = v == -kInf ? wall_at(broken_, qa, qb) : Wall{};
        if (v > current && valid(qa, qb)) {
          pa = qa;
          pb = qb;
          current = v;
          current_values = values_;
          moved = true;
          break;
        }
      }
      if (moved) continue;
      // The shortest step still broke a tet's rule: the measure that rule keeps joins the
      // directions to raise (a feasible direction along the wall), instead of ending the
      // ascent where it started.
      if (wall.tet == kNoWall || walls_.size() >= kJointWalls ||
          std::find(walls_.begin(), walls_.end(), wall) != walls_.end())
        break;
      walls_.push_back(wall);
    }
    return current;
  }

  /// The wall union tet k, which breaks its rule with a at pa and b at pb, sets: its
  /// radius-edge ratio where it kept the bounds and breaks one (is_bound_wall: a Free tet
  /// within its floor, or a Traded one), its orientation where it lies outside the domain,
  /// else its window dihedral sine (a Free tet below the least of them before, a Breaker
  /// leaving the window, a Traded tet below its floor or beyond its extreme angles).
  /// No wall where it is flat or inverted in the domain.
  Wall wall_at(std::size_t k, const Vec3& pa, const Vec3& pb) const {
    const UnionTet& u = tets_[k];
    if (u.role == Role::Outside) return {k, WallKind::Orientation};
    const auto q = at(u, pa, pb);
    if (!(min_window_dihedral_sine(q[0], q[1], q[2], q[3], rules_.obtuse_scale) > 0.0)) return {};
    if (is_bound_wall(k, pa, pb) ||
        (u.role == Role::Traded && u.kept_bounds && rules_.breaks_bounds(u.region, q[0], q[1], q[2], q[3])))
      return {k, WallKind::Bound};
    return {k, WallKind::Angles};
  }

  /// The direction wall w keeps, at (pa, pb): minus the gradient of its tet's radius-edge
  /// ratio, the gradient of its window dihedral sine, or that of its signed volume over
  /// length^3 (the scale of the sines' gradients, `length` the shortest edge at a or b).
  Vec6 wall_gradient(const Wall& w, const Vec3& pa, const Vec3& pb, double h, double length) const {
    const UnionTet& u = tets_[w.tet];
    switch (w.kind) {
      case WallKind::Bound:
        return gradient(u, pa, pb, h, [](const std::array<Vec3, 4>& q) { return -radius_edge_ratio(q[0], q[1], q[2], q[3]); });
      case WallKind::Angles:
        return gradient(u, pa, pb, h, [this](const std::array<Vec3, 4>& q) {
          return min_window_dihedral_sine(q[0], q[1], q[2], q[3], rules_.obtuse_scale);
        });
      case WallKind::Orientation:
        break;
    }
    const double cube = length * length * length;
    return gradient(u, pa, pb, h, [cube](const std::array<Vec3, 4>& q) { return signed_volume(q[0], q[1], q[2], q[3]) / cube; });
  }

  /// Does union tet k, Free and keeping the bounds, break them with a at pa and b at pb?
  bool is_bound_wall(std::size_t k, const Vec3& pa, const Vec3& pb) const {
    const UnionTet& u = tets_[k];
    if (u.role != Role::Free || !u.kept_bounds) return false;
    const auto q = at(u, pa, pb);
    return min_window_dihedral_sine(q[0], q[1], q[2], q[3], rules_.obtuse_scale) >= least_free_sine_ &&
           rules_.breaks_bounds(u.region, q[0], q[1], q[2], q[3]);
  }

  /// The gradient of f (a function of a tet's corners) for union tet u over both
  /// positions at (pa, pb), by central differences of step h, in their tangent spaces.
  template <typename F>
  Vec6 gradient(const UnionTet& u, const Vec3& pa, const Vec3& pb, double h, F f) const {
    Vec6 g = Vec6::Zero();
    for (int which = 0; which < 2; ++which) {
      if ((which == 0 ? u.la : u.lb) < 0) continue;
      Vec3 part;
      for (int c = 0; c < 3; ++c) {
        Vec3 plus_a = pa, minus_a = pa, plus_b = pb, minus_b = pb;
        (which == 0 ? plus_a : plus_b)[c] += h;
        (which == 0 ? minus_a : minus_b)[c] -= h;
        part[c] = (f(at(u, plus_a, plus_b)) - f(at(u, minus_a, minus_b))) / (2.0 * h);
      }
      g.segment<3>(3 * which) = tangent(which == 0 ? ca_ : cb_, part);
    }
    return g;
  }

  /// The count rules of a trade over the union: no more tets outside the window away from
  /// small angles, and more touching one only where fewer lie away from them or the least
  /// window dihedral sine of the tets touching one does not fall.
  bool counts_kept(const Vec3& pa, const Vec3& pb) const {
    std::array<std::size_t, 2> before{}, after{};
    double held_before = kInf, held_after = kInf;
    for (const UnionTet& u : tets_) {
      if (u.role == Role::Outside) continue;
      const int held = u.role == Role::Traded ? 1 : 0;
      const std::array<Vec3, 4> q = at(u, pa, pb);
      before[held] += dihedral_outside(u.p[0], u.p[1], u.p[2], u.p[3], rules_.low_deg, rules_.high_deg) ? 1 : 0;
      after[held] += dihedral_outside(q[0], q[1], q[2], q[3], rules_.low_deg, rules_.high_deg) ? 1 : 0;
      if (held) {
        held_before = std::min(held_before, min_window_dihedral_sine(u.p[0], u.p[1], u.p[2], u.p[3], rules_.obtuse_scale));
        held_after = std::min(held_after, min_window_dihedral_sine(q[0], q[1], q[2], q[3], rules_.obtuse_scale));
      }
    }
    return after[0] <= before[0] && (after[1] <= before[1] || after[0] < before[0] || held_after >= held_before);
  }

  RefineState& state_;
  TetMesh& mesh_;
  const JointMoveRules& rules_;
  std::uint32_t a_, b_;
  Constraint ca_, cb_;
  std::vector<UnionTet> tets_;
  std::vector<std::uint32_t> star_;
  std::vector<double> values_;
  std::vector<Vec6> gradients_;
  std::vector<Wall> walls_;  ///< union tets whose rule the ascent keeps (wall_at)
  std::size_t broken_ = 0;          ///< the tet at which objective() last returned -inf
  double least_free_sine_ = kInf;
  double traded_floor_ = 0.0;
};

}  // namespace

bool plan_joint_move(RefineState& state, const JointMoveRules& rules, std::uint32_t a, std::uint32_t b,
                     JointMove& move) {
  JointAscent ascent(state, rules, a, b);
  return ascent.run(move);
}

}  // namespace delmesh::tet3d
