// Local feature size of the input vertices: gaps to the nearest features (see feature_size.h).
#include "refiners/tet3d/feature_size.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <span>
#include <utility>
#include <vector>

namespace delmesh::tet3d {

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();
constexpr std::size_t kLeafSize = 4;

/// A segment (c == kNone) or a triangle of facet `facet` (kNone for a segment).
/// Its bounding box is kept in single precision, rounded outwards, so it still contains
/// the primitive: 40 bytes per primitive instead of 64 (the preparation's peak memory is
/// in feature_gaps). The box only prunes the search, whose distances are computed from
/// the vertices in double precision, so the gaps are the same.
struct Primitive {
  std::array<std::uint32_t, 3> v;
  std::uint32_t facet;
  Eigen::Vector3f lo, hi;
};
static_assert(sizeof(Primitive) == 40);

/// A node's box is the union of its primitives' single precision boxes, so it is kept
/// in single precision too: exactly the same box in 36 bytes instead of 64.
struct Node {
  Eigen::Vector3f lo, hi;
  std::uint32_t begin, end;  ///< primitive range (leaf) or children (left = this + 1)
  std::uint32_t right;       ///< right child, 0 for a leaf
};
static_assert(sizeof(Node) == 36);

Vec3 closest_on_segment(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 ab = b - a;
  const double len2 = ab.squaredNorm();
  if (!(len2 > 0.0)) return a;
  const double t = std::clamp((p - a).dot(ab) / len2, 0.0, 1.0);
  return a + t * ab;
}

/// Closest point of triangle abc to p (Ericson, Real-Time Collision Detection §5.1.5);
/// degenerate triangles fall back to their edges.
Vec3 closest_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  if (!(ab.cross(ac).squaredNorm() > 0.0)) {
    const Vec3 q1 = closest_on_segment(p, a, b), q2 = closest_on_segment(p, b, c), q3 = closest_on_segment(p, c, a);
    const double d1 = (p - q1).squaredNorm(), d2 = (p - q2).squaredNorm(), d3 = (p - q3).squaredNorm();
    return d1 <= d2 && d1 <= d3 ? q1 : (d2 <= d3 ? q2 : q3);
  }
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0.0 && d2 <= 0.0) return a;
  const Vec3 bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0.0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) return a + (d1 / (d1 - d3)) * ab;
  const Vec3 cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0.0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) return a + (d2 / (d2 - d6)) * ac;
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0) return b + ((d4 - d3) / ((d4 - d3) + (d5 - d6))) * (c - b);
  const double denom = 1.0 / (va + vb + vc);
  return a + ab * (vb * denom) + ac * (vc * denom);
}

double box_distance2(const Vec3& p, const Vec3& lo, const Vec3& hi) {
  const Vec3 d = (lo - p).cwiseMax(p - hi).cwiseMax(Vec3::Zero());
  return d.squaredNorm();
}

/// x rounded to a float no greater (round_up: no smaller) than x.
float round_float(double x, bool round_up) {
  const float f = static_cast<float>(x);
  if (round_up ? static_cast<double>(f) < x : static_cast<double>(f) > x)
    return std::nextafter(f, round_up ? std::numeric_limits<float>::infinity() : -std::numeric_limits<float>::infinity());
  return f;
}

class FeatureTree {
 public:
  FeatureTree(const RefineState& state, std::vector<Primitive> prims) : state_(state), prims_(std::move(prims)) {
    // A median split leaves at least two primitives per leaf, so a tree has fewer nodes
    // than primitives: no reallocation while it is built.
    nodes_.reserve(prims_.size());
    if (!prims_.empty()) build(0, static_cast<std::uint32_t>(prims_.size()));
  }

  /// Squared distance from input vertex v to the nearest primitive not excluded (a
  /// segment with an end w where stamp[w] == mark, a triangle of a facet f where
  /// facet_near[f] == mark) when it is below `bound2`, else infinity.
  double nearest2(std::uint32_t v, std::uint32_t mark, const std::vector<std::uint32_t>& stamp,
                  const std::vector<std::uint32_t>& facet_near, double bound2) const {
    double best = bound2;
    if (nodes_.empty()) return kInfinity;
    const Vec3& p = state_.mesh.point(v);
    // Nodes to visit with the squared distance from p to their boxes (computed once, when
    // pushed); best only decreases, so a node at least best away when pushed is skipped.
    auto& stack = stack_;
    stack.assign(1, {0, box_distance2(p, nodes_[0].lo.cast<double>(), nodes_[0].hi.cast<double>())});
    while (!stack.empty()) {
      const auto [id, distance2] = stack.back();
      stack.pop_back();
      if (distance2 >= best) continue;
      const Node& n = nodes_[id];
      if (n.right == 0) {
        for (std::uint32_t i = n.begin; i < n.end; ++i) {
          const Primitive& q = prims_[i];
          if (box_distance2(p, q.lo.cast<double>(), q.hi.cast<double>()) >= best || excluded(q, mark, stamp, facet_near))
            continue;
          const Vec3 c = q.facet == kNone
                             ? closest_on_segment(p, state_.mesh.point(q.v[0]), state_.mesh.point(q.v[1]))
                             : closest_on_triangle(p, state_.mesh.point(q.v[0]), state_.mesh.point(q.v[1]),
                                                   state_.mesh.point(q.v[2]));
          best = std::min(best, (p - c).squaredNorm());
        }
        continue;
      }
      const std::uint32_t left = id + 1, right = n.right;
      const double dl = box_distance2(p, nodes_[left].lo.cast<double>(), nodes_[left].hi.cast<double>());
      const double dr = box_distance2(p, nodes_[right].lo.cast<double>(), nodes_[right].hi.cast<double>());
      // The nearer child on top.
      if (dl < dr) {
        if (dr < best) stack.push_back({right, dr});
        if (dl < best) stack.push_back({left, dl});
      } else {
        if (dl < best) stack.push_back({left, dl});
        if (dr < best) stack.push_back({right, dr});
      }
    }
    return best < bound2 ? best : kInfinity;
  }

