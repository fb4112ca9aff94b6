// Small input angles (notes §4.2.3) and the tets that touch them. Theorem 28 of the notes
// guarantees termination of 3D Delaunay refinement only when the PLC has
//   * no two segments meeting at a vertex at an angle below 60 degrees,
//   * no segment meeting a facet at a vertex at an angle below arccos(1 / (2 sqrt 2)),
//     about 69.3 degrees, when the segment's orthogonal projection onto the facet's
//     plane enters the facet at that vertex (else the Projection Lemma makes the angle
//     harmless),
//   * no two facets meeting at a segment at a dihedral angle below 90 degrees (the
//     projection condition for convex facets; measured here as the angle between the
//     two facets' half-planes at the segment, so a thin wedge counts whichever side the
//     domain is on).
// Where such an angle occurs the termination floors of quality_refinement.h stop
// refinement, and the tets there may miss the radius-edge bound or the dihedral window.
//
// The rule used to report them (MeshResult::tet_at_small_angle, MeshStats, the CLI
// summary): a tet touches a small input angle when one of its four vertices is
//   (a) an input vertex where one of the angles above occurs (an apex), or
//   (b) a vertex on a segment whose facets meet below 90 degrees (a sharp segment; its
//       endpoints are apices by (a)),
//   (c) or when one of its vertices w lies in the floor zone of a sharp wedge: on one of
//       the two facets F1, F2 that meet at a sharp segment s at the angle theta < 89
//       degrees (on the facet or on its boundary segments and vertices), within distance
//       floor(w) / sin(theta) of s, floor(w) its termination floor (VertexInfo::
//       field_floor, quality_refinement.h). There the wedge is thinner than the floor:
//       dist(w, s) sin(theta) bounds the distance from w to the other facet's plane, and
//       refinement, whose vertices keep their floor from every other vertex, cannot grade
//       the mesh down towards s; splitting further would start the cycle of ever-shorter
//       edges that the small angle causes (notes §3.8, §4.2.3) and that the floor is there
//       to cut. A tet at w across the wedge is then flat or needle-like (a sliver, or a
//       cap) without touching s. The rule once asked all four vertices of the tet to lie on
//       the two facets in the zone; caps across the wedge with a vertex a little beyond it,
//       and tets at the zone with an interior vertex, then counted as elsewhere. Tets
//       outside the window [20, 150] at radius-edge 2 away from small angles, four
//       vertices -> one vertex: td-wedge-10 (10 degree wedge) 5 -> 0, td-wedge-5 1 -> 0,
//       td-slit-1 (4 degree edge) 116 -> 39; at radius-edge 1.414, tets above the bound
//       elsewhere on td-slit-1 3644 -> 0 (tets marked 3346 -> 12305 of 26342: most of its
//       mesh lies around the slit), td-wedge-10 4 -> 0; cgal-fandisk and trimesh-busted
//       unchanged.
//   (d) or when one of its vertices w lies on a segment s that makes an angle theta
//       below the limits above with another segment or a facet at an end a of s, where
//       the angle is narrower than w's termination floor: |w - a| sin(theta) <= floor(w)
//       (the floor zone of the angle; |w - a| sin(theta) is w's distance from the other
//       arm's line, or from the facet's plane). Refinement cannot place a vertex between the arms there (every
//       vertex keeps its floor from the others), so conforming recovery's subsegments on
//       the arms, as short as the gap between them, stay the shortest edges of the tets
//       around them. On a needle triangle of a surface mesh (cgal-anchor.off: arms of
//       0.55 at 0.017 degrees, their far ends 1.8e-4 apart, floors ~0.002) the zone covers
//       both arms end to end; at a 59 degree corner it reaches about a floor from the apex.
//       Measured at radius-edge 1.414 (tets above the bound elsewhere, before -> after the
//       rule): cgal-anchor 23229 -> 4, cgal-boeing 5233 -> 14, cgal-dino 2958 -> 9,
//       cgal-knot2 960 -> 6, cgal-armadillo 3320 -> 36, occt-sh2 18385 -> 899, gmsh-part
//       249 -> 2, gmsh-t20-data 383 -> 0, occt-screw 46 -> 0, pocc-io1-ug-214 12 -> 0; on
//       cgal-fandisk the tets marked go from 48751 to 48770. The mesh is the same: the rule
//       only sorts tets for the report.
//   (e) or when one of its vertices w lies beside a narrow corner: two segments s1, s2 meet
//       at an input vertex a at an angle below 60 degrees, w lies on a facet that has s1 or
//       s2 on its boundary (on the facet or on its boundary segments and vertices, but not
//       on s1 or s2 themselves: those are rule (d)'s), and w lies within its termination
//       floor of both s1 and s2. The corner's floor zone of rule (d) seen from the facets
//       beside its arms: refinement cannot place a vertex between w and either arm, so the
//       facet vertices that encroachment of the arms' short subsegments put there (as
//       close to the arm as the gap between the arms) stay the corners of flat tets lying
//       on the facet. gmsh-part.step has a wall facet with a 1.05 degree corner at each of
//       (56.93, +-7.94, 61.92) between its edges with two nearly tangent top faces (CAD
//       faces 13 and 23, 12 and 23): the top face's vertices beside the upper edge lie
//       0.002-0.004 from it, the gap between the arms there 0.0007-0.003, and three tets
//       on them, each with a vertex below the top face, were left outside the dihedral
//       window [20, 150] away from small angles (10.8 to 18.5 degrees, one at 151.2; 5 of
//       35619 tets, 0.014%, before the rule, 2 after); the rule marks 111 more of its tets
//       (7683 -> 7794). At a 59 degree corner it reaches about a floor from the apex.
//   (f) or when the tet lies across a sharp wedge: two of its vertices lie on the two
//       facets F1, F2 that meet at a sharp segment s at the angle theta (each on its facet
//       or on the facet's boundary), and one of them, w, lies within 2 floor(w) / sin(theta)
//       of s: the wedge is narrower than two floors there. A tet with a vertex on each
//       facet has a circumradius of at least half their distance, so at least half the
//       wedge's width between them, and no more is forced: where the width is below twice
//       the floor, the circumradius may lie under the floor, which then refuses the split
//       (its insertion radius is the circumradius), and the tet stays flat or needle-like
//       across the wedge. Rule (c) marks by vertex the zone where the wedge is narrower than
//       one floor; widening it to two floors for every tet at such a vertex (tets on one
//       side of the wedge included) marked 66% more tets on gmsh-netgen-hinge and 52% more
//       on cgal-anchor (docs/MESHING.md); asking for the tet to reach across the wedge marks 2% more
//       on the hinge. Measured at radius-edge 1.414 (delmesh mesh F --radius-edge 1.414
//       --stats; the mesh is the same, the rule only sorts tets for the report): tets above
//       the bound elsewhere, before -> after, gmsh-netgen-hinge 11 -> 2 (all 11 spanned
//       its 38.3 degree wedge between facets 402 and 465, 0.19-0.37 from the 20-long sharp
//       segment, 1.09-1.48 of rule (c)'s reach, with circumradii 0.095-0.14 against floors
//       0.104-0.113; tets marked 36155 -> 36868), occt-propeller 69 -> 31 (38 across
//       wedges of 31.8-44.5 degrees at the blades' trailing edges; 881664 -> 893388 marked),
//       occt-tr12j 283 -> 283 (660060 -> 660107 marked);
//       cgal-boeing, cgal-dino, cgal-couplingdown, occt-sh2 and gmsh-part mark 8 to 723 more
//       tets with the same tets elsewhere, cgal-anchor, cgal-homer, cgal-knot2, cgal-fandisk
//       and cgal-bear are unchanged. On a small model the share can be large: the 38 degree
//       wedge of test Tet3dSmallAngles.TetsAcrossAWedge (1 wide) marks 4885 of its 13116
//       tets, 3246 without the rule.
// Segments are the facets' polygon edges and the free segments: on a triangulated
// surface every triangle edge, so an input vertex with a triangle angle below 60 degrees
// is an apex.
// Right angles computed in floating point land a hair on either side of 90 degrees, so
// the facet test uses 89 degrees: a box's edges do not count. Angles are measured in
// floating point: this is reporting, no geometric decision of the mesher depends on it.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "refiners/tet3d/refine_state.h"

