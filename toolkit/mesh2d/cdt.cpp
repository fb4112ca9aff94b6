// Segment recovery by flips, crossing-segment splitting, and flood-fill removal of holes
// and concavities (see cdt.h).
#include "toolkit/mesh2d/cdt.h"

#include <algorithm>
#include <deque>
#include <unordered_map>
#include <unordered_set>
#include <string>
#include <utility>

#include "toolkit/predicates/predicates.h"

namespace delmesh::mesh2d {

using predicates::orient2d;

namespace {

struct Work {
  std::uint32_t a, b, seg;
};

class SegmentInserter {
 public:
  SegmentInserter(Triangulation& tri, SubsegmentOwners& owners, CdtStats& stats)
      : tri_(tri), owners_(owners), stats_(stats) {}

  Expected<void> run(const std::vector<std::array<std::uint32_t, 2>>& segments) {
    segments_ = &segments;
    // Exact duplicates (same two endpoints) are inserted once: the first one owns the
    // edges. (Inserting the second would walk along rounded crossing vertices of the
    // first and create a parallel constraint chain.)
    std::unordered_set<std::uint64_t> seen;
    seen.reserve(segments.size());
    for (std::size_t s = segments.size(); s-- > 0;) {
      const std::uint32_t a = segments[s][0], b = segments[s][1];
      if (a == b) continue;
      pending_.push_back({a, b, static_cast<std::uint32_t>(s)});
    }
    for (std::size_t k = pending_.size(); k-- > 0;) {
      const Work& w = pending_[k];
      if (seen.insert(SubsegmentOwners::key(w.a, w.b)).second) work_.push_back(w);
    }
    std::reverse(work_.begin(), work_.end());
    std::size_t budget = 64 * (segments.size() + tri_.points.size()) + 1024;
    while (!work_.empty()) {
      if (budget-- == 0) {
        return make_error(ErrorCode::SelfIntersection,
                          "segment recovery did not converge (too many crossing segments)");
      }
      const Work w = work_.back();
      work_.pop_back();
      if (w.a == w.b) continue;
      auto r = insert_one(w);
      if (!r) return r;
    }
    return {};
  }

 private:
  const double* P(std::uint32_t v) const { return tri_.points[v].data(); }
  Sign orient(std::uint32_t a, std::uint32_t b, std::uint32_t c) const {
    return orient2d(P(a), P(b), P(c));
  }

  // Does x lie on input segment `seg` (whose piece a->b is being inserted; o is
  // orient2d(a, b, x))? Exactly when x is on the piece's line or on the input segment's
  // line (piece endpoints may be rounded intersection vertices); also when x is an
  // intersection vertex defined on an input segment whose line is exactly this one: its
  // rounded position is then treated as on the line, so that overlapping collinear
  // segments do not create parallel constraint chains around it.
  bool on_line(std::uint32_t seg, std::uint32_t x, Sign o) const {
    if (o == Sign::Zero) return true;
    const auto& pq = (*segments_)[seg];
    if (orient(pq[0], pq[1], x) == Sign::Zero) return true;
    if (crossing_lines_.empty()) return false;
    const auto it = crossing_lines_.find(x);
    if (it == crossing_lines_.end()) return false;
    for (std::uint32_t s : it->second) {
      const auto& rs = (*segments_)[s];
      if (orient(rs[0], rs[1], pq[0]) == Sign::Zero && orient(rs[0], rs[1], pq[1]) == Sign::Zero)
        return true;
    }
    return false;
  }

  // x sees a and b at an obtuse angle: for x on the line ab, strictly between them.
  bool between(std::uint32_t a, std::uint32_t b, std::uint32_t x) const {
    return predicates::dot2d(P(a), P(b), P(x)) == Sign::Negative;
  }

  void mark(std::uint32_t ref, std::uint32_t a, std::uint32_t b, std::uint32_t seg) {
    tri_.set_subseg(ref / 3, ref % 3, true);
    owners_.set(a, b, seg);
  }

  // Splits the segment a->b at vertex c lying on it.
  void split_at(const Work& w, std::uint32_t c) {
    ++stats_.vertices_on_segments;
    work_.push_back({c, w.b, w.seg});
    work_.push_back({w.a, c, w.seg});
  }

