// TetMesh: compact storage of a 3D triangulation with an infinite vertex, and its
// navigation (notes §2.1.3; storage layout of ARCHITECTURE.md §4.4, the neighbour
// encoding of mmg and the infinite vertex of CGAL and geogram).
//
// Storage
//   - points: one Vec3 per vertex id, bit-exact copies of the input. Vertex 0 is the
//     INFINITE VERTEX (its coordinates are never read), so every triangle of the
//     triangulation is shared by exactly two tets: hull faces are glued to "infinite
//     tets" that join the hull face to vertex 0.
//   - tets: flat array of TetRecord (32 bytes): 4 vertex ids and 4 neighbour references.
//     adj[i] = 4*t' + j means: our face i is glued to face j of tet t'. Ids are 32-bit.
//     The array is a MappedArray (toolkit/core/mapped_array.h): it grows in place by
//     remapping pages, never holding an old and a new copy at once. So do the other
//     arrays that grow with the mesh during refinement (stamps, vertex_tet), whose
//     outgrown buffers would otherwise stay behind as holes in the heap.
//   - a generation stamp per tet (marks that never need clearing), a free list of dead
//     tets reused by later operations, and compact() to squeeze dead slots out.
//     The stamp array is allocated on demand: compact() releases it (its buffer becomes
//     the returned id map, so compaction needs no extra memory) and the next new_stamp()
//     brings it back, so a mesh that is only stored or read costs 32 bytes per tet.
//
// Local ordering (written once, used everywhere)
//
//                 v3                 Face i is the face opposite vertex v[i]. Its three
//                 /|\                vertices, in the order kFaceVertex[i], are
//                / | \               counterclockwise when seen from v[i]:
//               /  |  \                 orient3d(face[0], face[1], face[2], v[i]) > 0.
//              /   |   \             kFaceVertex = { {1,3,2}, {0,2,3}, {0,3,1}, {0,1,2} }.
//            v0----|----v2           Each row is an even permutation of the tet with v[i]
//              \   |   /             moved last, so replacing v[i] by a point p gives
//               \  |  /              orient3d(tet with v[i] := p) =
//                \ | /                  orient3d(face_i[0], face_i[1], face_i[2], p).
//                 v1
//
// Orientation convention (predicates.h: orient3d(a,b,c,d) = sign det[b-a, c-a, d-a]):
//   every live FINITE tet satisfies orient3d(p[v0], p[v1], p[v2], p[v3]) == Positive.
//   An INFINITE tet has vertex 0 at some index k; it is oriented as if vertex 0 were a
//   point far beyond its hull face: orient3d(face_k, q) is Positive exactly for points q
//   strictly outside the hull across that face (face_k listed in kFaceVertex[k] order).
//   Replacing vertex v[i] of any tet by a point p yields a tet of orientation
//   orient3d(face_i, p); every operation in toolkit/tetmesh builds new tets this way.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include "toolkit/core/mapped_array.h"
#include "toolkit/geometry/vec3.h"

namespace delmesh {

/// "No tet / no vertex / no reference".
inline constexpr std::uint32_t kNone = ~std::uint32_t{0};
/// Id of the infinite vertex.
inline constexpr std::uint32_t kInfiniteVertex = 0;

/// Vertices of face i (opposite vertex i), counterclockwise seen from vertex i.
inline constexpr std::uint8_t kFaceVertex[4][3] = {{1, 3, 2}, {0, 2, 3}, {0, 3, 1}, {0, 1, 2}};

/// One tetrahedron: v[i] is the vertex opposite face i; adj[i] = 4*t' + j encodes the
/// neighbour t' across face i and the index j of that face in t'.
struct TetRecord {
  std::array<std::uint32_t, 4> v;
  std::array<std::uint32_t, 4> adj;
};
static_assert(sizeof(TetRecord) == 32);

/// A face of a tet: the face of `tet` opposite its local vertex `face`.
struct FaceRef {
  std::uint32_t tet = kNone;
  std::uint8_t face = 0;
  friend bool operator==(const FaceRef&, const FaceRef&) = default;
};

/// A directed edge of a tet: local vertices i -> j of `tet`.
struct EdgeRef {
  std::uint32_t tet = kNone;
  std::uint8_t i = 0;
  std::uint8_t j = 0;
};

class TetMesh {
 public:
  /// An empty mesh holding only the infinite vertex.
  TetMesh();
  /// A mesh without tets whose vertex i + 1 is points[i] (vertex 0 is the infinite
  /// vertex). Takes the caller's array instead of copying it: pass it with std::move
  /// (when its capacity has no room for one more point it is reallocated once).
  explicit TetMesh(std::vector<Vec3> points);

