// Facet recovery as a conforming CDT by cavity retriangulation (see
// ccdt_facet_recovery.h; notes §2.1.4, §2.1.7, §4.2.1).
#include "refiners/tet3d/ccdt_facet_recovery.h"

#include <algorithm>
#include <array>
#include <numeric>
#include <string>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "refiners/tet3d/boundary_recovery.h"
#include "refiners/tet3d/boundary_split.h"
#include "refiners/tet3d/cavity_gift_wrap.h"
#include "toolkit/core/log.h"
#include "toolkit/predicates/predicates.h"
#include "toolkit/tetmesh/delaunay.h"

namespace delmesh::tet3d {

namespace {

/// Cavity enlargements by one tet allowed per region.
constexpr std::size_t kMaxEnlargements = 64;
/// Tets a region's cavity may hold, and tets its search may test.
constexpr std::size_t kMaxCavityTets = 20000;
constexpr std::size_t kMaxTestedTets = 200000;
/// CCDT passes before the rest is recovered the conforming way.
constexpr std::size_t kMaxRounds = 3;
/// Tets a gift-wrapped side may hold, per face of the side.
constexpr std::size_t kWrapTetsPerFace = 8;

/// The six edges of a tet as local vertex pairs.
constexpr int kTetEdges[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};

struct FaceKeyHash {
  std::size_t operator()(const FaceKey& k) const {
    return static_cast<std::size_t>((k[0] * 0x9E3779B97F4A7C15ULL) ^ (k[1] * 0xC2B2AE3D27D4EB4FULL) ^
                                    (k[2] * 0x165667B19E3779F9ULL));
  }
};

struct Box {
  Vec3 lo, hi;
  void add(const Vec3& p) {
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], p[k]);
      hi[k] = std::max(hi[k], p[k]);
    }
  }
  bool overlaps(const Box& o) const {
    for (int k = 0; k < 3; ++k)
      if (hi[k] < o.lo[k] || o.hi[k] < lo[k]) return false;
    return true;
  }
};

Box box_of(const TetMesh& mesh, std::initializer_list<std::uint32_t> vs) {
  Box b{mesh.point(*vs.begin()), mesh.point(*vs.begin())};
  for (const std::uint32_t v : vs) b.add(mesh.point(v));
  return b;
}

/// A connected region of missing subfacets of one facet, each counterclockwise in the
/// facet's orientation.
struct Region {
  std::uint32_t facet = 0;
  std::vector<std::array<std::uint32_t, 3>> faces;
  std::vector<Box> boxes;
  Box box;
  /// Interior edge -> index of one region face holding it.
  std::unordered_map<std::uint64_t, std::size_t> interior_edges;
  /// Boundary edge -> index of the region face holding it.
  std::unordered_map<std::uint64_t, std::size_t> boundary_edges;
  std::vector<std::uint32_t> vertices;
};

/// A boundary face of a cavity: vertices with the cavity on their positive side and the
/// encoded reference of the outside tet's face glued to it.
struct BoundaryFace {
  std::array<std::uint32_t, 3> v;
  std::uint32_t outside;
  std::uint32_t inside;  ///< encoded reference of the cavity tet's face
};

/// A face to recover on one side: vertices with that side's cavity on the positive side;
/// outside == kNone for a subfacet of the region.
struct SideFace {
  std::array<std::uint32_t, 3> v;
  std::uint32_t outside;
};

enum class Fill : std::uint8_t { Done, Enlarge, Fail };

/// Does the open segment pq, coplanar with the triangle abc (all exactly in one plane),
/// meet the triangle's open interior? Separating axes in a projection that keeps the
/// triangle non-degenerate: disjoint exactly when the triangle lies on one closed side of
/// the line pq or the segment on the closed outer side of one of its edges. Exact.
bool coplanar_segment_meets_triangle(const double* p, const double* q, const double* a, const double* b,
                                     const double* c) {
  for (const Axis axis : {Axis::X, Axis::Y, Axis::Z}) {
    const Sign o = predicates::orient2d_projected(a, b, c, axis);
    if (o == Sign::Zero) continue;
    const Sign sa = predicates::orient2d_projected(p, q, a, axis);
    const Sign sb = predicates::orient2d_projected(p, q, b, axis);
    const Sign sc = predicates::orient2d_projected(p, q, c, axis);
    const bool any_pos = sa == Sign::Positive || sb == Sign::Positive || sc == Sign::Positive;
    const bool any_neg = sa == Sign::Negative || sb == Sign::Negative || sc == Sign::Negative;
    if (!(any_pos && any_neg)) return false;
    const double* t[3] = {a, b, c};
    for (int k = 0; k < 3; ++k) {
      const Sign sp = predicates::orient2d_projected(t[k], t[(k + 1) % 3], p, axis) * o;
      const Sign sq = predicates::orient2d_projected(t[k], t[(k + 1) % 3], q, axis) * o;
      if (sp != Sign::Positive && sq != Sign::Positive) return false;
    }
    return true;
  }
  return false;
}

