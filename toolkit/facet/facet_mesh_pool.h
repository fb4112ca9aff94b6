// One OpenMesh triangle mesh that stores the triangulations of every facet of a PLC
// (notes §4.2.1: each facet keeps its own 2D constrained Delaunay triangulation whose
// triangles are the subfacets), each facet a separate component with its own copies of
// its vertices, so no facet's triangulation ever shares an element with another's.
//
// Memory layout (3D refinement keeps one triangulation per PLC facet: tens of thousands
// on curved surfaces, one per input triangle on a triangle soup):
//   - one mesh instead of one per facet: an OpenMesh mesh object with its property
//     tables costs about 2.5 KB before it holds a single vertex;
//   - the OpenMesh point of a vertex is its global id, the id of the shared vertex in the
//     tetrahedral core, whose coordinate array (given to the pool) is the only copy of
//     the coordinates; no normals, no status flags (a facet triangulation never deletes
//     an element: splits and flips reuse them);
//   - per vertex copy: the facet it belongs to and the next copy of the same global
//     vertex in another facet (a chain from first_copy[global id]), which replaces a
//     per-facet hash map from global ids to vertex handles;
//   - per face and per edge: the next face / edge of the same facet (lists in creation
//     order, so a facet enumerates its elements in the order a mesh of its own would).
// About 17 bytes per vertex copy, 37 per edge and 9 per face, and nothing per facet but
// the facet's own record (FacetTriangulation).
#pragma once

#include <cstdint>
#include <vector>

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>

#include "toolkit/geometry/vec3.h"

namespace delmesh {

/// The point of a vertex is the global id of the shared vertex (coordinates are read
/// from the coordinate array of the pool); connectivity only, with previous-halfedge
/// links (boundary loops of a facet can be long).
struct FacetMeshTraits : public OpenMesh::DefaultTraits {
  using Point = OpenMesh::VectorT<std::uint32_t, 1>;
};
using FacetMesh = OpenMesh::TriMesh_ArrayKernelT<FacetMeshTraits>;

class FacetMeshPool {
 public:
  using VH = OpenMesh::VertexHandle;
  using EH = OpenMesh::EdgeHandle;
  using FH = OpenMesh::FaceHandle;

  /// `points`: the coordinate array indexed by global vertex id (the tetrahedral core's
  /// points). The pool keeps a reference to the vector object: it may grow, it must
  /// outlive the pool.
  explicit FacetMeshPool(const std::vector<Vec3>& points);
  FacetMeshPool(const FacetMeshPool&) = delete;
  FacetMeshPool& operator=(const FacetMeshPool&) = delete;

  /// A new facet id (0, 1, ...).
  std::uint32_t new_facet() { return facet_count_++; }
  std::uint32_t facet_count() const { return facet_count_; }

  const FacetMesh& mesh() const { return mesh_; }
  FacetMesh& mesh() { return mesh_; }
  const std::vector<Vec3>& points() const { return *points_; }

  std::uint32_t global_id(VH v) const { return mesh_.point(v)[0]; }
  std::uint32_t facet_of(VH v) const { return mesh_.property(facet_, v); }
  /// The copy of global vertex `global_id` in `facet`, or an invalid handle.
  VH find_vertex(std::uint32_t facet, std::uint32_t global_id) const;
  /// Adds a copy of `global_id` to `facet` (the caller checks it has none yet).
  VH add_vertex(std::uint32_t facet, std::uint32_t global_id);
  /// Takes the copy v out of the lookup (it stays in the mesh, isolated).
  void unlink_vertex(VH v);

  bool is_segment(EH e) const { return mesh_.property(segment_, e); }
  void set_segment(EH e, bool segment) { mesh_.property(segment_, e) = segment; }

  /// Next face / edge of the same facet in creation order, invalid at the end.
  FH next_face(FH f) const { return mesh_.property(next_face_, f); }
  EH next_edge(EH e) const { return mesh_.property(next_edge_, e); }
  void set_next_face(FH f, FH next) { mesh_.property(next_face_, f) = next; }
  void set_next_edge(EH e, EH next) { mesh_.property(next_edge_, e) = next; }

  /// Coordinates of global vertex g: the array's, except for the one vertex being
  /// inserted before the core has it (set_pending).
  const double* coords(std::uint32_t g) const { return g == pending_id_ ? pending_.data() : (*points_)[g].data(); }
  /// Declares the coordinates of a vertex the core does not hold yet (kNoPending: none).
  void set_pending(std::uint32_t global_id, const Vec3& position) {
    pending_id_ = global_id;
    pending_ = position;
  }
  void clear_pending() { pending_id_ = kNoPending; }

  static constexpr std::uint32_t kNoPending = ~std::uint32_t{0};

  /// The pool's triangulations and lookup of vertex copies at one moment, which restore
  /// puts back (a trial change to the facets undone; the coordinates are the caller's).
  struct Saved {
    FacetMesh mesh;
    std::vector<VH> first_copy;
    std::uint32_t facet_count = 0;
  };
  Saved save() const { return {mesh_, first_copy_, facet_count_}; }
  /// Puts back a state save() took from this pool (the property handles are the same).
  void restore(const Saved& saved) {
    mesh_ = saved.mesh;
    first_copy_ = saved.first_copy;
    facet_count_ = saved.facet_count;
    clear_pending();
  }

 private:
  FacetMesh mesh_;
  const std::vector<Vec3>* points_;
  OpenMesh::VPropHandleT<std::uint32_t> facet_;
  OpenMesh::VPropHandleT<VH> next_copy_;
  OpenMesh::EPropHandleT<bool> segment_;
  OpenMesh::EPropHandleT<EH> next_edge_;
  OpenMesh::FPropHandleT<FH> next_face_;
  /// First copy of each global vertex (invalid: none), indexed by global id.
  std::vector<VH> first_copy_;
  std::uint32_t facet_count_ = 0;
  std::uint32_t pending_id_ = kNoPending;
  Vec3 pending_ = Vec3::Zero();
};

}  // namespace delmesh