  Expected<void> insert_one(const Work& w) {
    const std::uint32_t a = w.a, b = w.b;
    const std::uint32_t e = tri_.find_edge(a, b);
    if (e != kNone) {
      mark(e, a, b, w.seg);
      return {};
    }
    // Find the triangle (a, c, d) around a whose wedge contains the direction a->b.
    std::uint32_t t = tri_.vt[a];
    const std::uint32_t start = t;
    std::uint32_t c = kNone, d = kNone, ti = 3;
    for (;;) {
      std::uint32_t i = 0;
      while (tri_.tv[3 * t + i] != a) ++i;
      const std::uint32_t x = tri_.tv[3 * t + next3(i)], y = tri_.tv[3 * t + prev3(i)];
      if (x != kGhost && y != kGhost) {
        const Sign ox = orient(a, b, x), oy = orient(a, b, y);
        if (on_line(w.seg, x, ox) && between(a, b, x)) {
          split_at(w, x);
          return {};
        }
        if (on_line(w.seg, y, oy) && between(a, b, y)) {
          split_at(w, y);
          return {};
        }
        if (ox == Sign::Negative && oy == Sign::Positive) {
          c = x;
          d = y;
          ti = i;
          break;
        }
      }
      t = tri_.tn[3 * t + next3(i)] / 3;
      DELMESH_CHECK(t != start, "segment recovery: no triangle around a vertex faces the segment");
    }
    // Walk along a->b collecting the crossed edges (c on the right, d on the left).
    crossed_.clear();
    std::uint32_t ref = 3 * t + ti;
    for (;;) {
      if (tri_.subseg(ref / 3, ref % 3)) return split_crossing(w, c, d);
      crossed_.push_back({c, d});
      const std::uint32_t opp = tri_.tn[ref];
      const std::uint32_t u = opp / 3, j = opp % 3;
      const std::uint32_t x = tri_.tv[3 * u + j];
      DELMESH_CHECK(x != kGhost, "segment recovery: walk left the convex hull");
      if (x == b) break;
      const Sign ox = orient(a, b, x);
      if (on_line(w.seg, x, ox) && between(a, b, x)) {
        split_at(w, x);
        return {};
      }
      // u = (x, d, c): leave through c-x when x is left of a->b, else through x-d.
      if (ox == Sign::Positive) {
        ref = 3 * u + next3(j);  // edge c->x
        d = x;
      } else {
        ref = 3 * u + prev3(j);  // edge x->d
        c = x;
      }
    }
    return flip_out(w);
  }

  // Sloan's flipping of the crossed edges, then Lawson flips to restore Delaunay.
  Expected<void> flip_out(const Work& w) {
    const std::uint32_t a = w.a, b = w.b;
    std::deque<std::array<std::uint32_t, 2>> queue(crossed_.begin(), crossed_.end());
    fresh_.clear();
    std::size_t stall = 0;
    while (!queue.empty()) {
      if (stall > 2 * queue.size() + 8) {
        return make_error(ErrorCode::SelfIntersection,
                          "segment " + std::to_string(w.seg) + " could not be recovered");
      }
      const auto [c, d] = queue.front();
      queue.pop_front();
      const std::uint32_t e = tri_.find_edge(c, d);
      DELMESH_CHECK(e != kNone, "segment recovery: a crossed edge vanished");
      const std::uint32_t t = e / 3, i = e % 3;
      const std::uint32_t A = tri_.tv[3 * t + i];
      const std::uint32_t D = tri_.tv[tri_.tn[e]];
      const Sign oc = orient(A, D, c), od = orient(A, D, d);
      if (oc == Sign::Zero || od == Sign::Zero || oc == od) {
        queue.push_back({c, d});
        ++stall;
        continue;
      }
      stall = 0;
      tri_.flip(t, i);
      const Sign oa = orient(a, b, A), odd = orient(a, b, D);
      if (A != a && A != b && D != a && D != b && oa != Sign::Zero && odd != Sign::Zero && oa != odd) {
        queue.push_back({A, D});
      } else {
        fresh_.push_back({A, D});
      }
    }
    const std::uint32_t e = tri_.find_edge(a, b);
    DELMESH_CHECK(e != kNone, "segment recovery: segment missing after flips");
    mark(e, a, b, w.seg);
    lawson();
    return {};
  }

