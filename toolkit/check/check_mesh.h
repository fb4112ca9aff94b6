// Validation of a tetrahedral mesh against the PLC it was generated from (issue 5 item 8;
// notes §2.1.4 for constrained Delaunay, §4.1 for PLCs). Independent of the refinement
// code: it sees only the output arrays (TetraMesh), the input (Plc) and the facet index of
// each boundary face, so tests and `delmesh mesh --check` can trust it to judge any mesher.
//
// What is verified, in this order (orientation and topology first, geometry after):
//   - indices: vertex ids in range and distinct per tet, array sizes consistent;
//   - every tet positively oriented (predicates::orient3d Positive; Zero is a flat tet);
//   - the tets form a complex: a face is shared by at most two tets, with opposite
//     orientations; the faces of exactly one tet (the domain boundary) are exactly listed
//     as boundary faces, with the outward orientation; every listed face is a tet face;
//   - every boundary face lies in its PLC facet: its vertices on the facet's plane, its
//     centroid inside the facet polygon minus holes in the facet's projection onto a
//     coordinate plane (exact orient2d); its marker is the facet's marker;
//   - the boundary faces of each facet cover it: their area sum equals the facet area to
//     `relative_tolerance` plus the facet's perimeter times the roundoff distance below
//     (split points on its segments move the covered area by that much); a facet with none
//     is accepted when a point strictly inside it lies in no tet: the domain is on neither
//     side, e.g. between a hole and the exterior;
//   - every PLC segment (facet polygon edges and extra segments) is a chain of mesh edges;
//   - constrained Delaunay: across every interior face not on a facet, the apex of one tet
//     is not strictly inside the other's circumsphere (predicates::insphere);
//   - the total tet volume equals the volume the PLC's facets enclose (computed from the
//     facet polygons, oriented by the mesh's outward boundary faces) to
//     `relative_tolerance`.
//
// Steiner points that a mesher places on tilted facets and segments are rounded to
// doubles and are generally off the exact plane or line by a few ulps. The plane and line
// tests are therefore exact first (orient3d Zero, collinearity), then accept a point whose
// floating-point distance is at most `roundoff_tolerance` times the PLC's bounding-box
// diagonal; roundoff_tolerance = 0 makes them purely exact. This is a checker's tolerance,
// never a decision of the meshing core.
//
// The mesh's first plc.points.size() points are the PLC's vertices, with the same ids
// (as mesh_plc returns them); PLC segments are looked up by these ids.
//
// Tets of region -1 lie outside the domain (the kept convex hull of MeshOptions::
// keep_convex_hull): their free faces need not be listed and their volume is not counted.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "toolkit/mesh3d/tetra_mesh.h"
#include "toolkit/plc/plc.h"

namespace delmesh {

enum class MeshCheckKind : std::uint8_t {
  BadIndex,              ///< ids: tet or face; an id out of range, a repeated vertex, array sizes
  InvertedTet,           ///< ids: tet
  FlatTet,               ///< ids: tet
  NonManifoldFace,       ///< ids: the face's 3 vertices; shared by more than two tets
  FaceOrientation,       ///< ids: two tets sharing a face in one orientation, or an inward boundary face
  UnlistedBoundaryFace,  ///< ids: tet, then the face's 3 vertices; a free face missing from boundary_faces
  MissingBoundaryFace,   ///< ids: boundary face index; listed but not a face of any tet
  DuplicateBoundaryFace, ///< ids: the two boundary face indices
  WrongMarker,           ///< ids: boundary face index, facet index
  FaceOffFacet,          ///< ids: boundary face index, facet index
  FacetNotCovered,       ///< ids: facet index
  MissingSegment,        ///< ids: segment's two PLC vertices
  NotDelaunay,           ///< ids: the two tets sharing the face
  VolumeMismatch,        ///< ids: none
};

/// "InvertedTet", ...
const char* to_string(MeshCheckKind kind);

struct MeshCheckIssue {
  MeshCheckKind kind = MeshCheckKind::BadIndex;
  std::vector<std::uint32_t> ids;  ///< the entities concerned, as documented per kind
  std::string message;
};

struct CheckMeshOptions {
  bool check_delaunay = true;        ///< constrained Delaunay property of interior faces
  bool check_volume = true;          ///< total volume against the PLC's enclosed volume
  double relative_tolerance = 1e-9;  ///< for the facet area and total volume comparisons
  double roundoff_tolerance = 1e-12; ///< off-plane / off-line distance over the bbox diagonal
  std::size_t max_issues = 100;      ///< stop collecting after this many
};

/// Checks `mesh` against `plc`. `boundary_face_facets[i]` is the PLC facet of boundary face
/// i (MeshResult::boundary_face_facets); when it is empty the facet-related checks (plane,
/// marker, coverage, volume) are skipped. Returns the issues found (empty: valid).
std::vector<MeshCheckIssue> check_mesh(const TetraMesh& mesh, const Plc& plc,
                                       std::span<const std::uint32_t> boundary_face_facets,
                                       const CheckMeshOptions& options = {});

}  // namespace delmesh