/// For a face f lying in the plane of the region's subfacet s: Positive when f and s
/// agree in orientation (exact orient2d in a projection keeping both non-degenerate),
/// Negative when opposite, Zero when no projection decides.
Sign coplanar_side(const TetMesh& mesh, const std::array<std::uint32_t, 3>& s, const std::array<std::uint32_t, 3>& f) {
  for (const Axis axis : {Axis::X, Axis::Y, Axis::Z}) {
    const Sign os = predicates::orient2d_projected(mesh.coords(s[0]), mesh.coords(s[1]), mesh.coords(s[2]), axis);
    const Sign of = predicates::orient2d_projected(mesh.coords(f[0]), mesh.coords(f[1]), mesh.coords(f[2]), axis);
    if (os != Sign::Zero && of != Sign::Zero) return os * of;
  }
  return Sign::Zero;
}

/// Does the edge (p, q) cross the relative interior of the region (a subfacet's open
/// interior or an open edge between two of its subfacets)? An edge in a subfacet's plane
/// crosses it when it meets the subfacet's open interior (a tetrahedralization face in the
/// plane overlaps the subfacet there).
bool edge_crosses(const TetMesh& mesh, std::uint32_t p, std::uint32_t q, const Region& region) {
  if (p == kInfiniteVertex || q == kInfiniteVertex) return false;
  const Box eb = box_of(mesh, {p, q});
  if (!eb.overlaps(region.box)) return false;
  const double* pp = mesh.coords(p);
  const double* pq = mesh.coords(q);
  for (std::size_t i = 0; i < region.faces.size(); ++i) {
    if (!eb.overlaps(region.boxes[i])) continue;
    const auto& f = region.faces[i];
    const double* a = mesh.coords(f[0]);
    const double* b = mesh.coords(f[1]);
    const double* c = mesh.coords(f[2]);
    const Sign op = predicates::orient3d(a, b, c, pp);
    const Sign oq = predicates::orient3d(a, b, c, pq);
    if (op == Sign::Zero && oq == Sign::Zero) {
      if (coplanar_segment_meets_triangle(pp, pq, a, b, c)) return true;
      continue;
    }
    if (op == Sign::Zero || oq == Sign::Zero || op == oq) continue;
    const Sign s[3] = {predicates::orient3d(pp, pq, a, b), predicates::orient3d(pp, pq, b, c),
                       predicates::orient3d(pp, pq, c, a)};
    int zeros = 0, zero_at = -1;
    Sign nonzero = Sign::Zero;
    bool mixed = false;
    for (int k = 0; k < 3; ++k) {
      if (s[k] == Sign::Zero) {
        ++zeros;
        zero_at = k;
      } else if (nonzero == Sign::Zero) {
        nonzero = s[k];
      } else if (s[k] != nonzero) {
        mixed = true;
      }
    }
    if (mixed || zeros > 1) continue;
    if (zeros == 0) return true;
    const std::uint64_t e = edge_key(f[static_cast<std::size_t>(zero_at)], f[static_cast<std::size_t>((zero_at + 1) % 3)]);
    if (region.interior_edges.count(e)) return true;
  }
  return false;
}

/// An infinite tet crosses when an edge of its hull face does (the region then lies in
/// the plane of that hull face).
bool tet_crosses(const TetMesh& mesh, std::uint32_t t, const Region& region) {
  const auto& v = mesh.tet(t).v;
  for (const auto& e : kTetEdges)
    if (edge_crosses(mesh, v[e[0]], v[e[1]], region)) return true;
  return false;
}

/// The tets with an edge crossing the region, by a search from the stars of its
/// vertices through face neighbours; false when the work bounds are exceeded.
bool crossing_tets(TetMesh& mesh, const Region& region, std::vector<std::uint32_t>& cavity) {
  std::unordered_set<std::uint32_t> tested;
  std::vector<std::uint32_t> stack, star;
  for (const std::uint32_t v : region.vertices) {
    mesh.star(v, star);
    for (const std::uint32_t t : star) {
      if (!tested.insert(t).second) continue;
      if (tet_crosses(mesh, t, region)) stack.push_back(t);
    }
  }
  cavity = stack;
  while (!stack.empty()) {
    const std::uint32_t t = stack.back();
    stack.pop_back();
    for (int i = 0; i < 4; ++i) {
      const std::uint32_t n = mesh.neighbor(t, i);
      if (!tested.insert(n).second) continue;
      if (tested.size() > kMaxTestedTets) return false;
      if (!tet_crosses(mesh, n, region)) continue;
      cavity.push_back(n);
      stack.push_back(n);
    }
    if (cavity.size() > kMaxCavityTets) return false;
  }
  std::sort(cavity.begin(), cavity.end());
  return true;
}