 private:
  static bool excluded(const Primitive& q, std::uint32_t mark, const std::vector<std::uint32_t>& stamp,
                       const std::vector<std::uint32_t>& facet_near) {
    if (q.facet == kNone) return stamp[q.v[0]] == mark || stamp[q.v[1]] == mark;
    return facet_near[q.facet] == mark;
  }

  std::uint32_t build(std::uint32_t begin, std::uint32_t end) {
    const std::uint32_t id = static_cast<std::uint32_t>(nodes_.size());
    nodes_.push_back({Eigen::Vector3f::Zero(), Eigen::Vector3f::Zero(), 0, 0, 0});
    Eigen::Vector3f lo = prims_[begin].lo, hi = prims_[begin].hi;
    for (std::uint32_t i = begin + 1; i < end; ++i) {
      lo = lo.cwiseMin(prims_[i].lo);
      hi = hi.cwiseMax(prims_[i].hi);
    }
    std::uint32_t right = 0;
    if (end - begin > kLeafSize) {
      int axis = 0;
      (hi - lo).maxCoeff(&axis);
      const std::uint32_t mid = begin + (end - begin) / 2;
      std::nth_element(prims_.begin() + begin, prims_.begin() + mid, prims_.begin() + end,
                       [axis](const Primitive& x, const Primitive& y) { return x.lo[axis] + x.hi[axis] < y.lo[axis] + y.hi[axis]; });
      build(begin, mid);
      right = build(mid, end);
    }
    nodes_[id] = {lo, hi, begin, end, right};
    return id;
  }

  const RefineState& state_;
  std::vector<Primitive> prims_;
  std::vector<Node> nodes_;
  /// nearest2's nodes to visit and their squared distances (kept from one query to the
  /// next: no allocation per query).
  mutable std::vector<std::pair<std::uint32_t, double>> stack_;
};

Primitive make_primitive(const RefineState& state, std::array<std::uint32_t, 3> v, std::uint32_t facet) {
  const int n = facet == kNone ? 2 : 3;
  Vec3 lo = state.mesh.point(v[0]), hi = lo;
  for (int i = 1; i < n; ++i) {
    lo = lo.cwiseMin(state.mesh.point(v[i]));
    hi = hi.cwiseMax(state.mesh.point(v[i]));
  }
  Primitive q{v, facet, {}, {}};
  for (int k = 0; k < 3; ++k) {
    q.lo[k] = round_float(lo[k], false);
    q.hi[k] = round_float(hi[k], true);
  }
  return q;
}

/// Lists of ids per owner in one array: list i is ids[start[i] .. start[i + 1]).
struct Incidence {
  std::vector<std::uint32_t> start, ids;
  std::span<const std::uint32_t> of(std::size_t i) const { return {ids.data() + start[i], ids.data() + start[i + 1]}; }
};

/// The items at each of `owners` owners, in increasing item order: `each(item, emit)`
/// calls emit(owner) for every owner of item (0 .. items - 1); a counting pass, then a
/// filling pass.
template <class Each>
Incidence incidence(std::size_t owners, std::size_t items, Each each) {
  Incidence out;
  out.start.assign(owners + 1, 0);
  for (std::uint32_t i = 0; i < items; ++i) each(i, [&](std::uint32_t owner) { ++out.start[owner + 1]; });
  for (std::size_t o = 0; o < owners; ++o) out.start[o + 1] += out.start[o];
  out.ids.resize(out.start[owners]);
  std::vector<std::uint32_t> fill(out.start.begin(), out.start.end() - 1);
  for (std::uint32_t i = 0; i < items; ++i) each(i, [&](std::uint32_t owner) { out.ids[fill[owner]++] = i; });
  return out;
}

}  // namespace

