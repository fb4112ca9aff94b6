// Vertex insertion into a TetMesh: Bowyer–Watson with the cavity found by depth-first
// search (notes §2.1.5, "the insertion polyhedron may be found by depth-first search
// from the initial triangle"; Bowyer 1981, Watson 1981), and topological splits of a
// tet, a face or an edge at a given vertex.
//
// Robustness. A tet is in conflict with the new point p (id ip) when
//   finite tet (a,b,c,d):   insphere_sos(a,b,c,d,p) is Positive — exact, and with
//                           symbolic perturbation (ids) so cospherical points are never
//                           ambiguous;
//   infinite tet, hull face f: orient3d(f, p) is Positive (p strictly beyond the hull
//                           face), or it is Zero and the finite tet across f is in
//                           conflict (the limit of the perturbed test as the infinite
//                           vertex goes to infinity, as in CGAL and geogram).
// With these exact, perturbed tests the conflict region is exactly the set of tets whose
// perturbed circumsphere holds p; it is connected and star-shaped from p, so the DFS
// from the tet containing p finds all of it and the new tets (p joined to each boundary
// face) are positively oriented. Cospherical input (grids) can never corrupt the mesh.
//
// Two-phase use (needed by Delaunay refinement to test a candidate point): compute_cavity
// finds the conflict tets and the boundary faces WITHOUT changing the mesh; the caller
// may inspect them (e.g. check that the cavity crosses no constrained face) and then
// commit_cavity, or simply drop the Cavity. The mesh must not change in between.
#pragma once

#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "toolkit/tetmesh/tet_locate.h"
#include "toolkit/tetmesh/tet_mesh.h"

namespace delmesh {

/// A boundary face of a cavity: its vertices, ordered so that the cavity lies on their
/// positive side (orient3d(v[0], v[1], v[2], x) > 0 for x inside the cavity), and the
/// encoded reference 4*t + j of the face of the surviving tet glued to it.
struct CavityFace {
  std::uint32_t v[3];
  std::uint32_t outside;
};

/// The conflict region of a point, plus scratch buffers reused from one insertion to
/// the next (keep one Cavity per thread and pass it to every call: no allocation in the
/// steady state).
struct Cavity {
  std::vector<std::uint32_t> tets;      ///< tets to delete
  std::vector<CavityFace> boundary;     ///< faces to join to the new vertex
  std::vector<std::uint32_t> created;   ///< after commit: the new tets, one per boundary face
  Location location;                    ///< where the point was located
  std::uint64_t rng = 0x9E3779B97F4A7C15ULL;  ///< state of the location walk
  /// commit_cavity keeps mesh.vertex_tet() up to date; bulk construction turns this off
  /// and calls mesh.rebuild_vertex_tets() once at the end.
  bool update_vertex_tets = true;