std::size_t find_root(std::vector<std::size_t>& parent, std::size_t x) {
  while (parent[x] != x) x = parent[x] = parent[parent[x]];
  return x;
}

/// Fills one side: the tets of the Delaunay tetrahedralization of the side's vertices
/// inside its faces, as global vertex ids. Enlarge: `grow` names the outside face of a
/// boundary face missing from that tetrahedralization.
Fill fill_side(const TetMesh& mesh, const std::vector<SideFace>& faces, std::uint32_t& grow,
               std::vector<std::array<std::uint32_t, 4>>& out) {
  std::vector<std::uint32_t> ids;
  for (const SideFace& f : faces) ids.insert(ids.end(), f.v.begin(), f.v.end());
  std::sort(ids.begin(), ids.end());
  ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
  std::vector<Vec3> points;
  points.reserve(ids.size());
  for (const std::uint32_t v : ids) points.push_back(mesh.point(v));
  // Points in increasing global id: the perturbation of insphere_sos orders them as the
  // whole mesh does.
  auto dt = delaunay_tetrahedralize(std::span<const Vec3>(points));
  if (!dt || dt->num_duplicates > 0) return Fill::Fail;
  TetMesh& local = dt->mesh;
  auto local_id = [&](std::uint32_t g) {
    return static_cast<std::uint32_t>(std::lower_bound(ids.begin(), ids.end(), g) - ids.begin()) + 1;
  };
  std::unordered_set<FaceKey, FaceKeyHash> constraint;
  std::vector<std::uint32_t> seeds;
  for (const SideFace& f : faces) {
    const std::uint32_t l[3] = {local_id(f.v[0]), local_id(f.v[1]), local_id(f.v[2])};
    const auto ref = local.find_face(l[0], l[1], l[2]);
    if (!ref) {
      if (f.outside == kNone) return Fill::Fail;
      grow = f.outside;
      return Fill::Enlarge;
    }
    const auto fv = local.face_vertices(*ref);
    int at = 0;
    while (fv[static_cast<std::size_t>(at)] != l[0]) ++at;
    const bool same = fv[static_cast<std::size_t>((at + 1) % 3)] == l[1];
    const std::uint32_t inside = same ? ref->tet : local.mirror(*ref).tet;
    if (local.is_infinite(inside)) return Fill::Fail;
    seeds.push_back(inside);
    constraint.insert(sorted_face_key(l[0], l[1], l[2]));
  }
  std::vector<std::uint8_t> in(local.tet_slots(), 0);
  std::vector<std::uint32_t> stack;
  for (const std::uint32_t t : seeds) {
    if (in[t]) continue;
    in[t] = 1;
    stack.push_back(t);
  }
  std::vector<std::uint32_t> inside_tets;
  while (!stack.empty()) {
    const std::uint32_t t = stack.back();
    stack.pop_back();
    inside_tets.push_back(t);
    for (int i = 0; i < 4; ++i) {
      const auto fv = local.face_vertices({t, static_cast<std::uint8_t>(i)});
      if (constraint.count(sorted_face_key(fv[0], fv[1], fv[2]))) continue;
      const std::uint32_t n = local.neighbor(t, i);
      if (local.is_infinite(n)) return Fill::Fail;
      if (in[n]) continue;
      in[n] = 1;
      stack.push_back(n);
    }
  }
  // Every constraint face must separate an inside tet from an outside one.
  for (const SideFace& f : faces) {
    const auto ref = local.find_face(local_id(f.v[0]), local_id(f.v[1]), local_id(f.v[2]));
    if (in[ref->tet] + in[local.mirror(*ref).tet] != 1) return Fill::Fail;
  }
  std::sort(inside_tets.begin(), inside_tets.end());
  for (const std::uint32_t t : inside_tets) {
    const auto& v = local.tet(t).v;
    out.push_back({ids[v[0] - 1], ids[v[1] - 1], ids[v[2] - 1], ids[v[3] - 1]});
  }
  return Fill::Done;
}