std::vector<double> nearest_vertex_distances(const RefineState& state) {
  std::vector<double> nearest(state.mesh.num_vertices(), kInfinity);
  for (std::uint32_t t = 0; t < state.mesh.tet_slots(); ++t) {
    if (state.mesh.is_dead(t) || state.mesh.is_infinite(t)) continue;
    const auto& v = state.mesh.tet(t).v;
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j) {
        const double d = (state.mesh.point(v[i]) - state.mesh.point(v[j])).norm();
        nearest[v[i]] = std::min(nearest[v[i]], d);
        nearest[v[j]] = std::min(nearest[v[j]], d);
      }
  }
  return nearest;
}

FeatureGaps feature_gaps(const RefineState& state, std::size_t input_vertices, const std::vector<double>* below) {
  const std::size_t n = state.mesh.num_vertices();
  FeatureGaps gaps;
  gaps.separate.assign(n, kInfinity);
  gaps.adjacent.assign(n, kInfinity);
  // Incidences: the segments and the facets at each vertex, the vertices of each facet,
  // each as one array with offsets (list i is ids[start[i] .. start[i + 1])) rather than
  // a vector per vertex and per facet.
  const Incidence segments_of = incidence(n, state.segments.size(), [&](std::uint32_t s, auto&& emit) {
    emit(state.segments[s].a);
    emit(state.segments[s].b);
  });
  Incidence facet_vertices;
  facet_vertices.start.reserve(state.facets.size() + 1);
  facet_vertices.start.push_back(0);
  // Reserved at the exact count: the preparation's peak memory is here, and a doubled
  // array would leave its old half resident beside the new one.
  std::size_t prim_count = state.segments.size();
  for (const auto& facet : state.facets) prim_count += facet.subface_count();
  std::vector<Primitive> prims;
  prims.reserve(prim_count);
  for (const SegmentData& seg : state.segments) prims.push_back(make_primitive(state, {seg.a, seg.b, seg.b}, kNone));
  std::vector<std::uint32_t> fv;
  for (std::size_t f = 0; f < state.facets.size(); ++f) {
    const std::uint32_t facet = static_cast<std::uint32_t>(f);
    fv.clear();
    for (const Subface& t : state.facets[f].subfaces()) {
      prims.push_back(make_primitive(state, t, facet));
      fv.insert(fv.end(), t.begin(), t.end());
    }
    std::sort(fv.begin(), fv.end());
    fv.erase(std::unique(fv.begin(), fv.end()), fv.end());
    facet_vertices.ids.insert(facet_vertices.ids.end(), fv.begin(), fv.end());
    facet_vertices.start.push_back(static_cast<std::uint32_t>(facet_vertices.ids.size()));
  }
  const Incidence facets_of = incidence(n, state.facets.size(), [&](std::uint32_t f, auto&& emit) {
    for (const std::uint32_t v : facet_vertices.of(f)) emit(v);
  });
  const FeatureTree tree(state, std::move(prims));
  // stamp[w] == v: w is excluded with v; facet_near[f] == v: facet f is. Stamps are
  // vertex ids >= 1 (adjacent pass) or their complement (separate pass), 0 marks nothing.
  std::vector<std::uint32_t> stamp(n, 0), facet_near(state.facets.size(), 0);
  std::vector<std::uint32_t> star;
  for (std::uint32_t v = 1; v <= input_vertices && v < n; ++v) {
    // Gaps at least below[v] are not measured: squared, with a margin that keeps every
    // primitive whose distance rounds below below[v].
    const double bound2 = below ? (*below)[v] * (*below)[v] * (1.0 + 1e-9) : kInfinity;
    // Features containing v.
    stamp[v] = v;
    for (const std::uint32_t f : facets_of.of(v)) facet_near[f] = v;
    gaps.adjacent[v] = std::sqrt(tree.nearest2(v, v, stamp, facet_near, bound2));
    // Features sharing a vertex with v's star.
    const std::uint32_t mark = ~v;
    star.assign(1, v);
    for (const std::uint32_t s : segments_of.of(v)) {
      star.push_back(state.segments[s].a);
      star.push_back(state.segments[s].b);
    }
    for (const std::uint32_t f : facets_of.of(v)) {
      const auto vertices = facet_vertices.of(f);
      star.insert(star.end(), vertices.begin(), vertices.end());
    }
    for (const std::uint32_t w : star) stamp[w] = mark;
    for (const std::uint32_t w : star)
      for (const std::uint32_t f : facets_of.of(w)) facet_near[f] = mark;
    gaps.separate[v] = std::sqrt(tree.nearest2(v, mark, stamp, facet_near, bound2));
  }
  return gaps;
}

double floor_feature_size(double nearest, const FeatureGaps& gaps, std::uint32_t v) {
  double lfs = nearest;
  if (gaps.separate[v] > 0.0) lfs = std::min(lfs, gaps.separate[v]);
  if (gaps.adjacent[v] > 0.0) lfs = std::min(lfs, std::max(gaps.adjacent[v], kAdjacentGapShare * nearest));
  return lfs;
}

}  // namespace delmesh::tet3d
