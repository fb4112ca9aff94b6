// Tessellation of a model of closed solids (after make_solids) into a PLC: BRepMesh
// discretises every edge once, so faces sharing an edge share its vertices; planar faces
// become polygonal facets with holes, curved faces patches of triangles; face ids become
// facet markers and solids regions. Internal to importers/step/.
#pragma once

#include <string>
#include <vector>

#include "importers/step/cad_model.h"
#include "importers/step/surface_refinement.h"
#include "importers/step/surface_smoothing.h"
#include "toolkit/core/error.h"
#include "toolkit/core/log.h"
#include "toolkit/plc/plc.h"

namespace delmesh::step {

struct TessellationParameters {
  double linear_deflection = 0.0;  ///< absolute chordal deflection (model units)
  double angular_deflection = 0.0; ///< radians
  double min_angle_deg = 20.0;     ///< refinement bound for the triangles of non-planar faces
  double min_edge_length = 0.0;    ///< refinement never splits shorter edges
  /// Coordinate-plane values of one axis within this distance are one plane (model units;
  /// 0: only equal values are).
  double plane_merge_tolerance = 0.0;
};

/// Statistics of one tessellation, for the log and the benchmarks.
struct TessellationReport {
  int faces = 0;
  int planar_polygon_facets = 0;     ///< planar faces written as one polygonal facet
  int planar_faces_triangulated = 0; ///< planar faces whose vertices are not exactly coplanar
  int curved_triangles = 0;
  int dropped_degenerate_triangles = 0;
  int edge_node_mismatches = 0;      ///< edge nodes matched to the nearest shared parameter
  int cancelled_fin_triangles = 0;   ///< coincident opposite triangle pairs removed
  /// Distinct coordinate-plane values moved onto another within plane_merge_tolerance.
  int coordinate_plane_values_merged = 0;
  SurfaceRefinementStats refinement;
  SurfaceSmoothingStats smoothing;
  /// Faces whose refinement was undone because it lowered their smallest angle or
  /// folded them (they keep BRepMesh's triangles, split only along shared CAD edges).
  int faces_excluded_from_refinement = 0;
  /// Inner nodes collapsed into a neighbour after refinement, before the node moves
  /// (surface_coarsening.h; counted before smoothing is undone on faces it made worse).
  std::size_t smoothing_collapses = 0;
  int faces_refined = 0;  ///< faces given to refinement (not written as polygons)
  /// Faces refined with offsets: their nodes lie off their surface by more than half the
  /// chordal deflection (loose CAD tolerances; SurfaceMeshes::Face::offset).
  int faces_with_offsets = 0;
  /// Faces refined on their own tessellation (BRepMesh's triangles as their surface,
  /// tessellation_surface.h) because refinement on their surface folded them.
  int faces_on_tessellation = 0;
  /// Faces refined on their surface plus their edges' offsets blended over a reach
  /// (offset_blend.h) because interpolated offsets folded them.
  int faces_blended = 0;
  /// Smallest angle refinement can change (surface_mesh_quality.h) over the refined
  /// faces, BRepMesh's triangles and the final ones.
  double min_unforced_angle_before_deg = 180.0;
  double min_unforced_angle_after_deg = 180.0;
  /// The same after refinement, without the triangles at a face corner under
  /// kSmallFaceCornerDeg (surface_mesh_quality.h).
  double min_angle_away_from_small_corners_deg = 180.0;
  bool refinement_reverted = false;  ///< no acceptable refinement: BRepMesh's triangles kept
  /// One entry per face given to refinement.
  struct RefinedFace {
    int marker = 0;            ///< CAD face id
    std::string surface;       ///< kind of surface ("cylinder", "B-spline", ...)
    double min_angle_before_deg = 180.0;  ///< smallest angle not between CAD segments
    double min_angle_after_deg = 180.0;
    /// Smallest corner of the face at a vertex of the triangle holding that angle (360:
    /// none on the face's boundary): near corners under 60 degrees the bound cannot be
    /// guaranteed.
    double corner_deg = 360.0;
    /// Smallest angle of the triangles not at a corner under kSmallFaceCornerDeg.
    double min_angle_away_from_small_corners_deg = 180.0;
    bool excluded = false;     ///< kept BRepMesh's triangles
    std::string reason;        ///< why it was excluded
  };
  std::vector<RefinedFace> refined_faces;
};

Expected<Plc> tessellate_to_plc(const CadModel& model, const TessellationParameters& parameters,
                                const std::string& file, TessellationReport& report, LogSink* sink);

}  // namespace delmesh::step