  void lawson() {
    while (!fresh_.empty()) {
      const auto [x, y] = fresh_.back();
      fresh_.pop_back();
      const std::uint32_t e = tri_.find_edge(x, y);
      if (e == kNone) continue;
      const std::uint32_t t = e / 3, i = e % 3;
      if (tri_.subseg(t, i)) continue;
      const std::uint32_t o = tri_.tn[e];
      const std::uint32_t u = o / 3;
      if (tri_.ghost(t) || tri_.ghost(u)) continue;
      const std::uint32_t A = tri_.tv[3 * t + i], B = tri_.tv[3 * t + next3(i)],
                          C = tri_.tv[3 * t + prev3(i)], D = tri_.tv[o];
      if (predicates::incircle_sos(P(A), P(B), P(C), P(D), A, B, C, D) != Sign::Positive) continue;
      // Not locally Delaunay: the quadrilateral is convex, flip.
      tri_.flip(t, i);
      fresh_.push_back({A, B});
      fresh_.push_back({B, D});
      fresh_.push_back({D, C});
      fresh_.push_back({C, A});
    }
  }

  // The walk along w met subsegment c-d: split both at their intersection.
  Expected<void> split_crossing(const Work& w, std::uint32_t c, std::uint32_t d) {
    const std::uint32_t other = owners_.get(c, d);
    const Point2 pa = tri_.points[w.a], pb = tri_.points[w.b];
    const Point2 pc = tri_.points[c], pd = tri_.points[d];
    const double rx = pb[0] - pa[0], ry = pb[1] - pa[1];
    const double sx = pd[0] - pc[0], sy = pd[1] - pc[1];
    const double den = rx * sy - ry * sx;
    double s = ((pc[0] - pa[0]) * sy - (pc[1] - pa[1]) * sx) / den;
    if (!(s > 0.0)) s = 0.0;
    if (s > 1.0) s = 1.0;
    const Point2 px = {pa[0] + s * rx, pa[1] + s * ry};
    ++stats_.crossings;
    const std::uint32_t cd = tri_.find_edge(c, d);
    tri_.set_subseg(cd / 3, cd % 3, false);
    owners_.erase(c, d);
    std::uint32_t x = kNone;
    for (std::uint32_t v : {w.a, w.b, c, d})
      if (tri_.points[v] == px) x = v;
    if (x == kNone) {
      const Location loc = tri_.locate(px, tri_.vt[c]);
      if (loc.kind == Location::OnVertex) {
        x = loc.vertex;
      } else {
        x = static_cast<std::uint32_t>(tri_.points.size());
        tri_.points.push_back(px);
        if (!tri_.find_cavity(x, &loc.tri, 1, true)) {
          tri_.points.pop_back();
          Error err = make_error(ErrorCode::SelfIntersection,
                                 "segments " + std::to_string(w.seg) + " and " +
                                     std::to_string(other) +
                                     " cross where no vertex can be inserted");
          err.entity_ids = {w.seg, other};
          return err;
        }
        tri_.commit_cavity(x);
      }
      auto& lines = crossing_lines_[x];
      lines.push_back(w.seg);
      lines.push_back(other);
    }
    work_.push_back({c, x, other});
    work_.push_back({x, d, other});
    work_.push_back({x, w.b, w.seg});
    work_.push_back({w.a, x, w.seg});
    return {};
  }

