// Result extraction (see result_extraction.h).
#include "refiners/tet3d/result_extraction.h"

#include "refiners/tet3d/boundary_split.h"

namespace delmesh::tet3d {

void extract_result(RefineState& state, MeshResult& result) {
  TetMesh& mesh = state.mesh;
  TetraMesh& out = result.mesh;
  std::vector<std::uint32_t> index(mesh.num_vertices(), kNone);
  auto map_vertex = [&](std::uint32_t v) {
    if (index[v] == kNone) {
      index[v] = static_cast<std::uint32_t>(out.points.size());
      out.points.push_back(mesh.point(v));
    }
    return index[v];
  };
  // Vertices in increasing id order (input points first, in input order).
  std::vector<char> used(mesh.num_vertices(), 0);
  for (std::uint32_t t = 0; t < mesh.tet_slots(); ++t) {
    if (mesh.is_dead(t) || mesh.is_infinite(t) || !in_domain(state.tet_region[t])) continue;
    for (const std::uint32_t v : mesh.tet(t).v) used[v] = 1;
  }
  for (std::uint32_t v = 1; v < mesh.num_vertices(); ++v)
    if (used[v]) map_vertex(v);
  for (std::uint32_t t = 0; t < mesh.tet_slots(); ++t) {
    if (mesh.is_dead(t) || mesh.is_infinite(t) || !in_domain(state.tet_region[t])) continue;
    const auto& v = mesh.tet(t).v;
    out.tets.push_back({map_vertex(v[0]), map_vertex(v[1]), map_vertex(v[2]), map_vertex(v[3])});
    out.tet_regions.push_back(state.tet_region[t]);
  }
  // Boundary faces in a deterministic order: facet by facet, in facet triangulation order.
  for (std::uint32_t f = 0; f < state.facets.size(); ++f) {
    for (const Subface& s : state.facets[f]->subfaces()) {
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
      out.boundary_faces.push_back({map_vertex(fv[0]), map_vertex(fv[2]), map_vertex(fv[1])});
      out.boundary_markers.push_back(state.facet_markers[f]);
      result.boundary_face_facets.push_back(f);
    }
  }
  out.marker_names = state.plc.facet_marker_names;
  out.region_names = state.plc.region_names;
  out.marker_colors = state.plc.facet_marker_colors;
  out.region_colors = state.plc.region_colors;
}

}  // namespace delmesh::tet3d
