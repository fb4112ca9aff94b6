// delmesh's public library interface for FEM preprocessors: one header to include, one
// CMake target to link (find_package(delmesh) then delmesh::delmesh_api).
//
//   delmesh::Plc part = ...;                       // or a file: delmesh::mesh("part.step", options)
//   delmesh::MeshOptions options;
//   options.max_radius_edge = 1.414;               // quality bound (notes §4.2)
//   options.max_volume = 0.01;
//   auto result = delmesh::mesh(part, options);
//   if (!result) { report result.error().describe(); }
//   result->mesh.tets, .tet_regions, .boundary_faces, .boundary_markers, result->status
//   delmesh::write_tetra_mesh("part.msh", result->mesh);
//
// It re-exports the option, result and mesh types (MeshOptions, MeshResult, MeshStats,
// MeshStatus, TetraMesh, Plc), the writers (write_tetra_mesh), the quality report
// (tet_quality_report), the importers (import_file, ImportOptions) and the validator
// (check_mesh). Errors come back as values
// (delmesh::Error with file, line and entity ids); the library never prints and never
// exits; progress and warnings go to MeshOptions::log.
#pragma once

#include <filesystem>
#include <vector>

#include "importers/import.h"
#include "refiners/tet3d/mesh_plc.h"
#include "toolkit/check/check_mesh.h"
#include "toolkit/core/error.h"
#include "toolkit/core/log.h"
#include "toolkit/core/mesh_status.h"
#include "toolkit/mesh3d/tetra_mesh.h"
#include "toolkit/mesh3d/tetra_mesh_writer.h"
#include "toolkit/plc/plc.h"
#include "toolkit/quality/tet_quality.h"

namespace delmesh {

/// Quality tetrahedral mesh of a PLC (3D Delaunay refinement, notes ch. 4): tets with
/// region ids, boundary triangles with the facet markers, status Complete or Partial.
Expected<MeshResult> mesh(const Plc& plc, const MeshOptions& options = {});

/// Imports `file` (STEP/BREP/IGES, STL/OFF/OBJ/PLY, TetGen .poly/.smesh, by extension;
/// importers/import.h) and meshes it. CAD face and solid names and colours become the
/// mesh's marker and region tables (TetraMesh::marker_names, region_names, marker_colors,
/// region_colors). Import errors name the file and line. With quality refinement on and
/// no StepImportOptions::surface_min_angle_deg given, CAD tessellations are refined to
/// tet3d::tessellation_min_angle_deg of the radius-edge bound (26 degrees at 1.414).
Expected<MeshResult> mesh(const std::filesystem::path& file, const MeshOptions& options = {},
                          const ImportOptions& import_options = {});

/// check_mesh on a result of mesh(): the issues found (empty: the mesh is valid). The
/// Delaunay test only where the result is still Delaunay (MeshResult::
/// constrained_delaunay: not after the improvement pass changed it).
std::vector<MeshCheckIssue> check_mesh(const MeshResult& result, const Plc& plc,
                                       const CheckMeshOptions& options = {});

}  // namespace delmesh
