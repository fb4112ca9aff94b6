// STEP (and BREP/IGES) import through OpenCASCADE into a PLC (notes §4.1 for what a PLC
// must satisfy). This header is the whole public face of the OCCT-based importer: no
// OpenCASCADE type appears here, and OCCT headers are included only by the .cpp files of
// importers/step/ (they clash with OpenMesh's headers).
#pragma once

#include <filesystem>

#include "toolkit/core/error.h"
#include "toolkit/core/log.h"
#include "toolkit/plc/plc.h"

namespace delmesh {

/// What the bounded-angle refinement of the curved faces' tessellation achieved.
struct StepSurfaceSummary {
  int faces_refined = 0;   ///< faces triangulated and refined (curved, or planar but tilted)
  int faces_excluded = 0;  ///< of those, faces that kept BRepMesh's triangles
  bool reverted = false;   ///< no acceptable refinement: BRepMesh's triangles everywhere
  /// Smallest angle of the refined faces' triangles that refinement can change (corners
  /// between two CAD segments not counted), before (BRepMesh) and after refinement.
  double min_angle_before_deg = 180.0;
  double min_angle_after_deg = 180.0;
  /// min_angle_after_deg without the triangles at a corner of their face under 60
  /// degrees (a small input angle: no triangulation guarantees the bound beside it).
  double min_angle_away_from_small_corners_deg = 180.0;
  /// Faces refined and accepted whose smallest angle stays below the bound away from
  /// small corners (refinement stopped short: segments it may not split, budget).
  int faces_below_bound = 0;
};

struct StepImportOptions {
  /// Chordal (linear) deflection of the tessellation of curved faces, relative to the
  /// model's bounding-box diagonal; <= 0 selects the default.
  double relative_linear_deflection = -1.0;
  /// Angular deflection in degrees; <= 0 selects the default.
  double angular_deflection_deg = -1.0;
  /// Planar faces in coordinate planes (x, y or z constant) whose plane values differ by
  /// at most this fraction of the model's bounding-box diagonal lie in one plane (the
  /// parts of an assembly place one plane a few ulps apart); their vertices are snapped
  /// onto one value so the faces stay polygonal facets. < 0 selects the default (1e-10),
  /// 0 merges only equal values. A merge that changes something is logged as a warning.
  double relative_plane_tolerance = -1.0;
  /// Glue the solids of an assembly so that touching faces become one shared facet.
  bool glue_assembly = true;
  /// Smallest angle, in degrees, the refinement of the curved faces' triangles aims for
  /// (surface_refinement.h); <= 0 selects the default (20). At most 30. Meshing at a
  /// radius-edge bound under about 1.76 asks for more (tet3d::tessellation_min_angle_deg):
  /// the tets at a triangle corner under arcsin(1.2 / (2 B)) are left skinny. When a
  /// higher bound makes refinement exclude more faces than the default does, the default
  /// is used (logged as Info).
  double surface_min_angle_deg = -1.0;
  LogSink* log = nullptr;
  /// Filled with the surface refinement's outcome when not null.
  StepSurfaceSummary* surface_summary = nullptr;
};

/// Reads a CAD file (.step/.stp, .brep, .iges/.igs) into a PLC: every CAD face becomes
/// facets carrying the face id as marker (names in facet_marker_names, colours from the
/// STEP/IGES file in facet_marker_colors: the face's own, else that of the nearest
/// coloured shape above it, where an assembly instance's or SHUO colour replaces its
/// product's), every solid a region (names in region_names, colours in region_colors).
Expected<Plc> import_step(const std::filesystem::path& path, const StepImportOptions& options);

}  // namespace delmesh
