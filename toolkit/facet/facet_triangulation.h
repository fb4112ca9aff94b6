// The triangulation of one planar facet of a PLC, kept in OpenMesh while 3D Delaunay
// refinement recovers and refines the facet (notes §4.2.1: each facet is maintained as a
// 2D constrained Delaunay triangulation whose triangles, the subfacets, must appear as
// faces of the tetrahedralization).
//
// The facet's triangulation is one component of a FacetMeshPool (facet_mesh_pool.h): its
// own vertex copies, edges and faces in the pool's OpenMesh mesh, each vertex carrying
// the global id of the tetrahedral core's vertex, whose coordinates (the only copy) the
// pool reads. Every 2D decision uses exact predicates on the 3D coordinates projected
// along the dominant axis of the facet normal (orient2d_projected), and Delaunay flips
// use incircle_in_plane, a fixed positive definite in-plane metric, so Steiner points
// that lie off the plane by roundoff still give a well-defined constrained Delaunay
// triangulation and flipping terminates. Faces are stored counterclockwise in the
// projection. Segment edges (the facet's boundary, hole boundaries and internal
// segments) are never flipped.
//
// A facet that is a single triangle (every input triangle of a surface mesh is a facet
// of its own) may be assigned with assign_lone_triangle: the pool then holds nothing of
// it, the record keeps its three vertex ids, and the read-only queries answer from them,
// until the first operation that changes the facet (insert_vertex, split_segment,
// flip_edge, add_vertex) builds its component in the pool exactly as add_vertex and
// assign would have (same vertex order, same face). Per facet, elements are listed in
// their own creation order, so where in the pool a component lies changes no answer.
// Refinement splits only some facets: the others cost their record alone.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "toolkit/core/error.h"
#include "toolkit/facet/facet_mesh_pool.h"
#include "toolkit/geometry/vec3.h"
#include "toolkit/predicates/predicates.h"

namespace delmesh {

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
  /// A new, empty facet in `pool` (which must outlive it). `normal`: any nonzero normal
  /// of the facet's plane (it fixes the projection axis and the in-plane metric).
  FacetTriangulation(FacetMeshPool& pool, const Vec3& normal);

  Axis axis() const { return axis_; }
  const Vec3& normal() const { return normal_; }

  /// Adds a vertex (not yet in any triangle) by its global id, whose coordinates the
  /// pool's coordinate array holds; ids are unique within the facet.
  void add_vertex(std::uint32_t global_id);

  /// Replaces the triangles by `triangles` (global ids of added vertices, any orientation)
  /// and marks `segments` as constrained edges. Error if a triangle is degenerate in the
  /// projection, the triangles do not form a manifold, or a segment is not an edge.
  Expected<void> assign(std::span<const Subface> triangles,
                        std::span<const std::array<std::uint32_t, 2>> segments);

  /// The same facet as add_vertex for each of `vertices` (in that order) followed by
  /// assign({triangle}, its three edges), with the pool's component built only when an
  /// operation first changes the facet. `triangle`: the three ids of `vertices`, any
  /// orientation. Error if it is degenerate in the projection.
  Expected<void> assign_lone_triangle(const std::array<std::uint32_t, 3>& vertices, const Subface& triangle);

  /// Flips unconstrained edges until every one is locally Delaunay (in the facet metric).
  /// Returns the number of flips.
  std::size_t make_delaunay(SubfaceChange* change = nullptr);

  /// Inserts a new vertex whose projection lies in the facet's triangulated domain:
  /// splits the triangle (or the edge, or the segment) containing it and restores the
  /// constrained Delaunay property by flips. Error if the point is outside the domain or
  /// coincides with a vertex. `position` may be a point the coordinate array does not
  /// hold yet; the array must hold it (bit-identical) before the next call on the pool.
  /// The walk that finds the triangle starts at a triangle of `near_vertex` when that is a
  /// vertex of the facet (e.g. a vertex of the subfacet whose circumcenter is inserted),
  /// else at the triangle last touched; the result does not depend on where it starts.
  /// With `delaunay` false the split is made without the flips (mesh improvement makes
  /// the flips it has checked itself, with flip_edge).
  Expected<SubfaceChange> insert_vertex(std::uint32_t global_id, const Vec3& position,
                                        std::uint32_t near_vertex = ~0u, bool delaunay = true);

