// Compact 2D (constrained) Delaunay triangulation: the kernel of delmesh's 2D meshing
// (notes §2.1.1, §2.1.2, §2.1.5).
//
// Storage (flat arrays, 32-bit ids, no per-element heap allocation):
//   tv[3t+i]  vertex i of triangle t (counterclockwise), or kGhost
//   tn[3t+i]  neighbour across edge i, encoded 3*u+j where j is the index of the same
//             edge in triangle u (so tn[tn[3t+i]] == 3t+i)
//   tf[t]     flags: bits 0..2 "edge i is a subsegment", kDead (slot on the free list),
//             kGhostTri (one vertex is the ghost), kOutside (removed from the domain:
//             exterior, hole or concavity), kVisited (scratch)
//   vt[v]     one triangle incident to vertex v (kNone when v is in no triangle)
//
// Local numbering / orientation table (for triangle t = (v0, v1, v2), counterclockwise):
//   edge i is opposite vertex i and runs from v[(i+1)%3] to v[(i+2)%3], so the triangle
//   lies on its left;  edge 0 = v1->v2, edge 1 = v2->v0, edge 2 = v0->v1.
//   Around vertex v[i], the next triangle counterclockwise lies across edge (i+1)%3
//   (the edge v[i+2]->v[i]); the next one clockwise lies across edge (i+2)%3.
//
// Hull: the convex hull is closed by ghost triangles (u, v, kGhost) on each hull edge
// v->u seen from inside, so every edge has two triangles and no case analysis is needed
// at the boundary. A ghost triangle (x, y, G) conflicts with a point p when p lies
// strictly left of x->y, or on the open segment xy.
//
// Insertion is Bowyer-Watson: the cavity of triangles whose circumcircle contains the
// new point (predicates::incircle_sos with the vertex ids, so cocircular points such as
// integer grids are resolved consistently) is found by a depth-first search that, in a
// constrained triangulation, does not cross subsegments; the cavity is checked to be
// star-shaped from the new point (exact orient2d) before anything is modified, so a
// refused insertion leaves the mesh untouched. Point location is a remembering
// visibility walk from the last triangle created.
#pragma once

#include <cstdint>
#include <vector>

#include "toolkit/core/error.h"
#include "toolkit/mesh2d/pslg.h"

namespace delmesh::mesh2d {

inline constexpr std::uint32_t kGhost = 0xFFFFFFFFu;
inline constexpr std::uint32_t kNone = 0xFFFFFFFFu;

inline constexpr std::uint8_t kSubsegMask = 0x07;
inline constexpr std::uint8_t kDead = 0x08;
inline constexpr std::uint8_t kGhostTri = 0x10;
inline constexpr std::uint8_t kOutside = 0x20;
inline constexpr std::uint8_t kVisited = 0x40;

inline constexpr std::uint32_t next3(std::uint32_t i) { return i == 2 ? 0 : i + 1; }
inline constexpr std::uint32_t prev3(std::uint32_t i) { return i == 0 ? 2 : i - 1; }

/// Where a point lies relative to the triangulation.
struct Location {
  enum Kind : std::uint8_t { InTriangle, OnVertex, Outside, Blocked } kind = InTriangle;
  std::uint32_t tri = kNone;     ///< containing triangle (ghost when Outside)
  std::uint32_t vertex = kNone;  ///< for OnVertex
  std::uint32_t edge = 3;        ///< Blocked: the subsegment edge index in `tri` that stopped the walk
};

class Triangulation {
 public:
  std::vector<Point2> points;
  std::vector<std::uint32_t> tv;
  std::vector<std::uint32_t> tn;
  std::vector<std::uint8_t> tf;
  std::vector<std::uint32_t> vt;
  /// Optional per-triangle region index (empty when regions are not tracked); new
  /// triangles inherit the region of the cavity triangle they replace.
  std::vector<std::uint32_t> region;