  // scratch
  std::vector<std::uint32_t> stack;
  std::vector<std::uint64_t> edge_keys;
  std::vector<std::uint32_t> edge_values;
  std::vector<std::uint32_t> used_slots;
  std::vector<std::uint32_t> edge_table;
  std::vector<std::uint32_t> vertex_mark;
  std::uint32_t epoch = 0;
  std::vector<std::uint32_t> drop;  ///< shrink_cavity_to_star: the tets leaving the cavity
  std::vector<std::uint32_t> kept;  ///< shrink_cavity_to_star: the tets staying
};

/// Is tet t in conflict with point p of id ip (see the rule above)?
bool tet_in_conflict(const TetMesh& mesh, std::uint32_t t, const double* p, std::uint32_t ip);

/// Computes the Bowyer–Watson cavity of point p without changing the mesh. `ip` is the
/// id p has or will have (it decides the symbolic perturbation; use mesh.num_vertices()
/// for a point not yet added). Returns the location; when it is OnVertex the point
/// duplicates vertex mesh.vertex(loc.tet, loc.i) and the cavity is left empty.
Location compute_cavity(TetMesh& mesh, const double* p, std::uint32_t ip, std::uint32_t hint,
                        Cavity& cavity);

/// Decides whether the cavity search may cross face `face` of tet `tet`: true blocks it
/// (the face becomes a boundary face of the cavity). Must give the same answer from
/// either side of a face.
using CavityBlocker = std::function<bool(std::uint32_t tet, int face)>;

/// compute_cavity for insertion into a constrained (Delaunay) tetrahedralization (notes
/// §2.1.7: "vertices may be incrementally inserted into a CDT just like an ordinary
/// Delaunay triangulation"): the depth-first search from the tet holding p never crosses
/// a face the blocker blocks, so the cavity holds only the conflict tets visible from p
/// through unblocked faces. The same exact, perturbed conflict test as compute_cavity.
Location compute_constrained_cavity(TetMesh& mesh, const double* p, std::uint32_t ip, std::uint32_t hint,
                                    const CavityBlocker& blocked, Cavity& cavity);

/// Makes a cavity safe to commit for p when the mesh is only approximately constrained
/// Delaunay: while a finite boundary face does not see p strictly on its positive side,
/// or a vertex of a cavity tet is not on the boundary (it would be lost), the cavity tet
/// owning that face (holding that vertex) is removed from the cavity. Never removes
/// tet `keep` (the tet holding p): returns false when it would have to, or when the
/// cavity empties; true when the cavity is star-shaped from p with no interior vertex.
/// Each round removes at least one tet, so it ends within cavity.tets.size() rounds.
/// `shrunk` is set when a tet was removed.
bool shrink_cavity_to_star(TetMesh& mesh, const double* p, std::uint32_t keep, Cavity& cavity, bool& shrunk);

/// Replaces the cavity tets by the tets joining vertex v to every boundary face. v must be
/// the vertex the cavity was computed for. Fills cavity.created; returns one new tet.
std::uint32_t commit_cavity(TetMesh& mesh, std::uint32_t v, Cavity& cavity);

/// Fills cavity.tets and cavity.boundary for an arbitrary set of live tets (the faces of
/// the set not shared by two of its tets form the boundary). The set must be a
/// topological ball for commit_cavity to produce a valid mesh.
void cavity_from_tets(TetMesh& mesh, std::span<const std::uint32_t> tets, Cavity& cavity);

/// True when joining point p to every boundary face gives positively oriented tets (finite
/// faces only are tested: faces through the infinite vertex are combinatorial).
bool cavity_is_star_shaped(const TetMesh& mesh, const double* p, const Cavity& cavity);

struct InsertResult {
  Location location;
  std::uint32_t duplicate_of = kNone;  ///< the existing vertex at the same position, if any
  std::uint32_t tet = kNone;           ///< a new tet incident to the vertex (kNone if duplicate)
};

/// Bowyer–Watson insertion of vertex v (already added with mesh.add_vertex) into a mesh
/// with at least one finite tet. A vertex at the position of an existing one is not
/// inserted: the result names the existing vertex. hint: starting tet or kNone.
InsertResult insert_vertex(TetMesh& mesh, std::uint32_t v, std::uint32_t hint, Cavity& cavity);

/// Builds the first finite tet (a, b, c, d), reordered to positive orientation, and the
/// four infinite tets around it. The mesh must have no tets yet and the four points must
/// not be coplanar. Returns the finite tet.
std::uint32_t make_first_tet(TetMesh& mesh, std::uint32_t a, std::uint32_t b, std::uint32_t c,
                             std::uint32_t d);

/// Topological splits at vertex v, which must lie in the relative interior of the split
/// simplex (checked exactly on the finite new tets: when the check fails nothing
/// changes and false is returned). They keep the mesh valid but not necessarily Delaunay
/// (restore with flips, or use insert_vertex instead). Used by constrained refinement to
/// put a vertex on a face or edge without touching anything else.
bool split_tet(TetMesh& mesh, std::uint32_t t, std::uint32_t v, Cavity& cavity);
bool split_face(TetMesh& mesh, FaceRef face, std::uint32_t v, Cavity& cavity);
bool split_edge(TetMesh& mesh, std::uint32_t a, std::uint32_t b, std::uint32_t v, Cavity& cavity);

}  // namespace delmesh
