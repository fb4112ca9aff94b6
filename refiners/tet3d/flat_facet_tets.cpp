// Flat tets lying on a facet (see flat_facet_tets.h).
#include "refiners/tet3d/flat_facet_tets.h"

#include <array>

#include "toolkit/quality/tet_quality.h"

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
  auto change = state.facets[f]->flip_edge(vx, vy);
  if (!change) return false;
  for (const Subface& s : change->removed) state.subfaces.erase(face_key(s[0], s[1], s[2]));
  for (const Subface& s : change->added) state.subfaces[face_key(s[0], s[1], s[2])] = f;
  state.tet_region[t] = other;
  return true;
}

}  // namespace

std::size_t release_flat_facet_tets(RefineState& state, double low, double high) {
  const TetMesh& mesh = state.mesh;
  std::size_t released = 0;
  for (std::uint32_t t = 0; t < mesh.tet_slots() && t < state.tet_region.size(); ++t) {
    if (mesh.is_dead(t) || mesh.is_infinite(t) || !in_domain(state.tet_region[t])) continue;
    const auto& v = mesh.tet(t).v;
    // Cheap filters first: every vertex on the boundary, then the angles.
    bool boundary = true;
    for (const std::uint32_t w : v) boundary = boundary && state.vertices[w].kind != VertexKind::Interior;
    if (!boundary) continue;
    if (!dihedral_outside(mesh.point(v[0]), mesh.point(v[1]), mesh.point(v[2]), mesh.point(v[3]), low, high)) continue;
    released += try_release(state, t) ? 1 : 0;
  }
  return released;
}

}  // namespace delmesh::tet3d