/// Are the new tets constrained Delaunay across every face that is no subfacet: the apex
/// of the tet on one side not strictly inside the other's circumsphere (the property
/// check_mesh verifies; gift-wrapping's choice of apex among visible vertices only gives
/// it when the cavity has a CDT)?
bool locally_constrained_delaunay(const RefineState& state, const std::vector<std::array<std::uint32_t, 4>>& fresh,
                                  const std::unordered_map<FaceKey, std::uint32_t, FaceKeyHash>& outside) {
  const TetMesh& mesh = state.mesh;
  std::unordered_map<FaceKey, std::pair<std::size_t, std::uint32_t>, FaceKeyHash> first;  // tet, apex
  auto inside_sphere = [&](const std::array<std::uint32_t, 4>& t, std::uint32_t apex) {
    return predicates::insphere(mesh.coords(t[0]), mesh.coords(t[1]), mesh.coords(t[2]), mesh.coords(t[3]),
                                mesh.coords(apex)) == Sign::Positive;
  };
  for (std::size_t i = 0; i < fresh.size(); ++i) {
    const auto& t = fresh[i];
    if (std::find(t.begin(), t.end(), kInfiniteVertex) != t.end()) continue;
    for (int k = 0; k < 4; ++k) {
      const auto& fv = kFaceVertex[k];
      const FaceKey key = sorted_face_key(t[fv[0]], t[fv[1]], t[fv[2]]);
      if (state.subfaces.lookup(key)) continue;
      if (const auto it = outside.find(key); it != outside.end()) {
        const std::uint32_t n = it->second >> 2;
        if (mesh.is_infinite(n)) continue;
        if (inside_sphere(t, mesh.tet(n).v[it->second & 3])) return false;
      } else if (const auto [at, added] = first.emplace(key, std::pair{i, t[static_cast<std::size_t>(k)]}); !added) {
        if (inside_sphere(fresh[at->second.first], t[static_cast<std::size_t>(k)]) ||
            inside_sphere(t, at->second.second))
          return false;
      }
    }
  }
  return true;
}

bool fail(CcdtCounts& counts, CcdtFailure why) {
  ++counts.failures[static_cast<std::size_t>(why)];
  return false;
}

