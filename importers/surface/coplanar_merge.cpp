// Coplanar merge of edge-adjacent faces into polygonal facets (surface_importer.h, step 8).
//
// Two faces sharing an edge are merged when every vertex of one lies exactly on the
// plane of the other (orient3d == 0) and they are not folded onto each other (their first
// non-collinear corners have the same in-plane orientation: exact for triangles; for a
// polygon face whose first corner is reflex this only prevents a merge). Merged groups are bounded by the group's boundary
// edges, chained into loops; a group is kept merged only when its boundary is a set of
// simple loops (no vertex with two outgoing boundary edges), exactly one of them outer
// (counterclockwise about the outward normal), each other one a hole for which an ear
// of the hole loop is found with exact in-plane orientations: the ear's centroid is the
// facet's hole point. A group interior vertex that other facets also use stays in the
// merged facet as a 1-vertex polygon.
#include <algorithm>
#include <numeric>

#include <Eigen/Geometry>

#include "importers/surface/surface_mesh.h"
#include "toolkit/predicates/predicates.h"

namespace delmesh::surface {
namespace {

using predicates::orient2d_projected;
using predicates::orient3d;

std::uint32_t find_root(std::vector<std::uint32_t>& parent, std::uint32_t x) {
  while (parent[x] != x) {
    parent[x] = parent[parent[x]];
    x = parent[x];
  }
  return x;
}

/// Three non-collinear vertices of face f (positions in the face), or false.
bool face_triple(const PolygonSurface& s, std::size_t f, std::uint32_t out[3]) {
  const std::uint32_t* v = s.face(f);
  const std::size_t n = s.degree(f);
  for (std::size_t k = 2; k < n; ++k) {
    for (Axis axis : {Axis::X, Axis::Y, Axis::Z}) {
      if (orient2d_projected(s.points[v[0]].data(), s.points[v[1]].data(), s.points[v[k]].data(), axis) !=
          Sign::Zero) {
        out[0] = v[0];
        out[1] = v[1];
        out[2] = v[k];
        return true;
      }
    }
  }
  return false;
}

struct InPlane {
  Axis axis = Axis::Z;
  Sign sign = Sign::Positive;
  Sign orient(const Vec3& a, const Vec3& b, const Vec3& c) const {
    return orient2d_projected(a.data(), b.data(), c.data(), axis) * sign;
  }
};

/// Centroid of an ear of a hole loop, which runs clockwise about the outward normal (the
/// hole region lies to its right), or nullopt.
std::optional<Vec3> hole_point(const std::vector<Vec3>& P, const std::vector<std::uint32_t>& loop,
                               const InPlane& plane) {
  const std::size_t n = loop.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3& p = P[loop[(i + n - 1) % n]];
    const Vec3& q = P[loop[i]];
    const Vec3& r = P[loop[(i + 1) % n]];
    if (plane.orient(p, q, r) != Sign::Negative) continue;  // not a convex corner of the hole
    bool empty = true;
    for (std::size_t j = 0; j < n && empty; ++j) {
      const Vec3& x = P[loop[j]];
      if (x == p || x == q || x == r) continue;
      // x in the closed triangle p q r (clockwise): all orientations <= 0.
      if (plane.orient(p, q, x) != Sign::Positive && plane.orient(q, r, x) != Sign::Positive &&
          plane.orient(r, p, x) != Sign::Positive) {
        empty = false;
      }
    }
    if (empty) return (p + q + r) / 3.0;
  }
  return std::nullopt;
}

/// Builds the merged facet of a group, or returns false (the group stays unmerged).
bool merged_facet(const PolygonSurface& s, const std::vector<std::uint32_t>& faces,
                  const std::vector<std::uint32_t>& group_of, const std::vector<std::uint32_t>& twin_face,
                  const std::vector<std::uint32_t>& vertex_groups_shared, Plc::Facet& facet) {
  const std::uint32_t group = group_of[faces[0]];
  std::vector<std::pair<std::uint32_t, std::uint32_t>> boundary;  // directed a -> b
  for (std::uint32_t f : faces) {
    const std::uint32_t* v = s.face(f);
    const std::size_t n = s.degree(f);
    for (std::size_t k = 0; k < n; ++k) {
      const std::uint32_t t = twin_face[s.start[f] + k];
      if (t != ~0u && group_of[t] == group) continue;
      boundary.emplace_back(v[k], v[(k + 1) % n]);
    }
  }
  std::sort(boundary.begin(), boundary.end());
  for (std::size_t i = 1; i < boundary.size(); ++i) {
    if (boundary[i].first == boundary[i - 1].first) return false;  // pinched boundary
  }
  auto next_of = [&](std::uint32_t a) -> std::uint32_t {
    const auto it = std::lower_bound(boundary.begin(), boundary.end(), std::make_pair(a, 0u));
    return (it != boundary.end() && it->first == a) ? it->second : ~0u;
  };
  std::vector<bool> used(boundary.size(), false);
  std::vector<std::vector<std::uint32_t>> loops;
  for (std::size_t i = 0; i < boundary.size(); ++i) {
    if (used[i]) continue;
    std::vector<std::uint32_t> loop;
    std::uint32_t a = boundary[i].first;
    const std::uint32_t first = a;
    do {
      const auto it = std::lower_bound(boundary.begin(), boundary.end(), std::make_pair(a, 0u));
      if (it == boundary.end() || it->first != a) return false;
      const std::size_t idx = static_cast<std::size_t>(it - boundary.begin());
      if (used[idx]) return false;
      used[idx] = true;
      loop.push_back(a);
      a = next_of(a);
      if (loop.size() > boundary.size()) return false;
    } while (a != first);
    loops.push_back(std::move(loop));
  }
  std::uint32_t triple[3];
  if (!face_triple(s, faces[0], triple)) return false;
  const Vec3& A = s.points[triple[0]];
  const Vec3& B = s.points[triple[1]];
  const Vec3& C = s.points[triple[2]];
  const Vec3 normal = (B - A).cross(C - A);
  InPlane plane;
  for (Axis axis : {Axis::X, Axis::Y, Axis::Z}) {
    const Sign sg = orient2d_projected(A.data(), B.data(), C.data(), axis);
    if (sg != Sign::Zero) {
      plane.axis = axis;
      plane.sign = sg;
      break;
    }
  }
  int outer = -1;
  std::vector<std::size_t> holes;
  for (std::size_t l = 0; l < loops.size(); ++l) {
    Vec3 newell = Vec3::Zero();
    const auto& loop = loops[l];
    for (std::size_t i = 0; i < loop.size(); ++i) {
      newell += s.points[loop[i]].cross(s.points[loop[(i + 1) % loop.size()]]);
    }
    const double d = newell.dot(normal);
    if (d > 0) {
      if (outer >= 0) return false;
      outer = static_cast<int>(l);
    } else if (d < 0) {
      holes.push_back(l);
    } else {
      return false;
    }
  }
  if (outer < 0) return false;
  facet.polygons.push_back(loops[static_cast<std::size_t>(outer)]);
  for (std::size_t l : holes) {
    const auto point = hole_point(s.points, loops[l], plane);
    if (!point) return false;
    facet.polygons.push_back(loops[l]);
    facet.holes.push_back(*point);
  }
  // Interior vertices that other facets use stay as isolated points of the facet.
  std::vector<std::uint32_t> on_loops;
  for (const auto& loop : loops) on_loops.insert(on_loops.end(), loop.begin(), loop.end());
  std::sort(on_loops.begin(), on_loops.end());
  std::vector<std::uint32_t> interior;
  for (std::uint32_t f : faces) {
    for (std::size_t k = 0; k < s.degree(f); ++k) {
      const std::uint32_t v = s.face(f)[k];
      if (!std::binary_search(on_loops.begin(), on_loops.end(), v) && vertex_groups_shared[v]) {
        interior.push_back(v);
      }
    }
  }
  std::sort(interior.begin(), interior.end());
  interior.erase(std::unique(interior.begin(), interior.end()), interior.end());
  for (std::uint32_t v : interior) facet.polygons.push_back({v});
  return true;
}

}  // namespace