  Triangulation& tri_;
  SubsegmentOwners& owners_;
  CdtStats& stats_;
  std::vector<Work> work_;
  std::vector<Work> pending_;
  const std::vector<std::array<std::uint32_t, 2>>* segments_ = nullptr;
  /// Intersection vertex -> the two input segments it was defined on.
  std::unordered_map<std::uint32_t, std::vector<std::uint32_t>> crossing_lines_;
  std::vector<std::array<std::uint32_t, 2>> crossed_;
  std::vector<std::array<std::uint32_t, 2>> fresh_;
};

}  // namespace

Expected<void> insert_segments(Triangulation& tri,
                               const std::vector<std::array<std::uint32_t, 2>>& segments,
                               SubsegmentOwners& owners, CdtStats& stats) {
  SegmentInserter inserter(tri, owners, stats);
  return inserter.run(segments);
}

Expected<DomainResult> classify_domain(Triangulation& tri, const std::vector<Point2>& holes,
                                       const std::vector<Pslg::Region>& regions,
                                       const DomainOptions& options) {
  DomainResult result;
  const std::uint32_t n = tri.num_slots();
  // 0: domain, 1: exterior, 2: hole.
  std::vector<std::uint8_t> state(n, 0);
  std::vector<std::uint32_t> stack;
  auto flood = [&](std::uint8_t value) {
    while (!stack.empty()) {
      const std::uint32_t t = stack.back();
      stack.pop_back();
      for (std::uint32_t i = 0; i < 3; ++i) {
        if (tri.subseg(t, i)) continue;
        const std::uint32_t u = tri.tn[3 * t + i] / 3;
        if (state[u] != 0 || tri.ghost(u)) continue;
        state[u] = value;
        stack.push_back(u);
      }
    }
  };
  for (std::uint32_t t = 0; t < n; ++t) {
    if (!tri.alive(t) || tri.ghost(t)) continue;
    tri.tf[t] &= static_cast<std::uint8_t>(~kOutside);
    if (options.keep_convex_hull) continue;
    for (std::uint32_t i = 0; i < 3; ++i) {
      if (tri.subseg(t, i) || !tri.ghost(tri.tn[3 * t + i] / 3) || state[t] != 0) continue;
      state[t] = 1;
      stack.push_back(t);
    }
  }
  flood(1);
  for (std::size_t h = 0; h < holes.size(); ++h) {
    const Location loc = tri.locate(holes[h]);
    if (loc.kind == Location::Outside || state[loc.tri] == 1) {
      Error err = make_error(ErrorCode::InvalidInput,
                             "hole " + std::to_string(h) + " (" + std::to_string(holes[h][0]) +
                                 ", " + std::to_string(holes[h][1]) +
                                 ") lies outside the triangulated domain");
      err.entity_ids = {static_cast<std::uint32_t>(h)};
      return err;
    }
    if (state[loc.tri] == 2) continue;
    state[loc.tri] = 2;
    stack.push_back(loc.tri);
    flood(2);
  }
  for (std::uint32_t t = 0; t < n; ++t)
    if (state[t] != 0) tri.tf[t] |= kOutside;
  // Every edge between the domain and the rest becomes a subsegment.
  for (std::uint32_t t = 0; t < n; ++t) {
    if (!tri.in_domain(t)) continue;
    for (std::uint32_t i = 0; i < 3; ++i) {
      if (tri.subseg(t, i) || tri.in_domain(tri.tn[3 * t + i] / 3)) continue;
      tri.set_subseg(t, i, true);
      result.boundary_edges.push_back({tri.org(t, i), tri.dest(t, i)});
    }
  }
  if (options.track_regions) {
    tri.region.assign(n, 0);
    for (std::size_t r = 0; r < regions.size(); ++r) {
      const Location loc = tri.locate(regions[r].point);
      if (loc.kind == Location::Outside || !tri.in_domain(loc.tri)) {
        result.unused_regions.push_back(r);
        continue;
      }
      const auto value = static_cast<std::uint32_t>(r + 1);
      stack.push_back(loc.tri);
      tri.region[loc.tri] = value;
      while (!stack.empty()) {
        const std::uint32_t t = stack.back();
        stack.pop_back();
        for (std::uint32_t i = 0; i < 3; ++i) {
          if (tri.subseg(t, i)) continue;
          const std::uint32_t u = tri.tn[3 * t + i] / 3;
          if (!tri.in_domain(u) || tri.region[u] == value) continue;
          tri.region[u] = value;
          stack.push_back(u);
        }
      }
    }
  }
  return result;
}

}  // namespace delmesh::mesh2d