/// Recovers one region by cavity retriangulation; false (mesh unchanged) on failure.
bool recover_region(RefineState& state, const Region& region, CcdtCounts& counts) {
  TetMesh& mesh = state.mesh;
  std::vector<std::uint32_t> cavity;
  if (!crossing_tets(mesh, region, cavity) || cavity.empty()) return fail(counts, CcdtFailure::NoCrossingEdge);
  for (std::size_t round = 0; round <= kMaxEnlargements; ++round) {
    std::unordered_set<std::uint32_t> in_cavity(cavity.begin(), cavity.end());
    // Boundary faces, with the cavity on their positive side.
    std::vector<BoundaryFace> boundary;
    std::unordered_map<std::uint32_t, std::size_t> boundary_at;  // 4 * cavity tet + face -> index
    for (const std::uint32_t t : cavity) {
      for (int i = 0; i < 4; ++i) {
        if (in_cavity.count(mesh.neighbor(t, i))) continue;
        const std::uint32_t ref = 4 * t + static_cast<std::uint32_t>(i);
        boundary_at.emplace(ref, boundary.size());
        boundary.push_back({mesh.face_vertices({t, static_cast<std::uint8_t>(i)}), mesh.tet(t).adj[i], ref});
      }
    }
    // Every cavity vertex must stay: on the boundary or on the region.
    {
      std::unordered_set<std::uint32_t> kept(region.vertices.begin(), region.vertices.end());
      kept.insert(kInfiniteVertex);
      for (const BoundaryFace& f : boundary) kept.insert(f.v.begin(), f.v.end());
      for (const std::uint32_t t : cavity)
        for (const std::uint32_t v : mesh.tet(t).v)
          if (!kept.count(v)) return fail(counts, CcdtFailure::SplitSurface);
    }
    // The side of each boundary face: +1 on the region's positive side, -1 on the other.
    std::vector<int> face_side(boundary.size(), 0);
    // A region in a hull face's plane: the cavity holds infinite tets, and its side
    // beyond the hull (`beyond`) is the cone from the infinite vertex over the region and
    // the hull faces in the plane; every other face is on the side of the mesh.
    const bool hull = std::any_of(cavity.begin(), cavity.end(), [&](std::uint32_t t) { return mesh.is_infinite(t); });
    int beyond = 0;
    if (hull) {
      const auto& s0 = region.faces[0];
      auto plane_sign = [&](std::uint32_t v) {
        return predicates::orient3d(mesh.coords(s0[0]), mesh.coords(s0[1]), mesh.coords(s0[2]), mesh.coords(v));
      };
      for (const std::uint32_t t : cavity) {
        if (beyond != 0 || mesh.is_infinite(t)) continue;
        for (const std::uint32_t v : mesh.tet(t).v)
          if (const Sign o = plane_sign(v); o != Sign::Zero) beyond = o == Sign::Positive ? -1 : 1;
      }
      if (beyond == 0) return fail(counts, CcdtFailure::SplitSurface);
      for (std::size_t i = 0; i < boundary.size(); ++i) {
        const auto& f = boundary[i].v;
        if (std::find(f.begin(), f.end(), kInfiniteVertex) != f.end()) {
          face_side[i] = beyond;
        } else if (plane_sign(f[0]) == Sign::Zero && plane_sign(f[1]) == Sign::Zero && plane_sign(f[2]) == Sign::Zero) {
          const Sign o = coplanar_side(mesh, s0, f);
          if (o == Sign::Zero) return fail(counts, CcdtFailure::SplitSurface);
          face_side[i] = o == Sign::Positive ? 1 : -1;
        } else {
          face_side[i] = -beyond;
        }
      }
    } else {
      // The boundary surface must be a closed 2-manifold away from the region and pass
      // through every boundary edge of the region; an interior edge of the region that is
      // already an edge of the mesh may lie on it too (the cavity is pinched there, once on
      // each side it reaches). Its faces split into components along the region's edges.
      std::unordered_map<std::uint64_t, std::vector<std::size_t>> edge_faces;
      for (std::size_t i = 0; i < boundary.size(); ++i)
        for (int k = 0; k < 3; ++k) edge_faces[edge_key(boundary[i].v[k], boundary[i].v[(k + 1) % 3])].push_back(i);
      std::vector<std::size_t> parent(boundary.size());
      std::iota(parent.begin(), parent.end(), std::size_t{0});
      auto region_face_at = [&](std::uint64_t e) -> const std::array<std::uint32_t, 3>* {
        if (const auto it = region.boundary_edges.find(e); it != region.boundary_edges.end()) return &region.faces[it->second];
        if (const auto it = region.interior_edges.find(e); it != region.interior_edges.end()) return &region.faces[it->second];
        return nullptr;
      };
      for (const auto& [e, list] : edge_faces) {
        if (region_face_at(e)) {
          if (list.size() != 2 && list.size() != 4) return fail(counts, CcdtFailure::SplitSurface);
          continue;
        }
        if (list.size() % 2 != 0) return fail(counts, CcdtFailure::SplitSurface);
        if (list.size() == 2) {
          parent[find_root(parent, list[0])] = find_root(parent, list[1]);
          continue;
        }
        // The cavity is pinched at e, which the region does not touch: each boundary face
        // at e goes with the one reached by turning about e through cavity tets (the wedge
        // between them is one piece of the cavity, on one side of the region).
        for (const std::size_t i : list) {
          const std::uint32_t a = static_cast<std::uint32_t>(e >> 32), b = static_cast<std::uint32_t>(e);
          std::uint32_t t = boundary[i].inside >> 2;
          int entered = static_cast<int>(boundary[i].inside & 3);
          for (std::size_t steps = 0; steps <= cavity.size(); ++steps) {
            const auto& v = mesh.tet(t).v;
            int other = -1;
            for (int k = 0; k < 4; ++k)
              if (k != entered && v[k] != a && v[k] != b) other = k;
            const std::uint32_t n = mesh.neighbor(t, other);
            if (!in_cavity.count(n)) {
              const std::size_t j = boundary_at.at(4 * t + static_cast<std::uint32_t>(other));
              parent[find_root(parent, i)] = find_root(parent, j);
              break;
            }
            entered = static_cast<int>(mesh.tet(t).adj[other] & 3);
            t = n;
          }
        }
      }
      for (const auto& [e, face] : region.boundary_edges)
        if (!edge_faces.count(e)) return fail(counts, CcdtFailure::SplitSurface);
      // The side of each component: the sign of its apexes over the region's subfacets.
      std::vector<int> side(boundary.size(), 0);
      for (const auto& [e, list] : edge_faces) {
        const auto* s = region_face_at(e);
        if (!s) continue;
        for (const std::size_t i : list) {
          const auto& f = boundary[i].v;
          std::uint32_t apex = kNone;
          for (const std::uint32_t v : f)
            if (v != static_cast<std::uint32_t>(e >> 32) && v != static_cast<std::uint32_t>(e))
              apex = v;
          const Sign o = predicates::orient3d(mesh.coords((*s)[0]), mesh.coords((*s)[1]), mesh.coords((*s)[2]), mesh.coords(apex));
          if (o == Sign::Zero) continue;
          const int sign = o == Sign::Positive ? 1 : -1;
          int& r = side[find_root(parent, i)];
          if (r == -sign) return fail(counts, CcdtFailure::SplitSurface);
          r = sign;
        }
      }
      for (std::size_t i = 0; i < boundary.size(); ++i) face_side[i] = side[find_root(parent, i)];
    }
    std::vector<SideFace> upper, lower;
    for (std::size_t i = 0; i < boundary.size(); ++i) {
      const int s = face_side[i];
      if (s == 0) return fail(counts, CcdtFailure::SplitSurface);
      (s > 0 ? upper : lower).push_back({boundary[i].v, boundary[i].outside});
    }
    if (upper.empty() || lower.empty()) return fail(counts, CcdtFailure::SplitSurface);
    for (const auto& f : region.faces) {
      upper.push_back({f, kNone});
      lower.push_back({{f[0], f[2], f[1]}, kNone});
    }
    std::vector<std::array<std::uint32_t, 4>> fresh;
    std::uint32_t grow = kNone;
    // Each side: the Delaunay tetrahedralization of its vertices, or where that lacks
    // one of its faces, constrained gift-wrapping (cavity_gift_wrap.h).
    Fill fill = Fill::Done;
    std::size_t wrapped = 0;
    for (const std::vector<SideFace>* faces : {&upper, &lower}) {
      if (hull && faces == (beyond > 0 ? &upper : &lower)) {
        // The cone from the infinite vertex: an infinite tet over each finite face, the
        // outside across it (tet_mesh.h's convention for infinite tets).
        for (const SideFace& sf : *faces)
          if (std::find(sf.v.begin(), sf.v.end(), kInfiniteVertex) == sf.v.end())
            fresh.push_back({sf.v[0], sf.v[1], sf.v[2], kInfiniteVertex});
        continue;
      }
      const Fill f = fill_side(mesh, *faces, grow, fresh);
      if (f == Fill::Done) continue;
      std::vector<std::array<std::uint32_t, 3>> walls;
      for (const SideFace& sf : *faces) walls.push_back(sf.v);
      if (gift_wrap_cavity(mesh, walls, kWrapTetsPerFace * walls.size(), fresh)) {
        ++wrapped;
        continue;
      }
      fill = f;
      break;
    }
    if (fill == Fill::Fail) return fail(counts, CcdtFailure::FaceMissing);
    if (fill == Fill::Enlarge) {
      const std::uint32_t t = grow >> 2;
      if (mesh.is_infinite(t) || round == kMaxEnlargements) return fail(counts, CcdtFailure::FaceMissing);
      cavity.insert(std::lower_bound(cavity.begin(), cavity.end(), t), t);
      ++counts.enlargements;
      continue;
    }
    // Every boundary face exactly once among the new faces, every other face twice.
    std::unordered_map<FaceKey, std::uint32_t, FaceKeyHash> outside;
    for (const BoundaryFace& f : boundary) outside.emplace(sorted_face_key(f.v[0], f.v[1], f.v[2]), f.outside);
    std::unordered_map<FaceKey, int, FaceKeyHash> uses;
    for (const auto& t : fresh)
      for (const auto& fv : kFaceVertex) ++uses[sorted_face_key(t[fv[0]], t[fv[1]], t[fv[2]])];
    for (const auto& [key, n] : uses)
      if (n != (outside.count(key) ? 1 : 2)) return fail(counts, CcdtFailure::Gluing);
    for (const auto& [key, ref] : outside)
      if (!uses.count(key)) return fail(counts, CcdtFailure::Gluing);
    if (wrapped > 0 && !locally_constrained_delaunay(state, fresh, outside)) return fail(counts, CcdtFailure::NotDelaunay);
    // Commit.
    for (const std::uint32_t t : cavity) mesh.kill_tet(t);
    std::unordered_map<FaceKey, std::uint32_t, FaceKeyHash> open;
    for (const auto& v : fresh) {
      const std::uint32_t t = mesh.create_tet(v[0], v[1], v[2], v[3]);
      for (int i = 0; i < 4; ++i) {
        const auto& fv = kFaceVertex[i];
        const FaceKey key = sorted_face_key(v[fv[0]], v[fv[1]], v[fv[2]]);
        if (const auto it = outside.find(key); it != outside.end()) {
          mesh.glue_ref(t, i, it->second);
          continue;
        }
        const auto [it, added] = open.emplace(key, 4 * t + static_cast<std::uint32_t>(i));
        if (!added) {
          mesh.glue_ref(t, i, it->second);
          open.erase(it);
        }
      }
      for (const std::uint32_t u : v) mesh.set_vertex_tet(u, t);
    }
    if (state.tet_region.size() < mesh.tet_slots()) state.tet_region.resize(mesh.tet_slots(), kRegionUnknown);
    ++state.cavity_serial;
    counts.gift_wrapped_sides += wrapped;
    return true;
  }
  return fail(counts, CcdtFailure::FaceMissing);
}