namespace delmesh::tet3d {

inline constexpr double kSmallSegmentAngleDeg = 60.0;
/// arccos(1 / (2 sqrt 2)) in degrees.
inline constexpr double kSmallSegmentFacetAngleDeg = 69.295188945364572;
inline constexpr double kSmallFacetAngleDeg = 89.0;

/// Lists of ids per key (a facet or a vertex id) in one array: list k is
/// ids[start[k] .. start[k + 1]), empty for keys beyond the last one stored. Built once per
/// object instead of a hash map of vectors (one allocation per key).
struct IdLists {
  std::vector<std::uint32_t> start, ids;
  std::span<const std::uint32_t> of(std::uint32_t k) const {
    if (std::size_t{k} + 1 >= start.size()) return {};
    return {ids.data() + start[k], ids.data() + start[k + 1]};
  }
};

/// Sets VertexInfo::small_angle on the input vertices, SegmentData::small_angle on the
/// segments and SegmentData::sine_at_a / sine_at_b (rules (a), (b) and (d) above). Call once the
/// segments and the facet triangulations of the input are built (plc_preparation.h).
void classify_small_angles(RefineState& state);

/// Does vertex v touch a small input angle (rules (a), (b) and (d))?
bool vertex_at_small_angle(const RefineState& state, std::uint32_t v);

/// The sharp wedges of a state (rules (c) and (f)): for each sharp segment, each pair of its
/// facets that meet below kSmallFacetAngleDeg.
class SharpWedges {
 public:
  explicit SharpWedges(const RefineState& state);
  /// Rule (c): does vertex x lie on a facet of a sharp wedge within its floor over the
  /// sine of the wedge's angle of the wedge's sharp segment?
  bool in_wedge_zone(std::uint32_t x) const;
  /// Rule (f): do two of the vertices lie on the two facets of one sharp wedge, one of
  /// them within twice its floor over the sine of the wedge's angle of its segment?
  bool across_wedge(const std::array<std::uint32_t, 4>& v) const;
  /// Can vertex x be the near vertex of rule (f): does it lie on a facet of a sharp wedge
  /// within twice its floor over the sine of the wedge's angle of its segment?
  bool near_wedge(std::uint32_t x) const;