  /// Splits the segment (a, b) at a new vertex (global id v) on it (`position` as for
  /// insert_vertex; `delaunay` false: without the flips, as there).
  Expected<SubfaceChange> split_segment(std::uint32_t a, std::uint32_t b, std::uint32_t v, const Vec3& position,
                                        bool delaunay = true);

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
  /// Mesh smoothing moves facet vertices within the facet's plane with this check (and
  /// then moves the shared vertex in the coordinate array); the triangulation then need
  /// not stay Delaunay.
  bool can_move_vertex(std::uint32_t global_id, const Vec3& position) const;

  /// The subfacets in creation order of their faces.
  std::vector<Subface> subfaces() const;
  std::size_t subface_count() const { return face_count_; }
  bool has_vertex(std::uint32_t global_id) const;
  bool has_subface(std::uint32_t a, std::uint32_t b, std::uint32_t c) const;
  bool is_segment(std::uint32_t a, std::uint32_t b) const;
  /// Global ids of the segment edges.
  std::vector<std::array<std::uint32_t, 2>> segments() const;

  /// Structural and Delaunay checks: faces counterclockwise in projection, no
  /// unconstrained edge violating the Delaunay criterion. Empty when valid.
  std::vector<std::string> check() const;

  std::uint32_t facet_id() const { return facet_; }
  const FacetMeshPool& pool() const { return *pool_; }
  /// The facet's copy of global vertex `global_id` in the pool's mesh, or invalid (also
  /// while the facet is a lone triangle not yet built in the pool).
  OpenMesh::VertexHandle vertex_handle(std::uint32_t global_id) const { return pool_->find_vertex(facet_, global_id); }
  /// Is the facet a lone triangle whose component the pool does not hold yet?
  bool deferred() const { return lone_[0] != kNoVertex; }

 private:
  using VH = OpenMesh::VertexHandle;
  using HH = OpenMesh::HalfedgeHandle;
  using EH = OpenMesh::EdgeHandle;
  using FH = OpenMesh::FaceHandle;

  static constexpr std::uint32_t kNoVertex = ~std::uint32_t{0};

  FacetMesh& mesh() const { return pool_->mesh(); }
  const double* coords(VH v) const { return pool_->coords(id(v)); }
  std::uint32_t id(VH v) const { return pool_->global_id(v); }
  bool constrained(EH e) const { return pool_->is_segment(e); }
  /// The facet's faces / edges in creation order.
  std::vector<FH> face_list() const;
  std::vector<EH> edge_list() const;
  /// Element counts of the pool's mesh before an operation on this facet: adopt() then
  /// appends the faces and edges the operation created to the facet's lists.
  struct Mark {
    std::size_t faces, edges;
  };
  Mark mark() const { return {mesh().n_faces(), mesh().n_edges()}; }
  /// The lone triangle's vertices counterclockwise in projection, as face_ids lists the
  /// face that assign builds from it.
  Subface lone_face() const;
  /// Builds a deferred facet's component in the pool (no-op otherwise).
  void build_deferred();
  void adopt(Mark before);
  Subface face_ids(FH f) const;
  /// Is the unconstrained interior edge e locally non-Delaunay?
  bool should_flip(EH e) const;
  void record_removed(FH f, SubfaceChange* change) const;
  void record_added(FH f, SubfaceChange* change) const;
  /// Lawson flips from a stack of edges; records changes.
  std::size_t flip_edges(std::vector<EH>& stack, SubfaceChange* change);
  /// The halfedge h of edge (a, b) or invalid.
  HH find_halfedge(std::uint32_t a, std::uint32_t b) const;
  Expected<SubfaceChange> split_edge_at(EH e, VH v, bool delaunay = true);

  FacetMeshPool* pool_;
  Vec3 normal_;
  std::uint32_t facet_;
  Axis axis_;
  /// While deferred: lone_face() is lone_ reordered by permutation lone_order_ (of the six).
  std::uint8_t lone_order_ = 0;
  FH first_face_, tail_face_, last_face_;
  EH first_edge_, tail_edge_;
  std::uint32_t face_count_ = 0;
  /// While deferred: the lone triangle's vertex ids in the order add_vertex would add them.
  std::array<std::uint32_t, 3> lone_{kNoVertex, kNoVertex, kNoVertex};
};

}  // namespace delmesh