/// The connected regions of missing subfacets (sharing non-segment edges), per facet,
/// in a deterministic order.
std::vector<Region> missing_regions(RefineState& state) {
  std::vector<FaceKey> missing;
  for (const auto& [key, facet] : state.subfaces)
    if (!find_face_ref(state, key[0], key[1], key[2])) missing.push_back(key);
  std::sort(missing.begin(), missing.end());
  std::vector<std::size_t> parent(missing.size());
  std::iota(parent.begin(), parent.end(), std::size_t{0});
  std::unordered_map<std::uint64_t, std::size_t> first;
  for (std::size_t i = 0; i < missing.size(); ++i) {
    const FaceKey& k = missing[i];
    const std::uint32_t facet = state.subfaces.at(k);
    for (int e = 0; e < 3; ++e) {
      const std::uint32_t a = k[static_cast<std::size_t>(e)], b = k[static_cast<std::size_t>((e + 1) % 3)];
      if (state.facets[facet].is_segment(a, b)) continue;
      const auto [it, added] = first.emplace(edge_key(a, b), i);
      if (!added && state.subfaces.at(missing[it->second]) == facet)
        parent[find_root(parent, i)] = find_root(parent, it->second);
    }
  }
  std::vector<Region> regions;
  std::unordered_map<std::size_t, std::size_t> region_of_root;
  for (std::size_t i = 0; i < missing.size(); ++i) {
    const std::size_t root = find_root(parent, i);
    const auto [it, added] = region_of_root.emplace(root, regions.size());
    if (added) regions.emplace_back();
    Region& r = regions[it->second];
    r.facet = state.subfaces.at(missing[i]);
    std::array<std::uint32_t, 3> f = missing[i];
    const FacetTriangulation& tri = state.facets[r.facet];
    if (tri.third_vertex(f[0], f[1]) != f[2]) std::swap(f[1], f[2]);
    r.faces.push_back(f);
  }
  for (Region& r : regions) {
    std::unordered_map<std::uint64_t, std::pair<int, std::size_t>> edges;
    for (std::size_t i = 0; i < r.faces.size(); ++i) {
      const auto& f = r.faces[i];
      r.boxes.push_back(box_of(state.mesh, {f[0], f[1], f[2]}));
      for (int e = 0; e < 3; ++e) {
        auto& [n, face] = edges[edge_key(f[static_cast<std::size_t>(e)], f[static_cast<std::size_t>((e + 1) % 3)])];
        ++n;
        face = i;
      }
      r.vertices.insert(r.vertices.end(), f.begin(), f.end());
    }
    r.box = r.boxes[0];
    for (const Box& b : r.boxes) {
      r.box.add(b.lo);
      r.box.add(b.hi);
    }
    for (const auto& [e, use] : edges) {
      if (use.first == 1)
        r.boundary_edges.emplace(e, use.second);
      else
        r.interior_edges.emplace(e, use.second);
    }
    std::sort(r.vertices.begin(), r.vertices.end());
    r.vertices.erase(std::unique(r.vertices.begin(), r.vertices.end()), r.vertices.end());
  }
  return regions;
}