 private:
  struct Wedge {
    std::uint32_t segment, f1, f2;
    double sine;  ///< of the angle between the facets at the segment
  };
  /// Does vertex x lie on a facet of a sharp wedge within `floors` times its floor over
  /// the sine of the wedge's angle of the wedge's sharp segment?
  bool within_floors(std::uint32_t x, double floors) const;

  const RefineState& state_;
  std::vector<Wedge> wedges_;
  IdLists by_facet_;      ///< facet -> wedges
  IdLists input_facets_;  ///< segment end -> facets
};

/// The narrow corners of a state (rule (e)): each pair of segments meeting at an input
/// vertex below kSmallSegmentAngleDeg.
class NarrowCorners {
 public:
  explicit NarrowCorners(const RefineState& state);
  /// Rule (e): does vertex x lie on a facet beside an arm of a narrow corner, not on
  /// either arm, within its floor of both arms?
  bool in_corner_zone(std::uint32_t x) const;

 private:
  struct Corner {
    std::uint32_t s1, s2;
  };

  const RefineState& state_;
  std::vector<Corner> corners_;
  IdLists by_facet_;      ///< facet -> corners
  IdLists input_facets_;  ///< segment end -> facets
};

/// Per vertex of state.mesh: 1 when the vertex touches a small input angle by rules (a),
/// (b) or (d), 2 when it does not but lies in a sharp wedge's floor zone (rule (c)) or
/// beside a narrow corner (rule (e)), else 0 (the infinite vertex: 0). A tet touches a
/// small input angle when one of its vertices has a nonzero entry.
std::vector<std::uint8_t> small_angle_vertices(const RefineState& state);

/// Per tet slot of state.mesh: 1 when the tet has a vertex that touches a small input
/// angle by rules (a), (b) or (d), 2 when it does not but has a vertex in a sharp wedge's
/// floor zone (rule (c)) or beside a narrow corner (rule (e)) or lies across a sharp wedge
/// (rule (f)), else 0 (dead and infinite slots: 0).
std::vector<std::uint8_t> small_angle_tets(const RefineState& state);

}  // namespace delmesh::tet3d
