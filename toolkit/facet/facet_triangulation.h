// The triangulation of one planar facet of a PLC, kept in an OpenMesh triangle mesh while
// 3D Delaunay refinement recovers and refines the facet (notes §4.2.1: each facet is
// maintained as a 2D constrained Delaunay triangulation whose triangles, the subfacets,
// must appear as faces of the tetrahedralization).
//
// Vertices carry the global id of the tetrahedral core's point array (the source of
// truth; OpenMesh holds a bit-exact copy of the coordinates). Every 2D decision uses
// exact predicates on the 3D coordinates projected along the dominant axis of the facet
// normal (orient2d_projected), and Delaunay flips use incircle_in_plane, a fixed
// positive definite in-plane metric, so Steiner points that lie off the plane by roundoff
// still give a well-defined constrained Delaunay triangulation and flipping terminates.
// Faces are stored counterclockwise in the projection. Segment edges (the facet's
// boundary, hole boundaries and internal segments) are never flipped.
#pragma once

#include <array>
#include <optional>
#include <cstdint>
#include <span>
#include <string>
#include <unordered_map>
#include <vector>

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>

#include "toolkit/core/error.h"
#include "toolkit/geometry/vec3.h"
#include "toolkit/predicates/predicates.h"

namespace delmesh {

/// No status attributes: a facet triangulation never deletes an element (splits and
/// flips reuse them), and 3D refinement keeps one mesh per PLC facet (tens of thousands
/// on curved surfaces), so every property a mesh carries costs memory per facet.
struct FacetMeshTraits : public OpenMesh::DefaultTraits {
  using Point = OpenMesh::Vec3d;
  using Normal = OpenMesh::Vec3d;
};
using FacetMesh = OpenMesh::TriMesh_ArrayKernelT<FacetMeshTraits>;

/// A subfacet as three global vertex ids.
using Subface = std::array<std::uint32_t, 3>;

/// Subfacets that an operation removed and added (sorted-id triples), so the 3D side can
/// update its face lookups and refinement queues.
struct SubfaceChange {
  std::vector<Subface> removed;
  std::vector<Subface> added;
};

class FacetTriangulation {
 public:
  /// `normal`: any nonzero normal of the facet's plane (it fixes the projection axis and
  /// the in-plane metric).
  explicit FacetTriangulation(const Vec3& normal);

  Axis axis() const { return axis_; }
  const Vec3& normal() const { return normal_; }

  /// Adds a vertex (not yet in any triangle) with its global id; ids are unique.
  void add_vertex(std::uint32_t global_id, const Vec3& position);

  /// Replaces the triangles by `triangles` (global ids of added vertices, any orientation)
  /// and marks `segments` as constrained edges. Error if a triangle is degenerate in the
  /// projection, the triangles do not form a manifold, or a segment is not an edge.
  Expected<void> assign(std::span<const Subface> triangles,
                        std::span<const std::array<std::uint32_t, 2>> segments);

  /// Flips unconstrained edges until every one is locally Delaunay (in the facet metric).
  /// Returns the number of flips.
  std::size_t make_delaunay(SubfaceChange* change = nullptr);

  /// Inserts a new vertex whose projection lies in the facet's triangulated domain:
  /// splits the triangle (or the edge, or the segment) containing it and restores the
  /// constrained Delaunay property by flips. Error if the point is outside the domain or
  /// coincides with a vertex.
  Expected<SubfaceChange> insert_vertex(std::uint32_t global_id, const Vec3& position);

  /// Splits the segment (a, b) at a new vertex (global id v) on it.
  Expected<SubfaceChange> split_segment(std::uint32_t a, std::uint32_t b, std::uint32_t v, const Vec3& position);

  /// The subfacet whose closed projection contains the projection of p (vertices in
  /// counterclockwise order), found by a walk from a triangle at `near_vertex` (or any
  /// triangle when it is not a vertex of the facet); nullopt when p projects outside the
  /// facet. Used for the Projection Lemma order of subfacet splits (notes §4.2.1).
  std::optional<Subface> locate(const double* p, std::uint32_t near_vertex) const;

  /// The third vertex of the triangle holding the directed edge a -> b, or ~0u.
  std::uint32_t third_vertex(std::uint32_t a, std::uint32_t b) const;

  /// Flips the unconstrained interior edge (a, b) when its quadrilateral is strictly
  /// convex in projection (exact test); error otherwise. Used to make the facet agree with
  /// the tetrahedralization where cocircular vertices allow two triangulations (notes
  /// Figure 4.8).
  Expected<SubfaceChange> flip_edge(std::uint32_t a, std::uint32_t b);

  /// Would moving vertex `global_id` to `position` keep every triangle around it
  /// counterclockwise in projection (exact orient2d_projected)? False for an unknown id.
  /// Mesh smoothing moves facet vertices within the facet's plane with this check; the
  /// triangulation then need not stay Delaunay.
  bool can_move_vertex(std::uint32_t global_id, const Vec3& position) const;
  /// Moves the vertex (callers check can_move_vertex first).
  void move_vertex(std::uint32_t global_id, const Vec3& position);

  std::vector<Subface> subfaces() const;
  std::size_t subface_count() const { return mesh_.n_faces(); }
  bool has_vertex(std::uint32_t global_id) const { return handle_.count(global_id) != 0; }
  bool has_subface(std::uint32_t a, std::uint32_t b, std::uint32_t c) const;
  bool is_segment(std::uint32_t a, std::uint32_t b) const;
  /// Global ids of the segment edges.
  std::vector<std::array<std::uint32_t, 2>> segments() const;

  /// Structural and Delaunay checks: faces counterclockwise in projection, no
  /// unconstrained edge violating the Delaunay criterion. Empty when valid.
  std::vector<std::string> check() const;

  const FacetMesh& mesh() const { return mesh_; }

 private:
  using VH = OpenMesh::VertexHandle;
  using HH = OpenMesh::HalfedgeHandle;
  using EH = OpenMesh::EdgeHandle;
  using FH = OpenMesh::FaceHandle;

  const double* coords(VH v) const { return mesh_.point(v).data(); }
  std::uint32_t id(VH v) const { return mesh_.property(global_id_, v); }
  bool constrained(EH e) const { return mesh_.property(segment_, e); }
  Subface face_ids(FH f) const;
  /// Is the unconstrained interior edge e locally non-Delaunay?
  bool should_flip(EH e) const;
  void record_removed(FH f, SubfaceChange* change) const;
  void record_added(FH f, SubfaceChange* change) const;
  /// Lawson flips from a stack of edges; records changes.
  std::size_t flip_edges(std::vector<EH>& stack, SubfaceChange* change);
  /// The halfedge h of edge (a, b) or invalid.
  HH find_halfedge(std::uint32_t a, std::uint32_t b) const;
  Expected<SubfaceChange> split_edge_at(EH e, VH v);

  FacetMesh mesh_;
  OpenMesh::VPropHandleT<std::uint32_t> global_id_;
  OpenMesh::EPropHandleT<bool> segment_;
  std::unordered_map<std::uint32_t, VH> handle_;
  Vec3 normal_;
  Axis axis_;
  FH last_face_;
};

}  // namespace delmesh
