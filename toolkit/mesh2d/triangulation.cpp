// Bowyer-Watson insertion, visibility walk, flips and Delaunay construction on the
// compact triangulation of triangulation.h (notes §2.1.1, §2.1.5).
#include "toolkit/mesh2d/triangulation.h"

#include <algorithm>
#include <string>

#include "toolkit/mesh2d/spatial_sort.h"
#include "toolkit/predicates/predicates.h"

namespace delmesh::mesh2d {

using predicates::orient2d;

void Triangulation::set_subseg(std::uint32_t t, std::uint32_t i, bool on) {
  const std::uint32_t o = tn[3 * t + i];
  const std::uint8_t bit_t = static_cast<std::uint8_t>(1u << i);
  const std::uint8_t bit_o = static_cast<std::uint8_t>(1u << (o % 3));
  if (on) {
    tf[t] |= bit_t;
    tf[o / 3] |= bit_o;
  } else {
    tf[t] &= static_cast<std::uint8_t>(~bit_t);
    tf[o / 3] &= static_cast<std::uint8_t>(~bit_o);
  }
}

std::size_t Triangulation::count_real() const {
  std::size_t n = 0;
  for (std::uint8_t f : tf) n += (f & (kDead | kGhostTri)) == 0;
  return n;
}

std::size_t Triangulation::count_in_domain() const {
  std::size_t n = 0;
  for (std::uint8_t f : tf) n += (f & (kDead | kGhostTri | kOutside)) == 0;
  return n;
}

void Triangulation::reserve(std::size_t n) {
  points.reserve(n);
  vt.reserve(n);
  tv.reserve(6 * n + 16);
  tn.reserve(6 * n + 16);
  tf.reserve(2 * n + 8);
}

std::uint32_t Triangulation::alloc_tri() {
  if (free_head_ != kNone) {
    const std::uint32_t t = free_head_;
    free_head_ = tn[3 * t];
    tf[t] = 0;
    return t;
  }
  const auto t = static_cast<std::uint32_t>(tf.size());
  tv.resize(tv.size() + 3, kNone);
  tn.resize(tn.size() + 3, kNone);
  tf.push_back(0);
  if (!region.empty()) region.push_back(0);
  return t;
}

void Triangulation::free_tri(std::uint32_t t) {
  tf[t] = kDead;
  tv[3 * t] = tv[3 * t + 1] = tv[3 * t + 2] = kNone;
  tn[3 * t] = free_head_;
  free_head_ = t;
}

bool Triangulation::conflict(std::uint32_t t, std::uint32_t p) const {
  const std::uint32_t a = tv[3 * t], b = tv[3 * t + 1], c = tv[3 * t + 2];
  const double* pp = points[p].data();
  if (!(tf[t] & kGhostTri)) {
    return predicates::incircle_sos(points[a].data(), points[b].data(), points[c].data(), pp,
                                    a, b, c, p) == Sign::Positive;
  }
  std::uint32_t x = a, y = b;
  if (a == kGhost) {
    x = b;
    y = c;
  } else if (b == kGhost) {
    x = c;
    y = a;
  }
  const Sign o = orient2d(points[x].data(), points[y].data(), pp);
  if (o == Sign::Positive) return true;
  if (o == Sign::Negative) return false;
  return predicates::dot2d(points[x].data(), points[y].data(), pp) == Sign::Negative;
}

Location Triangulation::locate(const Point2& p, std::uint32_t start, bool stop_at_subsegments) {
  std::uint32_t t = start != kNone ? start : last_tri;
  if (t == kNone || t >= num_slots() || !alive(t)) {
    for (t = 0; t < num_slots(); ++t)
      if (alive(t) && !ghost(t)) break;
  }
  if (ghost(t)) {
    for (std::uint32_t i = 0; i < 3; ++i)
      if (tv[3 * t + i] == kGhost) t = tn[3 * t + i] / 3;
  }
  const double* pp = p.data();
  std::uint32_t prev = kNone;
  for (std::size_t steps = 0;; ++steps) {
    rng_ ^= rng_ << 13;
    rng_ ^= rng_ >> 17;
    rng_ ^= rng_ << 5;
    const std::uint32_t r = rng_ % 3;
    std::uint32_t blocked = 3;
    bool moved = false;
    for (std::uint32_t k = 0; k < 3; ++k) {
      const std::uint32_t i = (r + k) % 3;
      const std::uint32_t nb = tn[3 * t + i] / 3;
      if (nb == prev) continue;  // p is not beyond the edge we came through
      const std::uint32_t a = org(t, i), b = dest(t, i);
      if (orient2d(points[a].data(), points[b].data(), pp) != Sign::Negative) continue;
      if (stop_at_subsegments &&
          (subseg(t, i) || (tf[nb] & (kGhostTri | kOutside | kDead)))) {
        blocked = i;
        continue;
      }
      if (ghost(nb)) {
        Location loc;
        loc.kind = Location::Outside;
        loc.tri = nb;
        return loc;
      }
      prev = t;
      t = nb;
      moved = true;
      break;
    }
    if (moved) {
      if (steps > 8 * static_cast<std::size_t>(num_slots()) + 64) {
        // A cycle can only arise in a non-Delaunay region; restart without memory.
        prev = kNone;
        steps = 0;
      }
      continue;
    }
    Location loc;
    loc.tri = t;
    if (blocked != 3) {
      loc.kind = Location::Blocked;
      loc.edge = blocked;
      return loc;
    }
    for (std::uint32_t i = 0; i < 3; ++i) {
      const std::uint32_t v = tv[3 * t + i];
      if (points[v][0] == p[0] && points[v][1] == p[1]) {
        loc.kind = Location::OnVertex;
        loc.vertex = v;
        return loc;
      }
    }
    loc.kind = Location::InTriangle;
    return loc;
  }
}

bool Triangulation::find_cavity(std::uint32_t p, const std::uint32_t* seeds, int num_seeds,
                                bool constrained) {
  cavity_.clear();
  boundary_.clear();
  stack_.clear();
  for (int s = 0; s < num_seeds; ++s) {
    const std::uint32_t t = seeds[s];
    if (tf[t] & kVisited) continue;
    tf[t] |= kVisited;
    cavity_.push_back(t);
    stack_.push_back(t);
  }
  const bool track_region = !region.empty();
  while (!stack_.empty()) {
    const std::uint32_t t = stack_.back();
    stack_.pop_back();
    const bool expand = !constrained || !(tf[t] & (kGhostTri | kOutside));
    for (std::uint32_t i = 0; i < 3; ++i) {
      const std::uint32_t ref = tn[3 * t + i];
      const std::uint32_t u = ref / 3;
      if (tf[u] & kVisited) continue;
      bool grow = expand;
      if (grow && constrained && (subseg(t, i) || (tf[u] & (kGhostTri | kOutside)))) grow = false;
      if (grow && conflict(u, p)) {
        tf[u] |= kVisited;
        cavity_.push_back(u);
        stack_.push_back(u);
      } else {
        boundary_.push_back({ref, org(t, i), dest(t, i), t,
                             static_cast<std::uint8_t>(tf[t] & kOutside),
                             track_region ? region[t] : 0u});
      }
    }
  }
  // Star-shapedness: every real boundary edge must see p on its left.
  const double* pp = points[p].data();
  for (const CavityEdge& e : boundary_) {
    if (e.a == kGhost || e.b == kGhost) continue;
    if (orient2d(points[e.a].data(), points[e.b].data(), pp) != Sign::Positive) {
      abandon_cavity();
      return false;
    }
  }
  return true;
}

void Triangulation::abandon_cavity() {
  for (std::uint32_t t : cavity_) tf[t] &= static_cast<std::uint8_t>(~kVisited);
  cavity_.clear();
  boundary_.clear();
}

void Triangulation::commit_cavity(std::uint32_t p) {
  if (link_.size() < points.size()) link_.resize(points.size() + points.size() / 2 + 16, kNone);
  if (vt.size() < points.size()) vt.resize(points.size(), kNone);
  new_tris_.clear();
  const std::size_t nb = boundary_.size();
  const bool track_region = !region.empty();
  for (std::size_t k = 0; k < nb; ++k) {
    std::uint32_t t;
    if (k < cavity_.size()) {
      t = cavity_[k];
    } else {
      t = alloc_tri();
    }
    new_tris_.push_back(t);
  }
  for (std::size_t k = nb; k < cavity_.size(); ++k) free_tri(cavity_[k]);
  for (std::size_t k = 0; k < nb; ++k) {
    const CavityEdge& e = boundary_[k];
    const std::uint32_t t = new_tris_[k];
    tv[3 * t] = e.a;
    tv[3 * t + 1] = e.b;
    tv[3 * t + 2] = p;
    std::uint8_t f = e.inner_flags;
    if (e.a == kGhost || e.b == kGhost) f |= kGhostTri;
    const std::uint32_t o = e.outer;
    if ((tf[o / 3] >> (o % 3)) & 1u) f |= 4u;  // edge 2 is the boundary edge
    tf[t] = f;
    if (track_region) region[t] = e.inner_region;
    tn[3 * t + 2] = o;
    tn[o] = 3 * t + 2;
    if (e.a == kGhost) {
      ghost_link_ = t;
    } else {
      link_[e.a] = t;
    }
  }
  for (std::size_t k = 0; k < nb; ++k) {
    const CavityEdge& e = boundary_[k];
    const std::uint32_t t = new_tris_[k];
    const std::uint32_t u = e.b == kGhost ? ghost_link_ : link_[e.b];
    tn[3 * t] = 3 * u + 1;
    tn[3 * u + 1] = 3 * t;
    if (e.a != kGhost) vt[e.a] = t;
    if (!(tf[t] & kGhostTri)) last_tri = t;
  }
  vt[p] = last_tri;
  for (std::uint32_t t : new_tris_) {
    if (!(tf[t] & kGhostTri)) {
      vt[p] = t;
      break;
    }
  }
  cavity_.clear();
  boundary_.clear();
}

std::uint32_t Triangulation::find_edge(std::uint32_t a, std::uint32_t b) const {
  const std::uint32_t start = vt[a];
  if (start == kNone) return kNone;
  std::uint32_t t = start;
  for (std::size_t guard = 0; guard < tf.size() + 3; ++guard) {
    std::uint32_t i = 0;
    while (tv[3 * t + i] != a) ++i;
    if (tv[3 * t + next3(i)] == b) return 3 * t + prev3(i);
    t = tn[3 * t + next3(i)] / 3;
    if (t == start) return kNone;
  }
  return kNone;
}

void Triangulation::flip(std::uint32_t t, std::uint32_t i) {
  const std::uint32_t ref = tn[3 * t + i];
  const std::uint32_t u = ref / 3, j = ref % 3;
  const std::uint32_t A = tv[3 * t + i], B = tv[3 * t + next3(i)], C = tv[3 * t + prev3(i)];
  const std::uint32_t D = tv[3 * u + j];
  // Outer edges: t's C->A (opposite B) and A->B (opposite C); u's B->D (opposite C in u)
  // and D->C (opposite B in u).
  const std::uint32_t iB = next3(i), iC = prev3(i);
  const std::uint32_t jC = next3(j), jB = prev3(j);
  const std::uint32_t nCA = tn[3 * t + iB], nAB = tn[3 * t + iC];
  const std::uint32_t nBD = tn[3 * u + jC], nDC = tn[3 * u + jB];
  const unsigned fCA = (tf[t] >> iB) & 1u, fAB = (tf[t] >> iC) & 1u;
  const unsigned fBD = (tf[u] >> jC) & 1u, fDC = (tf[u] >> jB) & 1u;
  const std::uint8_t keep_t = tf[t] & static_cast<std::uint8_t>(~kSubsegMask);
  const std::uint8_t keep_u = tf[u] & static_cast<std::uint8_t>(~kSubsegMask);
  // t' = (A, B, D): edge0 B->D, edge1 D->A (diagonal), edge2 A->B.
  tv[3 * t] = A;
  tv[3 * t + 1] = B;
  tv[3 * t + 2] = D;
  tn[3 * t] = nBD;
  tn[nBD] = 3 * t;
  tn[3 * t + 1] = 3 * u + 1;
  tn[3 * t + 2] = nAB;
  tn[nAB] = 3 * t + 2;
  tf[t] = static_cast<std::uint8_t>(keep_t | fBD | (fAB << 2));
  // u' = (D, C, A): edge0 C->A, edge1 A->D (diagonal), edge2 D->C.
  tv[3 * u] = D;
  tv[3 * u + 1] = C;
  tv[3 * u + 2] = A;
  tn[3 * u] = nCA;
  tn[nCA] = 3 * u;
  tn[3 * u + 1] = 3 * t + 1;
  tn[3 * u + 2] = nDC;
  tn[nDC] = 3 * u + 2;
  tf[u] = static_cast<std::uint8_t>(keep_u | fCA | (fDC << 2));
  vt[A] = t;
  vt[B] = t;
  vt[D] = t;
  vt[C] = u;
  last_tri = t;
}

Expected<void> Triangulation::build_delaunay(std::vector<Point2> pts) {
  points = std::move(pts);
  const std::size_t n = points.size();
  vt.assign(n, kNone);
  duplicate_of.assign(n, kNone);
  num_duplicates = 0;
  tv.clear();
  tn.clear();
  tf.clear();
  free_head_ = kNone;
  last_tri = kNone;
  tv.reserve(6 * n + 16);
  tn.reserve(6 * n + 16);
  tf.reserve(2 * n + 8);
  if (n < 3) {
    return make_error(ErrorCode::DegenerateInput,
                      "fewer than three points: nothing to triangulate");
  }
  const std::vector<std::uint32_t> order = brio_hilbert_order(points);
  const std::uint32_t a = order[0];
  std::size_t ib = 1;
  while (ib < n && points[order[ib]] == points[a]) ++ib;
  if (ib == n) {
    return make_error(ErrorCode::DegenerateInput, "all points coincide: nothing to triangulate");
  }
  const std::uint32_t b = order[ib];
  std::size_t ic = ib + 1;
  Sign o = Sign::Zero;
  while (ic < n) {
    o = orient2d(points[a].data(), points[b].data(), points[order[ic]].data());
    if (o != Sign::Zero) break;
    ++ic;
  }
  if (ic == n) {
    return make_error(ErrorCode::DegenerateInput,
                      "all " + std::to_string(n) + " points are collinear: no triangle to build");
  }
  std::uint32_t c = order[ic];
  std::uint32_t v0 = a, v1 = b, v2 = c;
  if (o == Sign::Negative) std::swap(v1, v2);

  const std::uint32_t t0 = alloc_tri();
  tv[0] = v0;
  tv[1] = v1;
  tv[2] = v2;
  std::uint32_t g[3];
  for (std::uint32_t e = 0; e < 3; ++e) {
    g[e] = alloc_tri();
    const std::uint32_t x = org(t0, e), y = dest(t0, e);
    tv[3 * g[e]] = y;
    tv[3 * g[e] + 1] = x;
    tv[3 * g[e] + 2] = kGhost;
    tf[g[e]] = kGhostTri;
    tn[3 * t0 + e] = 3 * g[e] + 2;
    tn[3 * g[e] + 2] = 3 * t0 + e;
  }
  // Ghost of edge x->y links its edge 1 (G->y) with edge 0 (y->G) of the ghost of the
  // next hull edge, which starts at y: edge e is followed by edge next3(e) (t0's edge
  // order 2, 0, 1 is v0->v1, v1->v2, v2->v0).
  for (std::uint32_t e = 0; e < 3; ++e) {
    const std::uint32_t nx = next3(e);
    tn[3 * g[e] + 1] = 3 * g[nx];
    tn[3 * g[nx]] = 3 * g[e] + 1;
  }
  vt[v0] = vt[v1] = vt[v2] = t0;
  last_tri = t0;

  for (std::size_t k = 1; k < n; ++k) {
    if (k == ib || k == ic) continue;
    const std::uint32_t p = order[k];
    const Location loc = locate(points[p]);
    if (loc.kind == Location::OnVertex) {
      duplicate_of[p] = loc.vertex;
      ++num_duplicates;
      continue;
    }
    const bool ok = find_cavity(p, &loc.tri, 1, false);
    DELMESH_CHECK(ok, "Delaunay insertion: cavity not star-shaped for vertex " + std::to_string(p));
    commit_cavity(p);
  }
  return {};
}

}  // namespace delmesh::mesh2d