  // ---- vertices -------------------------------------------------------------------
  /// Number of vertex ids, the infinite vertex included (ids 0 .. num_vertices()-1).
  std::uint32_t num_vertices() const { return static_cast<std::uint32_t>(points_.size()); }
  /// Appends a vertex (not yet connected to any tet) and returns its id.
  std::uint32_t add_vertex(const Vec3& p);
  /// Reserves room for `vertices` vertices and `tets` tet slots.
  void reserve(std::size_t vertices, std::size_t tets);
  const Vec3& point(std::uint32_t v) const { return points_[v]; }
  /// Moves vertex v to p. The caller guarantees that every tet of v's star stays
  /// positively oriented (mesh smoothing checks it with orient3d first).
  void move_point(std::uint32_t v, const Vec3& p) { points_[v] = p; }
  const double* coords(std::uint32_t v) const { return points_[v].data(); }
  std::span<const Vec3> points() const { return points_; }
  /// The point array itself (a reference that stays valid as the mesh grows), for
  /// structures that read vertex coordinates by id, such as FacetMeshPool.
  const std::vector<Vec3>& point_array() const { return points_; }
  /// One live tet incident to v, or kNone if v is in no tet (e.g. a merged duplicate).
  std::uint32_t vertex_tet(std::uint32_t v) const { return vertex_tet_[v]; }
  void set_vertex_tet(std::uint32_t v, std::uint32_t t) { vertex_tet_[v] = t; }
  /// Id of vertex v in the symbolic perturbation of insphere_sos: v itself, unless
  /// set_perturbation_ids gave vertex v another one.
  std::uint32_t perturbation_id(std::uint32_t v) const {
    return v < perturbation_ids_.size() ? perturbation_ids_[v] : v;
  }
  /// Perturbation ids of vertices 0 .. ids.size()-1: distinct, and below ids.size() so
  /// that vertices added later (which use their own id) never collide. Bulk construction
  /// stores vertices in insertion order for locality but perturbs by input index, so
  /// that renumbering to input order afterwards keeps the perturbed Delaunay property.
  void set_perturbation_ids(std::vector<std::uint32_t> ids) { perturbation_ids_ = std::move(ids); }
  /// Moves the perturbation ids set by set_perturbation_ids out of the mesh (empty if
  /// none), which goes back to perturbing every vertex by its own id.
  std::vector<std::uint32_t> take_perturbation_ids() { return std::exchange(perturbation_ids_, {}); }
  /// Renumbers the vertices: vertex v becomes new_id[v] (a permutation of 0 .. n-1 that
  /// fixes the infinite vertex 0). Points, tets and vertex_tet follow; perturbation ids
  /// go back to the identity.
  void renumber_vertices(std::span<const std::uint32_t> new_id);
  /// Recomputes vertex_tet() for every vertex from the live tets (after bulk operations
  /// that skipped its maintenance).
  void rebuild_vertex_tets();

  // ---- tets -----------------------------------------------------------------------
  /// Number of tet slots, dead ones included (valid tet ids are below this).
  std::uint32_t tet_slots() const { return static_cast<std::uint32_t>(tets_.size()); }
  /// Number of live tets (finite and infinite).
  std::uint32_t num_live_tets() const {
    return static_cast<std::uint32_t>(tets_.size() - free_tets_.size());
  }
  /// Number of live finite tets (the tetrahedralization proper).
  std::uint32_t num_finite_tets() const;
  bool is_dead(std::uint32_t t) const { return tets_[t].v[0] == kNone; }
  /// Local index of the infinite vertex in t, or -1 for a finite tet.
  int infinite_index(std::uint32_t t) const {
    const auto& v = tets_[t].v;
    return v[0] == 0 ? 0 : v[1] == 0 ? 1 : v[2] == 0 ? 2 : v[3] == 0 ? 3 : -1;
  }
  bool is_infinite(std::uint32_t t) const { return infinite_index(t) >= 0; }
  bool is_finite(std::uint32_t t) const { return infinite_index(t) < 0; }