  std::uint32_t num_slots() const { return static_cast<std::uint32_t>(tf.size()); }
  bool alive(std::uint32_t t) const { return !(tf[t] & kDead); }
  bool ghost(std::uint32_t t) const { return (tf[t] & kGhostTri) != 0; }
  /// Alive, not ghost, not removed from the domain.
  bool in_domain(std::uint32_t t) const { return !(tf[t] & (kDead | kGhostTri | kOutside)); }
  bool subseg(std::uint32_t t, std::uint32_t i) const { return (tf[t] >> i) & 1u; }
  std::uint32_t vertex(std::uint32_t t, std::uint32_t i) const { return tv[3 * t + i]; }
  std::uint32_t org(std::uint32_t t, std::uint32_t i) const { return tv[3 * t + next3(i)]; }
  std::uint32_t dest(std::uint32_t t, std::uint32_t i) const { return tv[3 * t + prev3(i)]; }
  /// Marks or clears edge i of t as a subsegment on both of its sides.
  void set_subseg(std::uint32_t t, std::uint32_t i, bool on);
  /// Number of alive, non-ghost triangles (including those outside the domain).
  std::size_t count_real() const;
  std::size_t count_in_domain() const;

  /// Reserves room for about n vertices (and 2n triangles).
  void reserve(std::size_t n);

  /// Builds the Delaunay triangulation of `pts` (kept with their indices as vertex ids).
  /// Points are inserted in a BRIO/Hilbert order. An exact duplicate of an earlier point
  /// (in insertion order) is left out of the triangulation; duplicate_of[i] then names
  /// the vertex it coincides with (else kNone). All points collinear (or fewer than
  /// three distinct points): DegenerateInput.
  Expected<void> build_delaunay(std::vector<Point2> pts);
  std::vector<std::uint32_t> duplicate_of;
  std::size_t num_duplicates = 0;

  /// Visibility walk from `start` (or the last triangle created) towards p. With
  /// `stop_at_subsegments`, the walk does not cross subsegments nor leave the domain, and
  /// reports Blocked with the edge that stopped it.
  Location locate(const Point2& p, std::uint32_t start = kNone, bool stop_at_subsegments = false);

  /// Bowyer-Watson insertion of a point already appended to `points` (id = its index).
  /// `seeds` are triangles known to be in conflict (the containing triangle, or both
  /// triangles of the edge p lies on). With `constrained` the cavity does not cross
  /// subsegments nor enter ghost/outside triangles except the seeds. Returns false (and
  /// changes nothing) if the cavity is not star-shaped from p. On success, new_tris()
  /// lists the new triangles, each with p at local index 2.
  bool find_cavity(std::uint32_t p, const std::uint32_t* seeds, int num_seeds, bool constrained);
  const std::vector<std::uint32_t>& cavity_tris() const { return cavity_; }
  void commit_cavity(std::uint32_t p);
  /// Abandons the cavity last found (clears the scratch marks).
  void abandon_cavity();
  const std::vector<std::uint32_t>& new_tris() const { return new_tris_; }
  /// Subsegments on the boundary of the cavity last found, as (triangle, edge) outside it.
  struct CavityEdge {
    std::uint32_t outer;  ///< 3*u+j of the edge seen from the triangle outside the cavity
    std::uint32_t a, b;   ///< edge a->b with the cavity on its left
    std::uint32_t inner;  ///< the cavity triangle that owned the edge
    std::uint8_t inner_flags;      ///< kOutside bit of `inner`, inherited by the new triangle
    std::uint32_t inner_region;    ///< region of `inner` when regions are tracked
  };
  const std::vector<CavityEdge>& cavity_boundary() const { return boundary_; }

  /// Finds the edge a->b: returns 3t+i with edge i of t running from a to b, or kNone.
  std::uint32_t find_edge(std::uint32_t a, std::uint32_t b) const;
  /// Flips edge i of triangle t (both triangles real). The two triangles keep their ids.
  void flip(std::uint32_t t, std::uint32_t i);

  /// Triangle slot allocation (free list threaded through tn[3t]).
  std::uint32_t alloc_tri();
  void free_tri(std::uint32_t t);

  std::uint32_t last_tri = kNone;

 private:
  bool conflict(std::uint32_t t, std::uint32_t p) const;
  std::uint32_t free_head_ = kNone;
  std::uint32_t rng_ = 2463534242u;
  std::vector<std::uint32_t> cavity_;
  std::vector<std::uint32_t> stack_;
  std::vector<CavityEdge> boundary_;
  std::vector<std::uint32_t> new_tris_;
  std::vector<std::uint32_t> link_;  ///< per vertex scratch: new triangle starting there
  std::uint32_t ghost_link_ = kNone;
};

}  // namespace delmesh::mesh2d
