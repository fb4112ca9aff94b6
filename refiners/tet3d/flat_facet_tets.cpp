// Flat tets lying on a facet (see flat_facet_tets.h).
#include "refiners/tet3d/flat_facet_tets.h"

#include <algorithm>
#include <array>
#include <vector>

#include "refiners/tet3d/unmet_tets.h"
#include "toolkit/quality/tet_quality.h"
#include "toolkit/tetmesh/tet_flips.h"

namespace delmesh::tet3d {

namespace {

/// The facet of face i of tet t (opposite its vertex i), or kNone.
std::uint32_t face_facet(const RefineState& state, std::uint32_t t, int i) {
  const auto& v = state.mesh.tet(t).v;
  const std::uint32_t* facet = subface_of(state, v[(i + 1) % 4], v[(i + 2) % 4], v[(i + 3) % 4]);
  return facet ? *facet : kNone;
}

bool try_release(RefineState& state, std::uint32_t t) {
  TetMesh& mesh = state.mesh;
  const int region = state.tet_region[t];
  std::array<std::uint32_t, 4> facet{};
  int count = 0;
  for (int i = 0; i < 4; ++i) {
    facet[i] = face_facet(state, t, i);
    count += facet[i] != kNone ? 1 : 0;
  }
  if (count != 2) return false;
  // c, d: the vertices opposite the two subfacets; x, y: the shared edge.
  int c = -1, d = -1, x = -1, y = -1;
  for (int i = 0; i < 4; ++i) {
    if (facet[i] != kNone) {
      (c < 0 ? c : d) = i;
    } else {
      (x < 0 ? x : y) = i;
    }
  }
  const std::uint32_t f = facet[c];
  if (facet[d] != f) return false;
  const auto& v = mesh.tet(t).v;
  if (subsegment_of(state, v[x], v[y])) return false;
  const std::uint32_t uc = mesh.neighbor(t, c), ud = mesh.neighbor(t, d);
  const std::uint32_t ux = mesh.neighbor(t, x), uy = mesh.neighbor(t, y);
  auto region_of = [&](std::uint32_t u) {
    return u < state.tet_region.size() && !mesh.is_infinite(u) ? state.tet_region[u] : kRegionExterior;
  };
  const int other = region_of(uc);
  if (other == region || region_of(ud) != other || region_of(ux) != region || region_of(uy) != region) return false;
  const std::uint32_t vx = v[x], vy = v[y];
  auto change = state.facets[f].flip_edge(vx, vy);
  if (!change) return false;
  for (const Subface& s : change->removed) state.subfaces.erase(face_key(s[0], s[1], s[2]));
  for (const Subface& s : change->added) state.subfaces[face_key(s[0], s[1], s[2])] = f;
  state.tet_region[t] = other;
  return true;
}

/// A tet above the bounds by MeshStats::unmet_tets' rule (unmet_tets.cpp).
bool breaks_bounds(const RefineState& state, int region, const Vec3& a, const Vec3& b, const Vec3& c,
                   const Vec3& d) {
  const MeshOptions& options = state.options;
  if (outside_dihedral_window(a, b, c, d, options.min_dihedral_deg, options.max_dihedral_deg)) return true;
  if (options.quality && !(radius_edge_ratio(a, b, c, d) <= options.max_radius_edge)) return true;
  return misses_volume_bound(state, region, a, b, c, d);
}

using Triangle = std::array<std::size_t, 3>;

/// Every triangulation of the convex polygon i..j of ring positions (Catalan many),
/// appended to `out`.
void triangulations(std::size_t i, std::size_t j, std::vector<std::vector<Triangle>>& out) {
  out.clear();
  if (j < i + 2) {
    out.emplace_back();
    return;
  }
  std::vector<std::vector<Triangle>> left, right;
  for (std::size_t k = i + 1; k < j; ++k) {
    triangulations(i, k, left);
    triangulations(k, j, right);
    for (const auto& l : left) {
      for (const auto& r : right) {
        std::vector<Triangle> all = l;
        all.insert(all.end(), r.begin(), r.end());
        all.push_back({i, k, j});
        out.push_back(std::move(all));
      }
    }
  }
}

/// One triangulation of the ring of edge (c, d): the worst smallest dihedral angle of its
/// tets and how many of them break the bounds.
struct RingChoice {
  std::vector<std::array<std::uint32_t, 4>> tets;
  double worst_deg = 0.0;
  std::size_t unmet = 0;
};

bool try_remove_flat(RefineState& state, std::uint32_t t) {
  TetMesh& mesh = state.mesh;
  const int region = state.tet_region[t];
  const auto v = mesh.tet(t).v;
  std::array<bool, 4> sub{};
  int count = 0;
  for (int i = 0; i < 4; ++i) {
    sub[i] = face_facet(state, t, i) != kNone;
    count += sub[i] ? 1 : 0;
  }
  if (count != 2) return false;
  std::uint32_t c = kNone, d = kNone;
  for (int i = 0; i < 4; ++i)
    if (sub[i]) (c == kNone ? c : d) = v[i];
  if (subsegment_of(state, c, d)) return false;
  std::vector<std::uint32_t> ring_tets, ring;
  if (!mesh.tets_around_edge(c, d, ring_tets, &ring) || ring.size() > kFlatRingMax) return false;
  double old_worst = 180.0;
  std::size_t old_unmet = 0;
  for (std::size_t k = 0; k < ring_tets.size(); ++k) {
    const std::uint32_t u = ring_tets[k];
    if (u >= state.tet_region.size() || mesh.is_infinite(u) || state.tet_region[u] != region) return false;
    if (subface_of(state, c, d, ring[k])) return false;
    const auto& w = mesh.tet(u).v;
    const Vec3 &p0 = mesh.point(w[0]), &p1 = mesh.point(w[1]), &p2 = mesh.point(w[2]), &p3 = mesh.point(w[3]);
    old_worst = std::min(old_worst, dihedral_extremes_deg(p0, p1, p2, p3).first);
    old_unmet += breaks_bounds(state, region, p0, p1, p2, p3) ? 1 : 0;
  }
  std::vector<std::vector<Triangle>> all;
  triangulations(0, ring.size() - 1, all);
  std::vector<RingChoice> choices;
  for (const auto& triangulation : all) {
    RingChoice choice;
    choice.worst_deg = 180.0;
    for (const Triangle& tri : triangulation) {
      for (const std::uint32_t apex : {c, d}) {
        const std::array<std::uint32_t, 4> w{apex, ring[tri[0]], ring[tri[1]], ring[tri[2]]};
        const Vec3 &p0 = mesh.point(w[0]), &p1 = mesh.point(w[1]), &p2 = mesh.point(w[2]), &p3 = mesh.point(w[3]);
        choice.worst_deg = std::min(choice.worst_deg, dihedral_extremes_deg(p0, p1, p2, p3).first);
        choice.unmet += breaks_bounds(state, region, p0, p1, p2, p3) ? 1 : 0;
        choice.tets.push_back(w);
      }
    }
    if (choice.unmet <= old_unmet && choice.worst_deg > old_worst) choices.push_back(std::move(choice));
  }
  std::stable_sort(choices.begin(), choices.end(),
                   [](const RingChoice& x, const RingChoice& y) { return x.worst_deg > y.worst_deg; });
  std::vector<std::uint32_t> created;
  for (const RingChoice& choice : choices) {
    // remove_edge keeps the triangulation whose tets are all this choice's (quality 1;
    // any other tet -1), its orientations checked exactly, or changes nothing.
    const TetQualityFn chosen = [&](const Vec3& p, const Vec3& q, const Vec3& r, const Vec3& s) {
      for (const auto& w : choice.tets) {
        int same = 0;
        for (const std::uint32_t x : w) {
          const Vec3& at = mesh.point(x);
          same += (at == p || at == q || at == r || at == s) ? 1 : 0;
        }
        if (same == 4) return 1.0;
      }
      return -1.0;
    };
    if (!remove_edge(mesh, c, d, 0.0, &created, chosen)) continue;
    if (state.tet_region.size() < mesh.tet_slots()) state.tet_region.resize(mesh.tet_slots(), kRegionExterior);
    for (const std::uint32_t u : created) state.tet_region[u] = region;
    return true;
  }
  return false;
}

/// Offers each in-domain tet with every vertex on the boundary and a dihedral angle
/// outside [low, high] to `attempt` (cheap filters first: the vertices, then the angles);
/// returns how many attempts succeeded.
template <typename Attempt>
std::size_t for_boundary_tets_outside(RefineState& state, double low, double high, Attempt attempt) {
  const TetMesh& mesh = state.mesh;
  std::size_t done = 0;
  for (std::uint32_t t = 0; t < mesh.tet_slots() && t < state.tet_region.size(); ++t) {
    if (mesh.is_dead(t) || mesh.is_infinite(t) || !in_domain(state.tet_region[t])) continue;
    const auto& v = mesh.tet(t).v;
    bool boundary = true;
    for (const std::uint32_t w : v) boundary = boundary && state.vertices[w].kind != VertexKind::Interior;
    if (!boundary) continue;
    if (!dihedral_outside(mesh.point(v[0]), mesh.point(v[1]), mesh.point(v[2]), mesh.point(v[3]), low, high)) continue;
    done += attempt(state, t) ? 1 : 0;
  }
  return done;
}

}  // namespace

std::size_t remove_flat_boundary_tets(RefineState& state, double low, double high) {
  return for_boundary_tets_outside(state, low, high, try_remove_flat);
}

std::size_t release_flat_facet_tets(RefineState& state, double low, double high) {
  return for_boundary_tets_outside(state, low, high, try_release);
}

}  // namespace delmesh::tet3d
