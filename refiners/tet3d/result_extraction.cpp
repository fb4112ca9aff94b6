// Result extraction (see result_extraction.h).
//
// Memory: extraction is the last use of the refinement state, and the copy it makes
// would otherwise sit on top of everything the refinement kept (facet triangulations,
// lookup tables, queues, scratch, per-vertex records). So the tables, queues and
// per-vertex records are freed first, the boundary triangles are taken from the facet
// triangulations, these are freed too, and only then are the tets copied, into arrays
// reserved at their exact final size (no growth slack, no old and new buffer side by
// side).
#include "refiners/tet3d/result_extraction.h"

#include "refiners/tet3d/boundary_split.h"

namespace delmesh::tet3d {

namespace {

template <class T>
void release(T& x) {
  x = T();
}

/// Frees what the boundary faces do not need: the lookup tables (if release_lookup_tables
/// has not), segments, per-vertex records, queues and cavity scratch.
void release_refinement_tables(RefineState& state) {
  release_lookup_tables(state);
  release(state.segments);
  release(state.vertices);
}

/// Then what the tets do not need: the facet triangulations and the search marks.
void release_facets_and_marks(RefineState& state) {
  release(state.facets);
  release(state.facet_pool);
  release(state.scratch_tets);
  state.mesh.release_stamps();
}

}  // namespace

void release_lookup_tables(RefineState& state) {
  release(state.subfaces);
  release(state.subsegments);
  release(state.cavity);
  release(state.cavity_elements);
  release(state.subsegment_queue);
  release(state.subface_queue);
  release(state.new_tets);
  release(state.scratch_ring);
  release(state.scratch_regions);
}

void extract_result(RefineState& state, const std::vector<std::uint8_t>& small_angle, MeshResult& result) {
  TetMesh& mesh = state.mesh;
  TetraMesh& out = result.mesh;
  auto kept = [&](std::uint32_t t) { return !mesh.is_dead(t) && !mesh.is_infinite(t) && in_domain(state.tet_region[t]); };
  release_refinement_tables(state);

  // Vertices of the kept tets in increasing id order (input points first, in input
  // order): index[v] is v's output id, kNone for vertices of no kept tet.
  std::vector<std::uint32_t> index(mesh.num_vertices(), kNone);
  std::size_t tet_count = 0;
  for (std::uint32_t t = 0; t < mesh.tet_slots(); ++t) {
    if (!kept(t)) continue;
    ++tet_count;
    for (const std::uint32_t v : mesh.tet(t).v) index[v] = 0;
  }
  std::uint32_t vertex_count = 0;
  for (std::uint32_t v = 1; v < mesh.num_vertices(); ++v)
    if (index[v] != kNone) index[v] = vertex_count++;
  out.points.reserve(vertex_count);
  for (std::uint32_t v = 1; v < mesh.num_vertices(); ++v)
    if (index[v] != kNone) out.points.push_back(mesh.point(v));

  // Boundary faces in a deterministic order: facet by facet, in facet triangulation order.
  for (std::uint32_t f = 0; f < state.facets.size(); ++f) {
    for (const Subface& s : state.facets[f].subfaces()) {
      const auto face = find_face_ref(state, s[0], s[1], s[2]);
      if (!face) continue;
      const FaceRef other = mesh.mirror(*face);
      const bool in0 = !mesh.is_infinite(face->tet) && in_domain(state.tet_region[face->tet]);
      const bool in1 = !mesh.is_infinite(other.tet) && in_domain(state.tet_region[other.tet]);
      if (!in0 && !in1) continue;
      // kFaceVertex order faces the tet's own opposite vertex: reverse it to face away
      // from an in-domain tet.
      const FaceRef inside = in0 ? *face : other;
      const auto fv = mesh.face_vertices(inside);
      out.boundary_faces.push_back({index[fv[0]], index[fv[2]], index[fv[1]]});
      out.boundary_markers.push_back(state.facet_markers[f]);
      result.boundary_face_facets.push_back(f);
    }
  }
  release_facets_and_marks(state);

  out.tets.reserve(tet_count);
  out.tet_regions.reserve(tet_count);
  result.tet_at_small_angle.reserve(tet_count);
  for (std::uint32_t t = 0; t < mesh.tet_slots(); ++t) {
    if (!kept(t)) continue;
    const auto& v = mesh.tet(t).v;
    out.tets.push_back({index[v[0]], index[v[1]], index[v[2]], index[v[3]]});
    out.tet_regions.push_back(state.tet_region[t]);
    result.tet_at_small_angle.push_back(t < small_angle.size() ? small_angle[t] : 0);
  }
  out.marker_names = state.plc.facet_marker_names;
  out.region_names = state.plc.region_names;
  out.marker_colors = state.plc.facet_marker_colors;
  out.region_colors = state.plc.region_colors;
}

}  // namespace delmesh::tet3d
