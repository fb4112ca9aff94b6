// The shared OpenMesh mesh of the facet triangulations (see facet_mesh_pool.h).
#include "toolkit/facet/facet_mesh_pool.h"

#include <algorithm>

namespace delmesh {

FacetMeshPool::FacetMeshPool(const std::vector<Vec3>& points) : points_(&points) {
  mesh_.add_property(facet_);
  mesh_.add_property(next_copy_);
  mesh_.add_property(segment_);
  mesh_.add_property(next_edge_);
  mesh_.add_property(next_face_);
}

OpenMesh::VertexHandle FacetMeshPool::find_vertex(std::uint32_t facet, std::uint32_t global_id) const {
  if (global_id >= first_copy_.size()) return VH();
  for (VH v = first_copy_[global_id]; v.is_valid(); v = mesh_.property(next_copy_, v))
    if (mesh_.property(facet_, v) == facet) return v;
  return VH();
}

OpenMesh::VertexHandle FacetMeshPool::add_vertex(std::uint32_t facet, std::uint32_t global_id) {
  if (global_id >= first_copy_.size()) first_copy_.resize(std::max<std::size_t>(global_id + 1, first_copy_.size() * 3 / 2));
  const VH v = mesh_.add_vertex(FacetMesh::Point(global_id));
  mesh_.property(facet_, v) = facet;
  mesh_.property(next_copy_, v) = first_copy_[global_id];
  first_copy_[global_id] = v;
  return v;
}

void FacetMeshPool::unlink_vertex(VH v) {
  const std::uint32_t g = global_id(v);
  VH* link = &first_copy_[g];
  while (link->is_valid()) {
    if (*link == v) {
      *link = mesh_.property(next_copy_, v);
      mesh_.property(next_copy_, v) = VH();
      return;
    }
    link = &mesh_.property(next_copy_, *link);
  }
}

}  // namespace delmesh
