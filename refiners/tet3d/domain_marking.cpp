// Domain marking by flood fill blocked by subfacets (see domain_marking.h).
#include "refiners/tet3d/domain_marking.h"

#include "toolkit/tetmesh/tet_locate.h"

namespace delmesh::tet3d {

namespace {

constexpr int kUnset = kRegionUnknown;

/// Floods `value` from `seed` over tets still kUnset, without crossing subfacets.
void flood(RefineState& state, std::uint32_t seed, int value, std::vector<std::uint32_t>& stack) {
  TetMesh& mesh = state.mesh;
  if (state.tet_region[seed] != kUnset) return;
  state.tet_region[seed] = value;
  stack.clear();
  stack.push_back(seed);
  while (!stack.empty()) {
    const std::uint32_t t = stack.back();
    stack.pop_back();
    const TetRecord& r = mesh.tet(t);
    // The neighbours' marks and records lie anywhere in their arrays: fetch all four
    // before the first is read, so that their cache misses overlap.
    for (int f = 0; f < 4; ++f) {
      __builtin_prefetch(&state.tet_region[r.adj[f] >> 2]);
      __builtin_prefetch(&mesh.tet(r.adj[f] >> 2));
    }
    for (int f = 0; f < 4; ++f) {
      const std::uint32_t n = r.adj[f] >> 2;
      if (state.tet_region[n] != kUnset) continue;
      const auto& o = kFaceVertex[f];
      if (subface_of(state, r.v[o[0]], r.v[o[1]], r.v[o[2]])) continue;
      state.tet_region[n] = value;
      stack.push_back(n);
    }
  }
}

/// The finite tet holding p, or kNone when p is outside the hull.
std::uint32_t tet_at(RefineState& state, const Vec3& p) {
  std::uint64_t rng = 0x2545F4914F6CDD1DULL;
  const Location loc = locate(state.mesh, p.data(), kNone, rng);
  if (loc.kind == LocationKind::OutsideHull || loc.tet == kNone) return kNone;
  return state.mesh.is_infinite(loc.tet) ? kNone : loc.tet;
}

}  // namespace

void mark_domain(RefineState& state) {
  TetMesh& mesh = state.mesh;
  state.tet_region.assign(mesh.tet_slots(), kUnset);
  std::vector<std::uint32_t> stack;
  for (std::uint32_t t = 0; t < mesh.tet_slots(); ++t) {
    if (mesh.is_dead(t)) {
      state.tet_region[t] = kRegionExterior;
      continue;
    }
    if (!mesh.is_infinite(t)) continue;
    if (state.options.keep_convex_hull) {
      state.tet_region[t] = kRegionExterior;
    } else {
      state.tet_region[t] = kUnset;
    }
  }
  if (state.options.keep_convex_hull) {
    // Infinite tets are outside; the finite tets reached from the hull without crossing
    // a subfacet are kept as region -1.
    for (std::uint32_t t = 0; t < mesh.tet_slots(); ++t) {
      if (mesh.is_dead(t) || !mesh.is_infinite(t)) continue;
      const int k = mesh.infinite_index(t);
      const std::uint32_t n = mesh.neighbor(t, k);
      const auto f = mesh.face_vertices({t, static_cast<std::uint8_t>(k)});
      if (!state.subfaces.count(face_key(f[0], f[1], f[2]))) flood(state, n, -1, stack);
    }
  } else {
    for (std::uint32_t t = 0; t < mesh.tet_slots(); ++t)
      if (!mesh.is_dead(t) && mesh.is_infinite(t)) flood(state, t, kRegionExterior, stack);
  }
  for (const Vec3& h : state.plc.holes) {
    const std::uint32_t t = tet_at(state, h);
    if (t != kNone) flood(state, t, kRegionHole, stack);
  }
  for (const Plc::Region& r : state.plc.regions) {
    const std::uint32_t t = tet_at(state, r.point);
    if (t != kNone) flood(state, t, r.id, stack);
  }
  for (std::uint32_t t = 0; t < mesh.tet_slots(); ++t)
    if (state.tet_region[t] == kUnset) flood(state, t, 0, stack);
  state.domain_marked = true;
}

void remark_new_tets(RefineState& state, const std::vector<std::uint32_t>& created) {
  TetMesh& mesh = state.mesh;
  auto& reset = state.scratch_tets;
  auto& old_marks = state.scratch_regions;
  reset.clear();
  old_marks.clear();
  for (const std::uint32_t t : created) {
    if (mesh.is_dead(t) || mesh.is_infinite(t) || state.tet_region[t] == kUnset) continue;
    reset.push_back(t);
    old_marks.push_back(state.tet_region[t]);
    state.tet_region[t] = kUnset;
  }
  // Infinite tets are exterior; with the convex hull kept, what touches them across a
  // face that is not a subfacet is region -1 (mark_domain).
  const int beyond_hull = state.options.keep_convex_hull ? -1 : kRegionExterior;
  // Called after every insertion of the quality stage: reuse the state's scratch stack
  // rather than allocating one per call.
  auto& stack = state.scratch_ring;
  for (const std::uint32_t t : reset) {
    if (state.tet_region[t] != kUnset) continue;
    const TetRecord& r = mesh.tet(t);
    for (int f = 0; f < 4; ++f) {
      const std::uint32_t n = r.adj[f] >> 2;
      if (state.tet_region[n] == kUnset) continue;
      const auto& o = kFaceVertex[f];
      if (subface_of(state, r.v[o[0]], r.v[o[1]], r.v[o[2]])) continue;
      flood(state, t, mesh.is_infinite(n) ? beyond_hull : state.tet_region[n], stack);
      break;
    }
  }
  for (std::size_t k = 0; k < reset.size(); ++k)
    if (state.tet_region[reset[k]] == kUnset) state.tet_region[reset[k]] = old_marks[k];
}

}  // namespace delmesh::tet3d