/// Replaces the tetrahedralization by the Delaunay tetrahedralization of the same
/// vertices (those in some tet), perturbed by vertex id as the refinement's insertions
/// are, so that the conforming recovery can work on it.
Expected<void> rebuild_delaunay(RefineState& state) {
  const TetMesh& mesh = state.mesh;
  std::vector<std::uint32_t> used;
  std::vector<Vec3> points;
  for (std::uint32_t v = 1; v < mesh.num_vertices(); ++v) {
    if (mesh.vertex_tet(v) == kNone) continue;
    used.push_back(v);
    points.push_back(mesh.point(v));
  }
  auto dt = delaunay_tetrahedralize(std::move(points));
  if (!dt) return dt.error();
  TetMesh fresh(std::vector<Vec3>(mesh.points().begin() + 1, mesh.points().end()));
  const TetMesh& built = dt->mesh;
  for (std::uint32_t t = 0; t < built.tet_slots(); ++t) {
    const auto& v = built.tet(t).v;
    auto map = [&](std::uint32_t x) { return x == kInfiniteVertex ? kInfiniteVertex : used[x - 1]; };
    const std::uint32_t n = fresh.create_tet(map(v[0]), map(v[1]), map(v[2]), map(v[3]));
    fresh.tet(n).adj = built.tet(t).adj;
  }
  fresh.rebuild_vertex_tets();
  state.mesh = std::move(fresh);
  state.tet_region.assign(state.mesh.tet_slots(), kRegionUnknown);
  ++state.cavity_serial;
  return {};
}