  const TetRecord& tet(std::uint32_t t) const { return tets_[t]; }
  TetRecord& tet(std::uint32_t t) { return tets_[t]; }
  std::uint32_t vertex(std::uint32_t t, int i) const { return tets_[t].v[i]; }
  /// Neighbour of t across face i.
  std::uint32_t neighbor(std::uint32_t t, int i) const { return tets_[t].adj[i] >> 2; }
  /// Index, in neighbor(t, i), of the face glued to face i of t.
  int mirror_face(std::uint32_t t, int i) const { return static_cast<int>(tets_[t].adj[i] & 3u); }
  FaceRef mirror(FaceRef f) const {
    const std::uint32_t a = tets_[f.tet].adj[f.face];
    return {a >> 2, static_cast<std::uint8_t>(a & 3u)};
  }
  /// The vertex of the neighbouring tet opposite the face f.
  std::uint32_t opposite_vertex(FaceRef f) const {
    const FaceRef m = mirror(f);
    return tets_[m.tet].v[m.face];
  }
  /// Local index of vertex v in t, or -1.
  int local_index(std::uint32_t t, std::uint32_t v) const {
    const auto& r = tets_[t].v;
    return r[0] == v ? 0 : r[1] == v ? 1 : r[2] == v ? 2 : r[3] == v ? 3 : -1;
  }
  /// The three vertices of face f in kFaceVertex order.
  std::array<std::uint32_t, 3> face_vertices(FaceRef f) const {
    const auto& r = tets_[f.tet].v;
    const auto& o = kFaceVertex[f.face];
    return {r[o[0]], r[o[1]], r[o[2]]};
  }

  /// Creates a tet with vertices (a, b, c, d) and unset neighbours; reuses a dead slot
  /// when one is free. The caller is responsible for orientation and gluing.
  std::uint32_t create_tet(std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t d) {
    std::uint32_t t;
    if (!free_tets_.empty()) {
      t = free_tets_.back();
      free_tets_.pop_back();
    } else {
      t = static_cast<std::uint32_t>(tets_.size());
      // Stamps follow the tets only while the stamp array is allocated (see new_stamp).
      if (stamps_.size() == tets_.size()) stamps_.push_back(0);
      tets_.push_back(TetRecord{});
    }
    tets_[t].v = {a, b, c, d};
    tets_[t].adj = {kNone, kNone, kNone, kNone};
    last_tet_ = t;
    return t;
  }
  /// Marks t dead and puts its slot on the free list (its neighbours are not touched).
  void kill_tet(std::uint32_t t) {
    tets_[t].v[0] = kNone;
    free_tets_.push_back(t);
  }
  /// Glues face i of t to face j of u, in both directions.
  void glue(std::uint32_t t, int i, std::uint32_t u, int j) {
    tets_[t].adj[i] = (u << 2) | static_cast<std::uint32_t>(j);
    tets_[u].adj[j] = (t << 2) | static_cast<std::uint32_t>(i);
  }
  /// Sets face i of t to the encoded reference `ref` (4*u + j) and glues back.
  void glue_ref(std::uint32_t t, int i, std::uint32_t ref) {
    tets_[t].adj[i] = ref;
    tets_[ref >> 2].adj[ref & 3u] = (t << 2) | static_cast<std::uint32_t>(i);
  }

  /// Glues every still unglued face (adj == kNone) of the tets in `tets` to the face with
  /// the same three vertices, either of another tet in `tets` or among the faces given
  /// by `outside` (encoded references 4*t + j). Quadratic: for the few tets of a flip or
  /// a start-up configuration. Returns false if some face found no partner.
  bool glue_by_vertices(std::span<const std::uint32_t> tets, std::span<const std::uint32_t> outside);

