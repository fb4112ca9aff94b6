// Removal of an edge inside a facet (see facet_edge_flip.h).
#include "refiners/tet3d/facet_edge_flip.h"

#include <algorithm>
#include <limits>

#include "toolkit/core/error.h"
#include "toolkit/predicates/predicates.h"
#include "toolkit/tetmesh/ring_triangulation.h"

namespace delmesh::tet3d {

namespace {

using Quad = std::array<std::uint32_t, 4>;
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kInvalid = -kInf;

bool positive(const TetMesh& mesh, const Quad& q) {
  return predicates::orient3d(mesh.coords(q[0]), mesh.coords(q[1]), mesh.coords(q[2]), mesh.coords(q[3])) ==
         Sign::Positive;
}

/// Triangulates the open ring `ring` (in the rotation order of tets_around_edge(x, y),
/// closed by the edge ring.front() - ring.back()) and joins each triangle to x and y,
/// appending the tets to `out`. In the domain the triangulation maximizes the worst
/// quality of its tets (best_ring_triangulation, as in toolkit/tetmesh remove_edge); outside it
/// is any valid one (quality +inf). Returns the worst quality, or kInvalid when no valid
/// triangulation has a worst quality above `must_exceed`.
double triangulate_side(const TetMesh& mesh, std::uint32_t x, std::uint32_t y, const std::vector<std::uint32_t>& ring,
                        int region, double must_exceed, const RegionTetQuality& quality, std::vector<Quad>& out) {
  const int n = static_cast<int>(ring.size());
  const bool scored = in_domain(region);
  // The two tets of ring triangle (i, k, j), i < k < j: positive when the triangle is
  // valid (the ring turns counterclockwise seen from y).
  auto tets_of = [&](int i, int k, int j) {
    return std::array<Quad, 2>{Quad{ring[i], ring[k], ring[j], y}, Quad{ring[k], ring[i], ring[j], x}};
  };
  auto triangle_quality = [&](int i, int k, int j) {
    const auto q = tets_of(i, k, j);
    double worst = kInf;
    if (scored) {
      for (const Quad& t : q) {
        worst = std::min(worst, quality(region, mesh.point(t[0]), mesh.point(t[1]), mesh.point(t[2]),
                                        mesh.point(t[3])));
        if (!(worst > must_exceed)) return worst;
      }
    }
    if (!positive(mesh, q[0]) || !positive(mesh, q[1])) return kInvalid;
    return worst;
  };
  std::vector<std::array<int, 3>> triangles;
  const double result = best_ring_triangulation(n, must_exceed, triangle_quality, triangles);
  for (const auto& [i, k, j] : triangles) {
    for (const Quad& t : tets_of(i, k, j)) out.push_back(t);
  }
  return result;
}

/// The smallest angle of triangle (a, b, c), in radians (floating point: a quality measure).
double smallest_angle(const Vec3& a, const Vec3& b, const Vec3& c) {
  auto angle = [](const Vec3& o, const Vec3& p, const Vec3& q) {
    const double cosine = (p - o).normalized().dot((q - o).normalized());
    return std::acos(std::clamp(cosine, -1.0, 1.0));
  };
  return std::min({angle(a, b, c), angle(b, a, c), angle(c, a, b)});
}

}  // namespace

bool plan_facet_edge_flip(RefineState& state, std::uint32_t x, std::uint32_t y, double min_gain,
                          const RegionTetQuality& quality, FacetEdgeFlip& plan) {
  if (subsegment_of(state, x, y)) return false;
  TetMesh& mesh = state.mesh;
  std::vector<std::uint32_t> ring;
  if (!mesh.tets_around_edge(x, y, plan.old_tets, &ring)) return false;
  const std::size_t m = ring.size();
  if (m < 4 || m > kMaxFacetEdgeRing) return false;
  // The two subfacets around (x, y): (x, y, ring[first]) and (x, y, ring[second]).
  std::size_t first = m, second = m;
  std::uint32_t facet = kNone;
  std::size_t infinite = m;
  for (std::size_t k = 0; k < m; ++k) {
    if (ring[k] == kInfiniteVertex) {
      infinite = k;
      continue;
    }
    const std::uint32_t* f = subface_of(state, x, y, ring[k]);
    if (!f) continue;
    if (second < m || (first < m && *f != facet)) return false;
    (first < m ? second : first) = k;
    facet = *f;
  }
  if (second == m) return false;
  if (infinite > first && infinite < second) {
    // Rotate the ring to start at the second subfacet: side A (below) is then the one
    // without the infinite vertex.
    std::rotate(ring.begin(), ring.begin() + static_cast<std::ptrdiff_t>(second), ring.end());
    std::rotate(plan.old_tets.begin(), plan.old_tets.begin() + static_cast<std::ptrdiff_t>(second),
                plan.old_tets.end());
    infinite = infinite + m - second;
    const std::size_t span = second - first;
    first = 0;
    second = m - span;
  }
  // The facet's triangulation keeps its smallest angle.
  const Vec3 &px = mesh.point(x), &py = mesh.point(y), &pc = mesh.point(ring[first]), &pd = mesh.point(ring[second]);
  if (std::min(smallest_angle(pc, pd, px), smallest_angle(pc, pd, py)) <
      std::min(smallest_angle(px, py, pc), smallest_angle(px, py, pd)))
    return false;
  // Side A: the tets first .. second - 1 (from ring[first] to ring[second]); side B: the
  // others. Each of one region, of two tets at least.
  const std::size_t count_a = second - first, count_b = m - count_a;
  if (count_a < 2 || count_b < 2) return false;
  // On the convex hull the far side is the two infinite tets (x, y, d, inf) and (x, y,
  // inf, c); the hull stays convex only if the four vertices are coplanar.
  const bool hull = infinite < m;
  if (hull && (infinite != (second + 1) % m || count_b != 2 ||
               predicates::orient3d(mesh.coords(x), mesh.coords(y), mesh.coords(ring[first]),
                                    mesh.coords(ring[second])) != Sign::Zero))
    return false;
  auto region_of = [&](std::uint32_t t) {
    return t < state.tet_region.size() && !mesh.is_infinite(t) ? state.tet_region[t] : kRegionExterior;
  };
  const int region_a = region_of(plan.old_tets[first]), region_b = region_of(plan.old_tets[second]);
  double old_worst = kInf;
  for (std::size_t k = 0; k < m; ++k) {
    const std::uint32_t t = plan.old_tets[k];
    const int region = region_of(t);
    if (region != (k >= first && k < second ? region_a : region_b)) return false;
    if (!in_domain(region)) continue;
    const auto& v = mesh.tet(t).v;
    old_worst = std::min(old_worst, quality(region, mesh.point(v[0]), mesh.point(v[1]), mesh.point(v[2]),
                                            mesh.point(v[3])));
  }
  if (old_worst == kInf) return false;  // neither side in the domain
  const double must_exceed = old_worst + min_gain;
  std::vector<std::uint32_t> side_a(ring.begin() + static_cast<std::ptrdiff_t>(first),
                                    ring.begin() + static_cast<std::ptrdiff_t>(second) + 1);
  std::vector<std::uint32_t> side_b(ring.begin() + static_cast<std::ptrdiff_t>(second), ring.end());
  side_b.insert(side_b.end(), ring.begin(), ring.begin() + static_cast<std::ptrdiff_t>(first) + 1);
  plan.tets.clear();
  plan.regions.clear();
  const double worst_a = triangulate_side(mesh, x, y, side_a, region_a, must_exceed, quality, plan.tets);
  if (worst_a == kInvalid) return false;
  plan.regions.assign(plan.tets.size(), region_a);
  // The hull side: its one triangle (d, inf, c), no orientation to test.
  const double worst_b = hull ? kInf : triangulate_side(mesh, x, y, side_b, region_b, must_exceed, quality, plan.tets);
  if (worst_b == kInvalid) return false;
  if (hull) {
    plan.tets.push_back({side_b[0], side_b[1], side_b[2], y});
    plan.tets.push_back({side_b[1], side_b[0], side_b[2], x});
  }
  plan.regions.resize(plan.tets.size(), region_b);
  plan.x = x;
  plan.y = y;
  plan.c = ring[first];
  plan.d = ring[second];
  plan.facet = facet;
  plan.worst = std::min(worst_a, worst_b);
  return true;
}

bool commit_facet_edge_flip(RefineState& state, const FacetEdgeFlip& plan, std::vector<std::uint32_t>& created) {
  auto change = state.facets[plan.facet].flip_edge(plan.x, plan.y);
  if (!change) return false;
  for (const Subface& s : change->removed) state.subfaces.erase(face_key(s[0], s[1], s[2]));
  for (const Subface& s : change->added) state.subfaces[face_key(s[0], s[1], s[2])] = plan.facet;
  TetMesh& mesh = state.mesh;
  const std::uint32_t stamp = mesh.new_stamp();
  for (const std::uint32_t t : plan.old_tets) mesh.set_stamp(t, stamp);
  std::vector<std::uint32_t> outside;
  for (const std::uint32_t t : plan.old_tets)
    for (int f = 0; f < 4; ++f)
      if (mesh.stamp(mesh.neighbor(t, f)) != stamp) outside.push_back(mesh.tet(t).adj[f]);
  for (const std::uint32_t t : plan.old_tets) mesh.kill_tet(t);
  created.clear();
  for (const Quad& q : plan.tets) created.push_back(mesh.create_tet(q[0], q[1], q[2], q[3]));
  const bool glued = mesh.glue_by_vertices(created, outside);
  DELMESH_CHECK(glued, "facet edge flip: the new tets do not close up with the mesh");
  if (state.tet_region.size() < mesh.tet_slots()) state.tet_region.resize(mesh.tet_slots(), kRegionExterior);
  for (std::size_t k = 0; k < created.size(); ++k) {
    state.tet_region[created[k]] = plan.regions[k];
    for (const std::uint32_t v : mesh.tet(created[k]).v) mesh.set_vertex_tet(v, created[k]);
  }
  return true;
}

}  // namespace delmesh::tet3d