/// Figure 4.8 without Steiner points: where a missing subfacet and its neighbour have
/// cocircular vertices whose other diagonal the tetrahedralization holds, the facet
/// triangulation is flipped to match. Returns the number of flips.
std::size_t match_cocircular_subfaces(RefineState& state, CcdtCounts& counts) {
  std::size_t flips = 0;
  for (int pass = 0; pass < 8; ++pass) {
    std::vector<FaceKey> missing;
    for (const auto& [key, facet] : state.subfaces)
      if (!find_face_ref(state, key[0], key[1], key[2])) missing.push_back(key);
    std::sort(missing.begin(), missing.end());
    std::size_t done = 0;
    for (const FaceKey& key : missing) {
      const auto it = state.subfaces.find(key);
      if (it == state.subfaces.end() || find_face_ref(state, key[0], key[1], key[2])) continue;
      if (match_cocircular(state, it->second, key)) ++done;
    }
    flips += done;
    if (done == 0) break;
  }
  // The flips queued their new subfacets for the conforming loop, which is not running.
  state.subface_queue.clear();
  counts.cocircular_flips += flips;
  return flips;
}

/// Recovers the subfacets of `facets` (all facets when empty) the conforming way.
Expected<void> recover_conforming(RefineState& state, const std::vector<std::uint32_t>& facets) {
  const std::unordered_set<std::uint32_t> wanted(facets.begin(), facets.end());
  for (const auto& [key, facet] : state.subfaces)
    if (wanted.empty() || wanted.count(facet)) state.subface_queue.push_back({key});
  std::sort(state.subface_queue.begin(), state.subface_queue.end(),
            [](const SubfaceTask& x, const SubfaceTask& y) { return x.face > y.face; });
  return restore_conformity(state, false);
}

}  // namespace

Expected<CcdtCounts> recover_facets_ccdt(RefineState& state) {
  CcdtCounts counts;
  std::unordered_set<std::uint32_t> fallback;
  for (std::size_t round = 0; round < kMaxRounds; ++round) {
    match_cocircular_subfaces(state, counts);
    const std::vector<Region> regions = missing_regions(state);
    if (regions.empty()) break;
    ++counts.rounds;
    std::vector<std::uint32_t> failed;
    for (const Region& region : regions) {
      // An earlier region's retriangulation may have recovered some of these subfacets:
      // the next round takes what is left.
      const bool untouched = std::all_of(region.faces.begin(), region.faces.end(), [&](const auto& f) {
        return !find_face_ref(state, f[0], f[1], f[2]);
      });
      if (!untouched) continue;
      ++counts.regions;
      if (recover_region(state, region, counts)) {
        ++counts.recovered_regions;
        continue;
      }
      ++counts.failed_regions;
      failed.push_back(region.facet);
    }
    if (failed.empty()) continue;
    std::sort(failed.begin(), failed.end());
    failed.erase(std::unique(failed.begin(), failed.end()), failed.end());
    fallback.insert(failed.begin(), failed.end());
    // The conforming recovery needs a Delaunay tetrahedralization: the CCDT work of this
    // round is redone by the next one.
    if (auto ok = rebuild_delaunay(state); !ok) return ok.error();
    if (auto ok = recover_conforming(state, failed); !ok) return ok.error();
  }
  const std::vector<Region> left = missing_regions(state);
  if (!left.empty()) {
    for (const Region& region : left) fallback.insert(region.facet);
    if (auto ok = rebuild_delaunay(state); !ok) return ok.error();
    if (auto ok = recover_conforming(state, {}); !ok) return ok.error();
  }
  counts.fallback_facets = fallback.size();
  if (counts.failed_regions > 0) {
    log(state.options.log, LogLevel::Info,
        "ccdt: " + std::to_string(counts.failed_regions) + " regions failed: " +
            std::to_string(counts.failures[0]) + " without a crossing edge or over the work bound, " +
            std::to_string(counts.failures[1]) + " whose cavity surface does not split in two sides, " +
            std::to_string(counts.failures[2]) + " with a face missing after enlargements, " +
            std::to_string(counts.failures[3]) + " with inconsistent gluing, " +
            std::to_string(counts.failures[4]) + " gift-wrapped but not constrained Delaunay");
  }
  return counts;
}

}  // namespace delmesh::tet3d
