// Vertex insertion and subsegment/subfacet splits (see boundary_split.h; notes §4.2.1).
#include "refiners/tet3d/boundary_split.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>

#include "refiners/tet3d/narrow_facet_floor.h"
#include "refiners/tet3d/progress_report.h"
#include "refiners/tet3d/termination_floor.h"
#include "toolkit/geometry/circumcenter.h"

#include "toolkit/predicates/predicates.h"
#include "toolkit/tetmesh/tet_locate.h"

namespace delmesh::tet3d {

namespace {

constexpr std::uint8_t kEdgeVertex[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};

// Local indices (k, l) completing (i, j) to an even permutation of (0, 1, 2, 3), as in
// TetMesh::tets_around_edge: the next tet around edge (v[i], v[j]) is across face k.
constexpr std::uint8_t kEdgeOthers[4][4][2] = {
    {{0, 0}, {2, 3}, {3, 1}, {1, 2}},
    {{3, 2}, {0, 0}, {0, 3}, {2, 0}},
    {{1, 3}, {3, 0}, {0, 0}, {0, 1}},
    {{2, 1}, {0, 2}, {1, 0}, {0, 0}},
};

/// A tet with edge (a, b) and the local indices of a and b in it: TetMesh::find_edge
/// (the same breadth-first search over the star of a, hence the same tet) with the
/// state's scratch queue instead of an allocation per call.
bool find_edge_tet(RefineState& state, std::uint32_t a, std::uint32_t b, EdgeRef& edge) {
  TetMesh& mesh = state.mesh;
  if (a >= mesh.num_vertices() || b >= mesh.num_vertices() || a == b) return false;
  const std::uint32_t start = mesh.vertex_tet(a);
  if (start == kNone) return false;
  auto& queue = state.scratch_tets;
  queue.clear();
  queue.push_back(start);
  const std::uint32_t s = mesh.new_stamp();
  mesh.set_stamp(start, s);
  for (std::size_t k = 0; k < queue.size(); ++k) {
    const std::uint32_t t = queue[k];
    const TetRecord& r = mesh.tet(t);
    const int j = mesh.local_index(t, b);
    if (j >= 0) {
      edge = EdgeRef{t, static_cast<std::uint8_t>(mesh.local_index(t, a)), static_cast<std::uint8_t>(j)};
      return true;
    }
    for (int i = 0; i < 4; ++i) {
      if (r.v[i] == a) continue;
      const std::uint32_t n = r.adj[i] >> 2;
      if (mesh.stamp(n) == s) continue;
      mesh.set_stamp(n, s);
      // Read when the queue reaches it: fetch its record now, so that the misses of the
      // queued tets overlap.
      __builtin_prefetch(&mesh.tet(n));
      queue.push_back(n);
    }
  }
  return false;
}

/// The next tet around the edge (v[i], v[j]) of t and the local indices of the edge's
/// vertices in it (TetMesh::tets_around_edge order).
void rotate_around_edge(const TetMesh& mesh, EdgeRef& e) {
  const TetRecord& r = mesh.tet(e.tet);
  const std::uint32_t a = r.v[e.i], b = r.v[e.j];
  const std::uint32_t n = r.adj[kEdgeOthers[e.i][e.j][0]] >> 2;
  e.tet = n;
  e.i = static_cast<std::uint8_t>(mesh.local_index(n, a));
  e.j = static_cast<std::uint8_t>(mesh.local_index(n, b));
}

}  // namespace

std::optional<FaceRef> find_face_ref(RefineState& state, std::uint32_t a, std::uint32_t b, std::uint32_t c) {
  const TetMesh& mesh = state.mesh;
  if (c >= mesh.num_vertices() || c == a || c == b) return std::nullopt;
  EdgeRef e;
  if (!find_edge_tet(state, a, b, e)) return std::nullopt;
  const std::uint32_t start = e.tet;
  do {
    const TetRecord& r = mesh.tet(e.tet);
    if (mesh.local_index(e.tet, c) >= 0) {
      for (int f = 0; f < 4; ++f) {
        const std::uint32_t w = r.v[f];
        if (w != a && w != b && w != c) return FaceRef{e.tet, static_cast<std::uint8_t>(f)};
      }
    }
    rotate_around_edge(mesh, e);
  } while (e.tet != start);
  return std::nullopt;
}

namespace {

/// Is vertex w a vertex of the triangulation of `facet`? A vertex inserted in the
/// interior enters no facet; one inserted on a facet only that facet; one splitting a
/// subsegment every facet of its segment (split_subsegment). Only input vertices need
/// the facet's own map.
bool facet_has_vertex(const RefineState& state, std::uint32_t facet, std::uint32_t w) {
  const VertexInfo& info = state.vertices[w];
  switch (info.kind) {
    case VertexKind::Interior: return false;
    case VertexKind::OnFacet: return info.owner == facet;
    case VertexKind::OnSegment: {
      const auto& fs = state.segments[info.owner].facets;
      return std::find(fs.begin(), fs.end(), facet) != fs.end();
    }
    case VertexKind::Input:
    case VertexKind::Unused: break;
  }
  return state.facets[facet].has_vertex(w);
}

bool inside_or_on_diametral(const TetMesh& mesh, std::uint32_t a, std::uint32_t b, const double* p) {
  return predicates::dot3d(mesh.coords(a), mesh.coords(b), p) != Sign::Positive;
}

/// p inside or on the equatorial sphere of (a, b, c). The facet's own vertices (coplanar
/// up to roundoff) never count: the facet triangulation keeps them out of circumcircles.
bool encroaches_subface(const TetMesh& mesh, const FaceKey& f, const double* p) {
  return predicates::in_equatorial_sphere(mesh.coords(f[0]), mesh.coords(f[1]), mesh.coords(f[2]), p) !=
         Sign::Negative;
}

/// Set bits of a 4-bit mask (std::popcount compiles to a library call on the baseline
/// x86-64 target; the cavity scan asks twice per tet).
constexpr std::uint8_t kBitCount4[16] = {0, 1, 1, 2, 1, 2, 2, 3, 1, 2, 2, 3, 2, 3, 3, 4};

/// The small hash set of CavityElements::found_keys: the edge keys of the subsegments
/// found by the current scan (slots stamped with the scan's epoch; no clearing).
std::size_t found_slot(const CavityElements& ce, std::uint64_t key) {
  return static_cast<std::size_t>((key * 0x9E3779B97F4A7C15ULL) >> 40) & (ce.found_keys.size() - 1);
}

/// The index in ce.subsegments of the subsegment with edge key `key`, or kNone.
std::uint32_t found_index(const CavityElements& ce, std::uint64_t key) {
  const std::size_t mask = ce.found_keys.size() - 1;
  for (std::size_t i = found_slot(ce, key); ce.found_epochs[i] == ce.epoch; i = (i + 1) & mask)
    if (ce.found_keys[i] == key) return ce.found_index[i];
  return kNone;
}

bool found_before(const CavityElements& ce, std::uint64_t key) { return found_index(ce, key) != kNone; }

/// Files `key` as the subsegment at `index` of ce.subsegments (the table holds the
/// first `index` ones already).
void add_found(CavityElements& ce, std::uint64_t key, std::uint32_t index) {
  if (2 * (std::size_t{index} + 1) > ce.found_keys.size()) {
    // Grow, then put back the keys found so far.
    ce.found_keys.assign(2 * ce.found_keys.size(), 0);
    ce.found_epochs.assign(ce.found_keys.size(), 0);
    ce.found_index.assign(ce.found_keys.size(), 0);
    for (std::uint32_t k = 0; k < index; ++k)
      add_found(ce, edge_key(ce.subsegments[k].a, ce.subsegments[k].b), k);
  }
  const std::size_t mask = ce.found_keys.size() - 1;
  std::size_t i = found_slot(ce, key);
  while (ce.found_epochs[i] == ce.epoch) i = (i + 1) & mask;
  ce.found_keys[i] = key;
  ce.found_epochs[i] = ce.epoch;
  ce.found_index[i] = index;
}

/// The small hash set of CavityElements::scanned_tets (sized by cavity_elements to at
/// least twice the cavity, so it never fills up).
std::size_t scanned_slot(const CavityElements& ce, std::uint32_t t) {
  return static_cast<std::size_t>((t * 0x9E3779B97F4A7C15ULL) >> 32) & (ce.scanned_tets.size() - 1);
}

bool scanned(const CavityElements& ce, std::uint32_t t) {
  const std::size_t mask = ce.scanned_tets.size() - 1;
  for (std::size_t i = scanned_slot(ce, t); ce.scanned_epochs[i] == ce.epoch; i = (i + 1) & mask)
    if (ce.scanned_tets[i] == t) return true;
  return false;
}

void add_scanned(CavityElements& ce, std::uint32_t t) {
  const std::size_t mask = ce.scanned_tets.size() - 1;
  std::size_t i = scanned_slot(ce, t);
  while (ce.scanned_epochs[i] == ce.epoch) i = (i + 1) & mask;
  ce.scanned_tets[i] = t;
  ce.scanned_epochs[i] = ce.epoch;
}

/// The subsegments and subfacets of the prepared cavity (CavityElements), computed on the
/// first call after prepare_insertion and reused until the cavity or a table changes.
const CavityElements& cavity_elements(const RefineState& state) {
  CavityElements& ce = state.cavity_elements;
  const Cavity& cavity = state.cavity;
  const std::uint32_t first = cavity.tets.empty() ? kNone : cavity.tets.front();
  if (ce.serial == state.cavity_serial && ce.segment_version == state.subsegments.version() &&
      ce.face_version == state.subfaces.version() && ce.tet_count == cavity.tets.size() && ce.first_tet == first)
    return ce;
  ce.serial = state.cavity_serial;
  ce.segment_version = state.subsegments.version();
  ce.face_version = state.subfaces.version();
  ce.tet_count = cavity.tets.size();
  ce.first_tet = first;
  ce.subsegments.clear();
  ce.subsegment_encroached.clear();
  ce.subface_encroached.clear();
  ce.subfaces.clear();
  ce.subface_facets.clear();
  ce.subface_outside.clear();
  const TetMesh& mesh = state.mesh;
  if (++ce.epoch == 0) {
    std::fill(ce.scanned_epochs.begin(), ce.scanned_epochs.end(), 0u);
    std::fill(ce.found_epochs.begin(), ce.found_epochs.end(), 0u);
    ce.epoch = 1;
  }
  if (2 * cavity.tets.size() > ce.scanned_tets.size()) {
    ce.scanned_tets.assign(std::bit_ceil(2 * cavity.tets.size()), 0u);
    ce.scanned_epochs.assign(ce.scanned_tets.size(), 0u);
  }
  // The lookups below hit the tables at scattered places: start fetching them all first,
  // at the home slots of the cavity's flagged vertices, so that their misses overlap.
  for (const std::uint32_t t : cavity.tets) {
    for (const std::uint32_t v : mesh.tet(t).v) {
      if (state.subsegments.may_hold(v)) state.subsegments.prefetch_home(v);
      if (state.subfaces.may_hold(v)) state.subfaces.prefetch_home(v);
    }
  }
  for (const std::uint32_t t : cavity.tets) {
    const TetRecord& r = mesh.tet(t);
    // Bit i: vertex i may be a vertex of a subsegment (segment_bits) or a subfacet
    // (face_bits). Read once per tet; most cavity tets have too few flagged vertices for
    // any of their edges or faces to be asked about.
    unsigned segment_bits = 0, face_bits = 0;
    for (unsigned i = 0; i < 4; ++i) {
      segment_bits |= static_cast<unsigned>(state.subsegments.may_hold(r.v[i])) << i;
      face_bits |= static_cast<unsigned>(state.subfaces.may_hold(r.v[i])) << i;
    }
    // The scanned set is asked only about tets on a face of three flagged vertices (the
    // tet beyond such a face, below and for subface_outside): only such tets enter it.
    if (kBitCount4[face_bits] >= 3) add_scanned(ce, t);
    if (kBitCount4[segment_bits] >= 2) {
      for (const auto& e : kEdgeVertex) {
        if (((segment_bits >> e[0]) & (segment_bits >> e[1]) & 1u) == 0) continue;
        const std::uint32_t a = r.v[e[0]], b = r.v[e[1]];
        // An edge is shared by several cavity tets: skip the subsegments met already
        // before asking the table.
        const std::uint64_t key = edge_key(a, b);
        if (found_before(ce, key) || !state.subsegments.lookup(key)) continue;
        add_found(ce, key, static_cast<std::uint32_t>(ce.subsegments.size()));
        ce.subsegments.push_back({a, b});
      }
    }
    if (kBitCount4[face_bits] < 3) continue;
    for (unsigned f = 0; f < 4; ++f) {
      // Face f has every vertex but vertex f.
      if ((face_bits | (1u << f)) != 15u) continue;
      // A face shared with a cavity tet scanned before was met there already.
      if (scanned(ce, r.adj[f] >> 2)) continue;
      const auto& o = kFaceVertex[f];
      const FaceKey key = sorted_face_key(r.v[o[0]], r.v[o[1]], r.v[o[2]]);
      const std::uint32_t* facet = state.subfaces.lookup(key);
      if (!facet) continue;
      ce.subfaces.push_back(key);
      ce.subface_facets.push_back(*facet);
      ce.subface_outside.push_back(r.adj[f]);
    }
  }
  // Every cavity tet is marked now: a subfacet whose other tet is in the cavity is inside.
  for (std::uint32_t& ref : ce.subface_outside)
    if (scanned(ce, ref >> 2)) ref = kNone;
  return ce;
}

/// Right after commit_cavity: for each subsegment of the cavity, the first boundary face
/// of the cavity holding both its vertices (elements.boundary_face, kNone when none does:
/// the insertion deleted it) and their positions in that face. One pass over the
/// boundary, asking the cavity's subsegment map only about edges whose two vertices may
/// be subsegment vertices.
void locate_subsegments_on_boundary(const RefineState& state, const CavityElements& elements) {
  CavityElements& ce = state.cavity_elements;
  ce.boundary_face.assign(elements.subsegments.size(), kNone);
  ce.boundary_position.resize(elements.subsegments.size());
  std::size_t left = elements.subsegments.size();
  const std::vector<CavityFace>& boundary = state.cavity.boundary;
  for (std::size_t k = 0; k < boundary.size() && left > 0; ++k) {
    const CavityFace& f = boundary[k];
    unsigned bits = 0;
    for (unsigned i = 0; i < 3; ++i) bits |= static_cast<unsigned>(state.subsegments.may_hold(f.v[i])) << i;
    if (kBitCount4[bits] < 2) continue;
    for (unsigned i = 0; i < 3; ++i) {
      const unsigned j = i == 2 ? 0 : i + 1;
      if (((bits >> i) & (bits >> j) & 1u) == 0) continue;
      const std::uint32_t s = found_index(ce, edge_key(f.v[i], f.v[j]));
      if (s == kNone || ce.boundary_face[s] != kNone) continue;
      ce.boundary_face[s] = static_cast<std::uint32_t>(k);
      const bool forward = f.v[i] == elements.subsegments[s].a;
      ce.boundary_position[s] = {static_cast<std::uint8_t>(forward ? i : j), static_cast<std::uint8_t>(forward ? j : i)};
      --left;
    }
  }
}

/// Right after commit_cavity and locate_subsegments_on_boundary: is subsegment s of the
/// cavity still an edge, with no vertex around it inside or on its diametral sphere (the
/// status Present)? An edge that survives lies on two boundary faces of the cavity; the
/// new tet on the first of them starts the walk around it.
bool subsegment_clear_after_commit(const RefineState& state, const CavityElements& elements, std::size_t s,
                                   std::uint32_t v) {
  const std::uint32_t k = elements.boundary_face[s];
  if (k == kNone) return false;  // inside the cavity: deleted
  const TetMesh& mesh = state.mesh;
  const std::uint32_t a = elements.subsegments[s].a, b = elements.subsegments[s].b;
  // The new vertex v is one of the vertices around the edge: its answer may be known from
  // cavity_encroached_subsegments.
  const std::uint8_t known = s < elements.subsegment_encroached.size() &&
                                     elements.tested_segments_point == mesh.point(v)
                                 ? elements.subsegment_encroached[s]
                                 : CavityElements::kUntested;
  if (known == 1) return false;
  // The new tet on boundary face k is (f.v[0], f.v[1], f.v[2], v).
  EdgeRef e{state.cavity.created[k], elements.boundary_position[s][0], elements.boundary_position[s][1]};
  const std::uint32_t start = e.tet;
  do {
    const std::uint32_t w = mesh.tet(e.tet).v[kEdgeOthers[e.i][e.j][0]];
    if (w != kInfiniteVertex && !(w == v && known == 0) && inside_or_on_diametral(mesh, a, b, mesh.coords(w)))
      return false;
    rotate_around_edge(mesh, e);
  } while (e.tet != start);
  return true;
}

/// Right after commit_cavity: is subfacet k of the cavity still a face, with neither
/// apex (the new vertex v and the vertex beyond the face) encroaching it, facet vertices
/// aside (the status Present)?
bool subface_clear_after_commit(const RefineState& state, const CavityElements& elements, std::size_t k,
                                std::uint32_t v) {
  const std::uint32_t outside = elements.subface_outside[k];
  if (outside == kNone) return false;
  const std::uint32_t apex[2] = {v, state.mesh.tet(outside >> 2).v[outside & 3u]};
  for (const std::uint32_t w : apex) {
    // Membership first: a vertex of the facet is coplanar with the subfacet and often
    // cocircular with it (grids of facet points), where the predicate's filter fails and
    // it evaluates exactly.
    if (w == kInfiniteVertex || facet_has_vertex(state, elements.subface_facets[k], w)) continue;
    // The new vertex's answer may be known from cavity_encroached_subfaces.
    if (w == v && k < elements.subface_encroached.size() &&
        elements.subface_encroached[k] != CavityElements::kUntested &&
        elements.tested_faces_point == state.mesh.point(v)) {
      if (elements.subface_encroached[k] == 1) return false;
      continue;
    }
    if (encroaches_subface(state.mesh, elements.subfaces[k], state.mesh.coords(w))) return false;
  }
  return true;
}

/// Is tet t in the domain (not exterior, hole or unmarked)?
bool domain_tet(const RefineState& state, std::uint32_t t) {
  return t < state.tet_region.size() && in_domain(state.tet_region[t]);
}

}  // namespace

bool prepare_insertion(RefineState& state, const Vec3& p, std::uint32_t hint, InsertionSite site) {
  ++state.cavity_serial;
  if (state.mesh.num_vertices() >= state.vertex_cap) return false;
  if (!p.allFinite()) return false;
  if (!state.constrained) {
    const Location loc = compute_cavity(state.mesh, p.data(), state.mesh.num_vertices(), hint, state.cavity);
    return loc.kind != LocationKind::OnVertex;
  }
  const SegmentFacetList* segment_facets =
      site.segment != kNone ? &state.segments[site.segment].facets : nullptr;
  const TetMesh& mesh = state.mesh;
  const CavityBlocker blocked = [&](std::uint32_t t, int f) {
    const TetRecord& r = mesh.tet(t);
    const auto& o = kFaceVertex[f];
    const std::uint32_t a = r.v[o[0]], b = r.v[o[1]], c = r.v[o[2]];
    const std::uint32_t* facet = subface_of(state, a, b, c);
    if (!facet) return false;
    const bool split_facet =
        *facet == site.facet ||
        (segment_facets && std::find(segment_facets->begin(), segment_facets->end(), *facet) != segment_facets->end());
    // Of the split facet, only the subfacets the facet triangulation's insertion removes
    // (p in their circumcircle: inside or on their equatorial sphere) may be crossed;
    // deleting another would leave it missing.
    return !split_facet || !encroaches_subface(mesh, sorted_face_key(a, b, c), p.data());
  };
  const Location loc =
      compute_constrained_cavity(state.mesh, p.data(), state.mesh.num_vertices(), hint, blocked, state.cavity);
  if (loc.kind == LocationKind::OnVertex) return false;
  bool shrunk = false;
  const auto reject = [&state] {
    ++state.cavity_rejections;
    state.cavity.tets.clear();
    state.cavity.boundary.clear();
    return false;
  };
  if (!shrink_cavity_to_star(state.mesh, p.data(), loc.tet, state.cavity, shrunk)) return reject();
  if (shrunk && (site.facet != kNone || site.segment != kNone)) {
    // A split of a facet or segment whose cavity had to shrink: the subfacets the facet
    // triangulations' insertion removes must still lie inside the cavity. One on its
    // boundary (a crossable face, as the search crossed it) would stay in the mesh and
    // its replacements go missing: dropped.
    for (const CavityFace& f : state.cavity.boundary) {
      if (f.v[0] == kInfiniteVertex || f.v[1] == kInfiniteVertex || f.v[2] == kInfiniteVertex) continue;
      if (!subface_of(state, f.v[0], f.v[1], f.v[2]) || blocked(f.outside >> 2, static_cast<int>(f.outside & 3u)))
        continue;
      return reject();
    }
  }
  if (shrunk) ++state.cavity_shrinks;
  return true;
}

void pass_over_insertion(RefineState& state, const Vec3& p, std::uint32_t hint) {
  if (state.mesh.num_vertices() >= state.vertex_cap || !p.allFinite()) return;
  locate(state.mesh, p.data(), hint, state.cavity.rng);
}

std::uint32_t commit_insertion(RefineState& state, const Vec3& p, const VertexInfo& info) {
  TetMesh& mesh = state.mesh;
  Cavity& cavity = state.cavity;
  // The subsegments and subfacets the cavity touches: the insertion may delete them or
  // its vertex may encroach them.
  const CavityElements& elements = cavity_elements(state);
  // Region of each new tet: the region of the cavity tet that owned its boundary face.
  auto& owner_region = state.scratch_regions;
  owner_region.clear();
  for (const CavityFace& f : cavity.boundary) {
    const std::uint32_t out_tet = f.outside >> 2;
    const std::uint32_t inner = mesh.tet(out_tet).adj[f.outside & 3u] >> 2;
    owner_region.push_back(inner < state.tet_region.size() ? state.tet_region[inner] : kRegionUnknown);
  }
  double field_floor = new_vertex_floor(state, p, info.floor);
  // On a segment beside a narrower part of its facet, the floor follows the gap.
  if (info.kind == VertexKind::OnSegment) field_floor = std::min(field_floor, narrow_facet_floor(state, info.owner, p));
  const std::uint32_t v = mesh.add_vertex(p);
  state.vertices.push_back(info);
  state.vertices.back().field_floor = field_floor;
  commit_cavity(mesh, v, cavity);
  if (state.tet_region.size() < mesh.tet_slots()) state.tet_region.resize(mesh.tet_slots(), kRegionUnknown);
  for (std::size_t k = 0; k < cavity.created.size(); ++k) {
    const std::uint32_t t = cavity.created[k];
    state.tet_region[t] = mesh.is_infinite(t) ? kRegionExterior : owner_region[k];
    if (state.collect_new_tets) state.new_tets.push_back(t);
  }
  mesh.set_last_tet(cavity.created.front());
  // Queue those that are now missing or encroached. One found present and unencroached
  // needs no check: its status changes only when a later cavity holds it, and that
  // insertion queues it again.
  if (state.constrained && state.options.segment_recovery == SegmentRecovery::StronglyDelaunay) {
    // Strongly Delaunay recovery on the CCDT splits only missing elements (an encroached
    // one stays, restore_conformity): queue those the insertion deletes. A subsegment on
    // a boundary face of the cavity stays an edge, a subfacet on the boundary a face.
    if (!elements.subsegments.empty()) locate_subsegments_on_boundary(state, elements);
    for (std::size_t s = 0; s < elements.subsegments.size(); ++s)
      if (elements.boundary_face[s] == kNone) state.subsegment_queue.push_back(elements.subsegments[s]);
    for (std::size_t k = 0; k < elements.subfaces.size(); ++k)
      if (elements.subface_outside[k] == kNone) state.subface_queue.push_back({elements.subfaces[k]});
    ++state.stage_steiner;
    if (state.progress) state.progress->poll(state);
    return v;
  }
  if (state.constrained) {
    // Constrained: which apexes encroach depends on the regions of their tets, which
    // subsegment_status and subface_status read; queue every element for them.
    for (const SubsegmentTask& s : elements.subsegments) state.subsegment_queue.push_back(s);
    for (const FaceKey& f : elements.subfaces) state.subface_queue.push_back({f});
    ++state.stage_steiner;
    if (state.progress) state.progress->poll(state);
    return v;
  }
  if (!elements.subsegments.empty()) locate_subsegments_on_boundary(state, elements);
  for (std::size_t s = 0; s < elements.subsegments.size(); ++s)
    if (!subsegment_clear_after_commit(state, elements, s, v)) state.subsegment_queue.push_back(elements.subsegments[s]);
  for (std::size_t k = 0; k < elements.subfaces.size(); ++k)
    if (!subface_clear_after_commit(state, elements, k, v)) state.subface_queue.push_back({elements.subfaces[k]});
  ++state.stage_steiner;
  if (state.progress) state.progress->poll(state);
  return v;
}

void cavity_encroached_subsegments(const RefineState& state, const Vec3& p, std::uint64_t skip,
                                   std::vector<std::uint64_t>& out) {
  out.clear();
  const CavityElements& elements = cavity_elements(state);
  CavityElements& ce = state.cavity_elements;
  ce.tested_segments_point = p;
  ce.subsegment_encroached.assign(elements.subsegments.size(), CavityElements::kUntested);
  for (std::size_t k = 0; k < elements.subsegments.size(); ++k) {
    const SubsegmentTask& s = elements.subsegments[k];
    const std::uint64_t key = edge_key(s.a, s.b);
    if (key == skip) continue;
    const bool encroached = inside_or_on_diametral(state.mesh, s.a, s.b, p.data());
    ce.subsegment_encroached[k] = encroached ? 1 : 0;
    if (encroached) out.push_back(key);
  }
}

void cavity_encroached_subfaces(const RefineState& state, const Vec3& p, std::uint32_t skip_facet,
                                std::uint32_t skip_segment, std::vector<FaceKey>& out) {
  out.clear();
  const CavityElements& elements = cavity_elements(state);
  CavityElements& ce = state.cavity_elements;
  ce.tested_faces_point = p;
  ce.subface_encroached.assign(elements.subfaces.size(), CavityElements::kUntested);
  for (std::size_t k = 0; k < elements.subfaces.size(); ++k) {
    const std::uint32_t facet = elements.subface_facets[k];
    if (facet == skip_facet) continue;
    if (skip_segment != kNone) {
      const auto& fs = state.segments[skip_segment].facets;
      if (std::find(fs.begin(), fs.end(), facet) != fs.end()) continue;
    }
    const bool encroached = encroaches_subface(state.mesh, elements.subfaces[k], p.data());
    ce.subface_encroached[k] = encroached ? 1 : 0;
    if (encroached) out.push_back(elements.subfaces[k]);
  }
}

bool cavity_deletes_subface(const RefineState& state) {
  const CavityElements& elements = cavity_elements(state);
  return std::find(elements.subface_outside.begin(), elements.subface_outside.end(), kNone) !=
         elements.subface_outside.end();
}

SubfaceStatus subsegment_status(RefineState& state, std::uint32_t a, std::uint32_t b, std::uint32_t& by) {
  // The vertices around the edge in TetMesh::tets_around_edge order; the first one inside
  // or on the diametral sphere encroaches.
  EdgeRef e;
  if (!find_edge_tet(state, a, b, e)) return SubfaceStatus::Missing;
  const TetMesh& mesh = state.mesh;
  const std::uint32_t start = e.tet;
  do {
    // Constrained: only vertices of tets in the domain count (both apexes of each such
    // tet around the edge), so exterior space between parts never forces a split.
    const std::uint8_t k = kEdgeOthers[e.i][e.j][0];
    const std::uint8_t l = kEdgeOthers[e.i][e.j][1];
    const std::uint32_t w = mesh.tet(e.tet).v[k];
    if (!state.constrained) {
      if (w != kInfiniteVertex && inside_or_on_diametral(mesh, a, b, mesh.coords(w))) {
        by = w;
        return SubfaceStatus::Encroached;
      }
    } else if (domain_tet(state, e.tet)) {
      for (const std::uint32_t x : {w, mesh.tet(e.tet).v[l]}) {
        if (x != kInfiniteVertex && inside_or_on_diametral(mesh, a, b, mesh.coords(x))) {
          by = x;
          return SubfaceStatus::Encroached;
        }
      }
    }
    rotate_around_edge(mesh, e);
  } while (e.tet != start);
  return SubfaceStatus::Present;
}

SubfaceStatus subface_status(RefineState& state, const FaceKey& face, std::uint32_t& by) {
  const auto f = find_face_ref(state, face[0], face[1], face[2]);
  if (!f) return SubfaceStatus::Missing;
  const std::uint32_t apex[2] = {state.mesh.tet(f->tet).v[f->face], state.mesh.opposite_vertex(*f)};
  const std::uint32_t apex_tet[2] = {f->tet, state.mesh.neighbor(f->tet, f->face)};
  const std::uint32_t facet = state.subfaces.at(face);
  for (int i = 0; i < 2; ++i) {
    const std::uint32_t w = apex[i];
    // Constrained: an apex in an exterior or hole tet does not encroach.
    if (state.constrained && !domain_tet(state, apex_tet[i])) continue;
    // Membership first, as in subface_clear_after_commit.
    if (w == kInfiniteVertex || facet_has_vertex(state, facet, w)) continue;
    if (encroaches_subface(state.mesh, face, state.mesh.coords(w))) {
      by = w;
      return SubfaceStatus::Encroached;
    }
  }
  return SubfaceStatus::Present;
}

namespace {

/// The split point of subsegment (a, b), which does not touch the grid origin o of its
/// segment: at the distance from o that is a multiple m 2^k of the largest power of two
/// 2^k having a multiple in the middle third of the subsegment's distances from o. That
/// multiple is unique (of two consecutive multiples of 2^k one is a multiple of 2^(k+1)),
/// so it depends only on the two distances: segments of a narrow corner or cluster at o
/// whose vertices lie at the same distances from o are split at the same distances
/// again, and a vertex of one stays outside the diametral spheres of the other's
/// subsegments. o may lie off the segment's line (a cluster's apex): the distance then
/// grows along the subsegment only if o's foot on the line is not inside it, else
/// nullopt (the midpoint is used). The pieces are at least a third of the subsegment's
/// distance range from o.
std::optional<Vec3> grid_split_point(const RefineState& state, const SegmentData& seg, std::uint32_t a,
                                     std::uint32_t b) {
  const Vec3& po = state.mesh.point(seg.grid_origin);
  double ra = (state.mesh.point(a) - po).norm(), rb = (state.mesh.point(b) - po).norm();
  if (rb < ra) {
    std::swap(a, b);
    std::swap(ra, rb);
  }
  const Vec3& near = state.mesh.point(a);
  const Vec3 axis = state.mesh.point(b) - near;
  const double length = axis.norm();
  if (!(length > 0.0)) return std::nullopt;
  const Vec3 dir = axis / length;
  const double along = (near - po).dot(dir);  // >= 0: the distance from o grows along dir
  const double third = (rb - ra) / 3.0;
  const double from = ra + third, to = rb - third;
  if (!(along >= 0.0) || !(third > 0.0) || !(from > 0.0)) return std::nullopt;
  // From the largest power of two not above `to` down: once the step is at most the
  // middle third's length the third holds a multiple, so the loop ends after about
  // log2(rb / third) + 2 steps (bounded by the exponent range of double in any case).
  double step = std::exp2(std::floor(std::log2(to)));
  for (int k = 0; k < 2200 && step > 0.0; ++k, step *= 0.5) {
    const double r = std::ceil(from / step) * step;
    if (r > to) continue;
    // |near + t dir - o| = r: t = (r^2 - ra^2) / (along + sqrt(along^2 + r^2 - ra^2)).
    const double grow = (r - ra) * (r + ra);
    const double t = grow / (along + std::sqrt(along * along + grow));
    if (!(t > 0.0 && t < length)) return std::nullopt;
    return Vec3(near + t * dir);
  }
  return std::nullopt;
}

}  // namespace

Vec3 subsegment_split_point(const RefineState& state, std::uint32_t a, std::uint32_t b) {
  const Vec3& pa = state.mesh.point(a);
  const Vec3& pb = state.mesh.point(b);
  const Vec3 mid = 0.5 * (pa + pb);
  const auto it = state.subsegments.find(edge_key(a, b));
  if (it == state.subsegments.end()) return mid;
  const SegmentData& seg = state.segments[it->second];
  // An endpoint that is a shared input vertex of the segment: split on a shell around it.
  std::uint32_t apex = kNone, other = kNone;
  if (seg.grid_origin != kNone) {
    // A segment of a narrow corner: a shell around its origin, or a point of the grid.
    if (a != seg.grid_origin && b != seg.grid_origin) return grid_split_point(state, seg, a, b).value_or(mid);
    apex = seg.grid_origin;
    other = a == apex ? b : a;
  } else if ((a == seg.a && seg.shell_a) || (a == seg.b && seg.shell_b)) {
    apex = a;
    other = b;
  } else if ((b == seg.a && seg.shell_a) || (b == seg.b && seg.shell_b)) {
    apex = b;
    other = a;
  }
  if (apex == kNone) return mid;
  const Vec3& p0 = state.mesh.point(apex);
  const Vec3& p1 = state.mesh.point(other);
  const double length = (p1 - p0).norm();
  if (!(length > 0.0)) return mid;
  // The power of two nearest to half the length (in log scale): the smaller piece is at
  // least a third of the subsegment.
  const double d = std::exp2(std::round(std::log2(0.5 * length)));
  if (!(d > 0.0) || d >= length) return mid;
  return p0 + (d / length) * (p1 - p0);
}

double subsegment_split_radius(const RefineState& state, std::uint32_t a, std::uint32_t b, const Vec3& p) {
  return std::min((p - state.mesh.point(a)).norm(), (p - state.mesh.point(b)).norm());
}

void apply_subface_change(RefineState& state, std::uint32_t facet, const SubfaceChange& change) {
  for (const Subface& f : change.removed) state.subfaces.erase(face_key(f[0], f[1], f[2]));
  for (const Subface& f : change.added) {
    const FaceKey key = face_key(f[0], f[1], f[2]);
    state.subfaces[key] = facet;
    state.subface_queue.push_back({key});
  }
}

bool below_split_resolution(const RefineState& state, std::uint32_t a, std::uint32_t b, const Vec3& p) {
  const Vec3& pa = state.mesh.point(a);
  const Vec3& pb = state.mesh.point(b);
  const double magnitude = std::max({pa.cwiseAbs().maxCoeff(), pb.cwiseAbs().maxCoeff(), p.cwiseAbs().maxCoeff()});
  const double shortest = kSplitResolution * magnitude;
  return (p - pa).norm() < shortest || (p - pb).norm() < shortest;
}

namespace {

/// Other split points of a subsegment on the CCDT, as fractions of it from its first end,
/// tried in turn when the cavity of the split point is refused.
constexpr double kAlternateSplits[] = {0.375, 0.625, 0.25, 0.75};

/// Is (a, b) an edge of a boundary face of the prepared cavity? The insertion then keeps
/// the edge, and a point of the subsegment (a, b) lies on it: a point off the line by
/// roundoff can see such a face from its positive side, so the cavity, shrunk to a star
/// of the point, passes, and the split leaves (a, b) in the mesh beside its two pieces,
/// with a flat tet (a, b, x, p) whose face (a, b, p) may end on the domain boundary.
bool cavity_keeps_edge(const Cavity& cavity, std::uint32_t a, std::uint32_t b) {
  for (const CavityFace& f : cavity.boundary) {
    const bool has_a = f.v[0] == a || f.v[1] == a || f.v[2] == a;
    const bool has_b = f.v[0] == b || f.v[1] == b || f.v[2] == b;
    if (has_a && has_b) return true;
  }
  return false;
}

/// Prepares the cavity of split point p of subsegment (a, b) of segment `seg` on the
/// CCDT: prepare_insertion, refused as well when a new piece would be below the
/// resolution or the cavity keeps (a, b).
bool prepare_split_deleting_edge(RefineState& state, std::uint32_t a, std::uint32_t b, std::uint32_t seg,
                                 const Vec3& p) {
  if (below_split_resolution(state, a, b, p)) return false;
  if (!prepare_insertion(state, p, state.mesh.any_tet_of(a), {kNone, seg})) return false;
  return !cavity_keeps_edge(state.cavity, a, b);
}

}  // namespace

std::uint32_t split_subsegment(RefineState& state, std::uint32_t a, std::uint32_t b, const Vec3& split_point,
                               double floor, bool delaunay) {
  const auto it = state.subsegments.find(edge_key(a, b));
  DELMESH_CHECK(it != state.subsegments.end(), "split of a subsegment that does not exist");
  const std::uint32_t seg = it->second;
  if (below_split_resolution(state, a, b, split_point)) return kNone;
  Vec3 p = split_point;
  const std::uint32_t hint = state.mesh.any_tet_of(a);
  if (!state.constrained || !delaunay) {
    if (!prepare_insertion(state, p, hint, {kNone, seg})) return kNone;
  } else if (!prepare_split_deleting_edge(state, a, b, seg, p)) {
    // Refinement's own split on the CCDT: other points of the subsegment, whose
    // constrained cavities differ, then the split point with a cavity that keeps (a, b),
    // as when the cavity was not checked for it.
    bool prepared = false;
    for (const double t : kAlternateSplits) {
      p = state.mesh.point(a) + t * (state.mesh.point(b) - state.mesh.point(a));
      prepared = prepare_split_deleting_edge(state, a, b, seg, p);
      if (prepared) break;
    }
    if (!prepared) {
      p = split_point;
      if (!prepare_insertion(state, p, hint, {kNone, seg})) return kNone;
    }
  }
  VertexInfo info;
  info.kind = VertexKind::OnSegment;
  info.owner = seg;
  info.floor = floor;
  const std::uint32_t v = commit_insertion(state, p, info);
  ++state.stage_segment_splits.for_rejected_points;
  if (p != 0.5 * (state.mesh.point(a) + state.mesh.point(b))) ++state.stage_segment_splits.shell;
  state.subsegments.erase(edge_key(a, b));
  state.subsegments[edge_key(a, v)] = seg;
  state.subsegments[edge_key(v, b)] = seg;
  state.subsegment_queue.push_back({a, v});
  state.subsegment_queue.push_back({v, b});
  for (const std::uint32_t f : state.segments[seg].facets) {
    auto change = state.facets[f].split_segment(a, b, v, p, delaunay);
    DELMESH_CHECK(change.has_value(), "facet triangulation refused a subsegment split");
    apply_subface_change(state, f, change.value());
  }
  return v;
}

std::uint32_t insert_facet_point(RefineState& state, std::uint32_t facet, const Vec3& p, double floor,
                                 std::uint32_t near, bool delaunay) {
  const std::uint32_t id = state.mesh.num_vertices();
  auto change = state.facets[facet].insert_vertex(id, p, near, delaunay);
  if (!change.has_value()) return kNone;
  VertexInfo info;
  info.kind = VertexKind::OnFacet;
  info.owner = facet;
  info.floor = floor;
  const std::uint32_t v = commit_insertion(state, p, info);
  DELMESH_CHECK(v == id, "vertex id mismatch between facet and tetrahedralization");
  apply_subface_change(state, facet, change.value());
  return v;
}

std::optional<FaceKey> subface_below(const RefineState& state, std::uint32_t facet, std::uint32_t near,
                                     const Vec3& v) {
  const auto f = state.facets[facet].locate(v.data(), near);
  if (!f) return std::nullopt;
  return face_key((*f)[0], (*f)[1], (*f)[2]);
}

double cavity_insertion_radius(const RefineState& state, const Vec3& p) {
  double best = std::numeric_limits<double>::infinity();
  if (state.constrained) {
    // Constrained: only vertices of cavity tets in the domain count, as for encroachment
    // (a facet split's cavity reaches across the facet into exterior space, whose far
    // side may be another part's boundary a gap away).
    bool any = false;
    for (const std::uint32_t t : state.cavity.tets) {
      if (!domain_tet(state, t)) continue;
      any = true;
      for (const std::uint32_t w : state.mesh.tet(t).v)
        if (w != kInfiniteVertex) best = std::min(best, (state.mesh.point(w) - p).squaredNorm());
    }
    if (any) return std::sqrt(best);
  }
  for (const CavityFace& f : state.cavity.boundary) {
    for (const std::uint32_t w : f.v) {
      if (w == kInfiniteVertex) continue;
      best = std::min(best, (state.mesh.point(w) - p).squaredNorm());
    }
  }
  return std::sqrt(best);
}

}  // namespace delmesh::tet3d