  // ---- marks ----------------------------------------------------------------------
  /// A fresh stamp value no tet carries yet; stamps are cleared only on wrap-around.
  /// Allocates the stamp array (one zero per tet slot) when compact() released it, so
  /// stamp(), set_stamp() and stamps() are valid only after a new_stamp() call, for tets
  /// that existed then or were created after it.
  std::uint32_t new_stamp();
  /// Two consecutive fresh stamp values s and s+1 (returns s).
  std::uint32_t new_stamp_pair();
  /// Frees the stamp array (4 bytes per tet slot), as compact() does, for a mesh that is
  /// only read from now on; the next new_stamp() allocates it again.
  void release_stamps() {
    stamps_.release();
    current_stamp_ = 0;
  }
  std::uint32_t stamp(std::uint32_t t) const { return stamps_[t]; }
  void set_stamp(std::uint32_t t, std::uint32_t s) { stamps_[t] = s; }

  // ---- queries (all output buffers supplied by the caller) -------------------------
  /// A live tet of which v is a vertex, found through vertex_tet(); kNone if none.
  std::uint32_t any_tet_of(std::uint32_t v) const { return vertex_tet_[v]; }
  /// Every live tet incident to vertex v (its star), infinite tets included.
  void star(std::uint32_t v, std::vector<std::uint32_t>& out);
  /// Every vertex joined to v by an edge (its link vertices), the infinite one included.
  void vertex_neighbors(std::uint32_t v, std::vector<std::uint32_t>& out);
  /// A tet with edge (a, b), as local indices (i, j) with v[i] == a, v[j] == b.
  std::optional<EdgeRef> find_edge(std::uint32_t a, std::uint32_t b);
  /// The tets around edge (a, b), in rotation order: out[k] has the vertex set
  /// {a, b, ring[k], ring[k+1 mod m]} and (a, b, ring[k], ring[k+1]) is an even
  /// permutation of its vertices (positive orientation), and out[k] and out[k+1] share
  /// the face (a, b, ring[k+1]). The ring contains kInfiniteVertex for a hull edge.
  /// `ring` is optional. Returns false when (a, b) is not an edge.
  bool tets_around_edge(std::uint32_t a, std::uint32_t b, std::vector<std::uint32_t>& out,
                        std::vector<std::uint32_t>* ring = nullptr);
  /// The face (a, b, c) as seen from one of its two tets, or nullopt if it is not a face.
  std::optional<FaceRef> find_face(std::uint32_t a, std::uint32_t b, std::uint32_t c);

  // ---- maintenance ----------------------------------------------------------------
  /// Removes dead slots, renumbering live tets in their current order; returns the map
  /// old id -> new id (kNone for dead ones). The stamp array is released (its buffer
  /// holds the returned map); the next new_stamp() allocates a fresh one.
  MappedArray<std::uint32_t> compact();
  /// The hint used by point location: the last tet created.
  std::uint32_t last_tet() const { return last_tet_; }
  void set_last_tet(std::uint32_t t) { last_tet_ = t; }

  /// Raw access for the kernels of toolkit/tetmesh.
  MappedArray<TetRecord>& records() { return tets_; }
  const MappedArray<TetRecord>& records() const { return tets_; }
  std::vector<std::uint32_t>& free_list() { return free_tets_; }
  MappedArray<std::uint32_t>& stamps() { return stamps_; }

 private:
  std::vector<Vec3> points_;
  MappedArray<std::uint32_t> vertex_tet_;
  std::vector<std::uint32_t> perturbation_ids_;
  /// Grows without copying (mapped_array.h): the largest array of a refinement run.
  MappedArray<TetRecord> tets_;
  MappedArray<std::uint32_t> stamps_;
  std::vector<std::uint32_t> free_tets_;
  std::uint32_t current_stamp_ = 0;
  std::uint32_t last_tet_ = kNone;
};

}  // namespace delmesh
