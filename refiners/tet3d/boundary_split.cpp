// Vertex insertion and subsegment/subfacet splits (see boundary_split.h; notes §4.2.1).
#include "refiners/tet3d/boundary_split.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "refiners/tet3d/progress_report.h"
#include "toolkit/geometry/circumcenter.h"

#include "toolkit/predicates/predicates.h"

namespace delmesh::tet3d {

namespace {

constexpr std::uint8_t kEdgeVertex[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};

bool inside_or_on_diametral(const TetMesh& mesh, std::uint32_t a, std::uint32_t b, const double* p) {
  return predicates::dot3d(mesh.coords(a), mesh.coords(b), p) != Sign::Positive;
}

/// p inside or on the equatorial sphere of (a, b, c). The facet's own vertices (coplanar
/// up to roundoff) never count: the facet triangulation keeps them out of circumcircles.
bool encroaches_subface(const TetMesh& mesh, const FaceKey& f, const double* p) {
  return predicates::in_equatorial_sphere(mesh.coords(f[0]), mesh.coords(f[1]), mesh.coords(f[2]), p) !=
         Sign::Negative;
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
  ce.subfaces.clear();
  ce.subface_facets.clear();
  const TetMesh& mesh = state.mesh;
  if (ce.tet_mark.size() < mesh.tet_slots()) ce.tet_mark.resize(mesh.tet_slots() + mesh.tet_slots() / 4, 0);
  if (++ce.epoch == 0) {
    std::fill(ce.tet_mark.begin(), ce.tet_mark.end(), 0u);
    ce.epoch = 1;
  }
  for (const std::uint32_t t : cavity.tets) {
    ce.tet_mark[t] = ce.epoch;
    const TetRecord& r = mesh.tet(t);
    for (const auto& e : kEdgeVertex) {
      const std::uint32_t a = r.v[e[0]], b = r.v[e[1]];
      if (!subsegment_of(state, a, b)) continue;
      const std::uint64_t key = edge_key(a, b);
      bool seen = false;
      for (std::size_t k = 0; k < ce.subsegments.size() && !seen; ++k)
        seen = edge_key(ce.subsegments[k].a, ce.subsegments[k].b) == key;
      if (!seen) ce.subsegments.push_back({a, b});
    }
    for (int f = 0; f < 4; ++f) {
      // A face shared with a cavity tet scanned before was met there already.
      if (ce.tet_mark[r.adj[f] >> 2] == ce.epoch) continue;
      const auto& o = kFaceVertex[f];
      const std::uint32_t a = r.v[o[0]], b = r.v[o[1]], c = r.v[o[2]];
      const std::uint32_t* facet = subface_of(state, a, b, c);
      if (!facet) continue;
      ce.subfaces.push_back(sorted_face_key(a, b, c));
      ce.subface_facets.push_back(*facet);
    }
  }
  return ce;
}

}  // namespace

bool prepare_insertion(RefineState& state, const Vec3& p, std::uint32_t hint) {
  ++state.cavity_serial;
  if (state.mesh.num_vertices() >= state.vertex_cap) return false;
  if (!p.allFinite()) return false;
  const Location loc = compute_cavity(state.mesh, p.data(), state.mesh.num_vertices(), hint, state.cavity);
  return loc.kind != LocationKind::OnVertex;
}

std::uint32_t commit_insertion(RefineState& state, const Vec3& p, const VertexInfo& info) {
  TetMesh& mesh = state.mesh;
  Cavity& cavity = state.cavity;
  // Queue every subsegment and subfacet the cavity touches: they may be deleted or
  // encroached by the new vertex.
  const CavityElements& elements = cavity_elements(state);
  state.subsegment_queue.insert(state.subsegment_queue.end(), elements.subsegments.begin(),
                                elements.subsegments.end());
  for (const FaceKey& key : elements.subfaces) state.subface_queue.push_back({key});
  // Region of each new tet: the region of the cavity tet that owned its boundary face.
  auto& owner_region = state.scratch_regions;
  owner_region.clear();
  for (const CavityFace& f : cavity.boundary) {
    const std::uint32_t out_tet = f.outside >> 2;
    const std::uint32_t inner = mesh.tet(out_tet).adj[f.outside & 3u] >> 2;
    owner_region.push_back(inner < state.tet_region.size() ? state.tet_region[inner] : kRegionUnknown);
  }
  const std::uint32_t v = mesh.add_vertex(p);
  state.vertices.push_back(info);
  commit_cavity(mesh, v, cavity);
  if (state.tet_region.size() < mesh.tet_slots()) state.tet_region.resize(mesh.tet_slots(), kRegionUnknown);
  for (std::size_t k = 0; k < cavity.created.size(); ++k) {
    const std::uint32_t t = cavity.created[k];
    state.tet_region[t] = mesh.is_infinite(t) ? kRegionExterior : owner_region[k];
    if (state.collect_new_tets) state.new_tets.push_back(t);
  }
  mesh.set_last_tet(cavity.created.front());
  ++state.stage_steiner;
  if (state.progress) state.progress->poll(state);
  return v;
}

void cavity_encroached_subsegments(const RefineState& state, const Vec3& p, std::uint64_t skip,
                                   std::vector<std::uint64_t>& out) {
  out.clear();
  for (const SubsegmentTask& s : cavity_elements(state).subsegments) {
    const std::uint64_t key = edge_key(s.a, s.b);
    if (key != skip && inside_or_on_diametral(state.mesh, s.a, s.b, p.data())) out.push_back(key);
  }
}

void cavity_encroached_subfaces(const RefineState& state, const Vec3& p, std::uint32_t skip_facet,
                                std::uint32_t skip_segment, std::vector<FaceKey>& out) {
  out.clear();
  const CavityElements& elements = cavity_elements(state);
  for (std::size_t k = 0; k < elements.subfaces.size(); ++k) {
    const std::uint32_t facet = elements.subface_facets[k];
    if (facet == skip_facet) continue;
    if (skip_segment != kNone) {
      const auto& fs = state.segments[skip_segment].facets;
      if (std::find(fs.begin(), fs.end(), facet) != fs.end()) continue;
    }
    if (encroaches_subface(state.mesh, elements.subfaces[k], p.data())) out.push_back(elements.subfaces[k]);
  }
}

SubfaceStatus subsegment_status(RefineState& state, std::uint32_t a, std::uint32_t b, std::uint32_t& by) {
  auto& ring = state.scratch_ring;
  if (!state.mesh.tets_around_edge(a, b, state.scratch_tets, &ring)) return SubfaceStatus::Missing;
  for (const std::uint32_t w : ring) {
    if (w == kInfiniteVertex) continue;
    if (inside_or_on_diametral(state.mesh, a, b, state.mesh.coords(w))) {
      by = w;
      return SubfaceStatus::Encroached;
    }
  }
  return SubfaceStatus::Present;
}

SubfaceStatus subface_status(RefineState& state, const FaceKey& face, std::uint32_t& by) {
  const auto f = state.mesh.find_face(face[0], face[1], face[2]);
  if (!f) return SubfaceStatus::Missing;
  const std::uint32_t apex[2] = {state.mesh.tet(f->tet).v[f->face], state.mesh.opposite_vertex(*f)};
  const FacetTriangulation& facet = *state.facets[state.subfaces.at(face)];
  for (const std::uint32_t w : apex) {
    if (w == kInfiniteVertex || facet.has_vertex(w)) continue;
    if (encroaches_subface(state.mesh, face, state.mesh.coords(w))) {
      by = w;
      return SubfaceStatus::Encroached;
    }
  }
  return SubfaceStatus::Present;
}

Vec3 subsegment_split_point(const RefineState& state, std::uint32_t a, std::uint32_t b) {
  const Vec3& pa = state.mesh.point(a);
  const Vec3& pb = state.mesh.point(b);
  const Vec3 mid = 0.5 * (pa + pb);
  const auto it = state.subsegments.find(edge_key(a, b));
  if (it == state.subsegments.end()) return mid;
  const SegmentData& seg = state.segments[it->second];
  // An endpoint that is a shared input vertex of the segment: split on a shell around it.
  std::uint32_t apex = kNone, other = kNone;
  if ((a == seg.a && seg.shell_a) || (a == seg.b && seg.shell_b)) {
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

std::uint32_t split_subsegment(RefineState& state, std::uint32_t a, std::uint32_t b, const Vec3& p,
                               double floor) {
  const auto it = state.subsegments.find(edge_key(a, b));
  DELMESH_CHECK(it != state.subsegments.end(), "split of a subsegment that does not exist");
  const std::uint32_t seg = it->second;
  if (!prepare_insertion(state, p, state.mesh.any_tet_of(a))) return kNone;
  VertexInfo info;
  info.kind = VertexKind::OnSegment;
  info.owner = seg;
  info.floor = floor;
  const std::uint32_t v = commit_insertion(state, p, info);
  state.subsegments.erase(edge_key(a, b));
  state.subsegments[edge_key(a, v)] = seg;
  state.subsegments[edge_key(v, b)] = seg;
  state.subsegment_queue.push_back({a, v});
  state.subsegment_queue.push_back({v, b});
  for (const std::uint32_t f : state.segments[seg].facets) {
    auto change = state.facets[f]->split_segment(a, b, v, p);
    DELMESH_CHECK(change.has_value(), "facet triangulation refused a subsegment split");
    apply_subface_change(state, f, change.value());
  }
  return v;
}

std::uint32_t insert_facet_point(RefineState& state, std::uint32_t facet, const Vec3& p, double floor) {
  const std::uint32_t id = state.mesh.num_vertices();
  auto change = state.facets[facet]->insert_vertex(id, p);
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
  const auto f = state.facets[facet]->locate(v.data(), near);
  if (!f) return std::nullopt;
  return face_key((*f)[0], (*f)[1], (*f)[2]);
}

double cavity_insertion_radius(const RefineState& state, const Vec3& p) {
  double best = std::numeric_limits<double>::infinity();
  for (const CavityFace& f : state.cavity.boundary) {
    for (const std::uint32_t w : f.v) {
      if (w == kInfiniteVertex) continue;
      best = std::min(best, (state.mesh.point(w) - p).squaredNorm());
    }
  }
  return std::sqrt(best);
}

}  // namespace delmesh::tet3d