std::size_t merge_coplanar_faces(const PolygonSurface& s, bool merge, Plc& plc,
                                 std::vector<std::uint32_t>* facet_face) {
  const std::size_t nf = s.size();
  // Twin of every face corner's outgoing edge: the other face on that edge (manifold).
  struct EdgeUse {
    std::uint64_t key;
    std::uint32_t corner;  ///< index into s.verts
    std::uint32_t face;
  };
  std::vector<EdgeUse> uses;
  uses.reserve(s.verts.size());
  for (std::uint32_t f = 0; f < nf; ++f) {
    const std::size_t n = s.degree(f);
    for (std::size_t k = 0; k < n; ++k) {
      const std::uint32_t a = s.face(f)[k], b = s.face(f)[(k + 1) % n];
      uses.push_back({(static_cast<std::uint64_t>(std::min(a, b)) << 32) | std::max(a, b),
                      static_cast<std::uint32_t>(s.start[f] + k), f});
    }
  }
  std::sort(uses.begin(), uses.end(), [](const EdgeUse& x, const EdgeUse& y) { return x.key < y.key; });
  std::vector<std::uint32_t> twin_face(s.verts.size(), ~0u);
  for (std::size_t i = 0; i + 1 < uses.size(); ++i) {
    if (uses[i].key != uses[i + 1].key) continue;
    if (i + 2 < uses.size() && uses[i + 2].key == uses[i].key) continue;  // non-manifold: no twin
    if (i > 0 && uses[i - 1].key == uses[i].key) continue;
    twin_face[uses[i].corner] = uses[i + 1].face;
    twin_face[uses[i + 1].corner] = uses[i].face;
  }

  std::vector<std::uint32_t> parent(nf);
  std::iota(parent.begin(), parent.end(), 0u);
  if (merge) {
    for (std::uint32_t f = 0; f < nf; ++f) {
      std::uint32_t triple[3];
      if (!face_triple(s, f, triple)) continue;
      for (std::size_t k = 0; k < s.degree(f); ++k) {
        const std::uint32_t g = twin_face[s.start[f] + k];
        if (g == ~0u || g < f || s.shell[g] != s.shell[f]) continue;
        bool coplanar = true;
        for (std::size_t j = 0; j < s.degree(g) && coplanar; ++j) {
          const std::uint32_t w = s.face(g)[j];
          if (w == triple[0] || w == triple[1] || w == triple[2]) continue;
          coplanar = orient3d(s.points[triple[0]].data(), s.points[triple[1]].data(),
                              s.points[triple[2]].data(), s.points[s.face(g)[j]].data()) == Sign::Zero;
        }
        // Coplanar and consistently oriented neighbours are either flat or folded onto
        // each other; only flat ones merge (same in-plane orientation of their triples).
        std::uint32_t other[3];
        if (coplanar && face_triple(s, g, other)) {
          for (Axis axis : {Axis::X, Axis::Y, Axis::Z}) {
            const Sign sf = orient2d_projected(s.points[triple[0]].data(), s.points[triple[1]].data(),
                                               s.points[triple[2]].data(), axis);
            if (sf == Sign::Zero) continue;
            const Sign sg = orient2d_projected(s.points[other[0]].data(), s.points[other[1]].data(),
                                               s.points[other[2]].data(), axis);
            coplanar = sf == sg;
            break;
          }
        }
        if (coplanar) {
          parent[find_root(parent, g)] = find_root(parent, f);
        }
      }
    }
  }
  std::vector<std::uint32_t> group_of(nf);
  for (std::uint32_t f = 0; f < nf; ++f) group_of[f] = find_root(parent, f);
  std::vector<std::vector<std::uint32_t>> members(nf);
  for (std::uint32_t f = 0; f < nf; ++f) members[group_of[f]].push_back(f);

  // Vertices used by two or more groups.
  std::vector<std::uint32_t> first_group(s.points.size(), ~0u), shared(s.points.size(), 0);
  for (std::uint32_t f = 0; f < nf; ++f) {
    for (std::size_t k = 0; k < s.degree(f); ++k) {
      const std::uint32_t v = s.face(f)[k];
      if (first_group[v] == ~0u) {
        first_group[v] = group_of[f];
      } else if (first_group[v] != group_of[f]) {
        shared[v] = 1;
      }
    }
  }

  std::size_t merged = 0;
  for (std::uint32_t f = 0; f < nf; ++f) {
    if (group_of[f] != f && members[group_of[f]].front() != f) continue;
    const auto& faces = members[group_of[f]];
    if (faces.front() != f) continue;
    const int marker = static_cast<int>(s.shell[f]) + 1;
    if (faces.size() > 1) {
      Plc::Facet facet;
      facet.marker = marker;
      if (merged_facet(s, faces, group_of, twin_face, shared, facet)) {
        plc.facets.push_back(std::move(facet));
        if (facet_face) facet_face->push_back(f);
        ++merged;
        continue;
      }
    }
    for (std::uint32_t g : faces) {
      Plc::Facet facet;
      facet.marker = marker;
      facet.polygons.emplace_back(s.face(g), s.face(g) + s.degree(g));
      plc.facets.push_back(std::move(facet));
      if (facet_face) facet_face->push_back(g);
    }
  }
  return merged;
}

}  // namespace delmesh::surface
