// Writers of tetrahedral meshes for FEM tools (notes: none; file formats only).
//
//   .vtu   VTK XML unstructured grid: tets and boundary triangles, cell data region,
//          boundary_marker, radius_edge, min_dihedral, at_small_angle (ParaView)
//   .msh   Gmsh 4.1 ASCII (or 2.2), physical groups named after CAD faces and solids
//   .mesh  Medit (MeshVersionFormatted 2): tets with region refs, triangles with markers
//   .node  TetGen .node/.ele/.face (1-based unless zero_based), regions as .ele
//          attribute, facet markers in .face
//   .inp   Abaqus: C3D4 elements in one element set per region, one element-based
//          surface per facet marker
//   .ovm   OpenVolumeMesh ASCII with a cell property "region" and a face property
//          "boundary_marker"
// Every format writes tets with delmesh's positive orientation, which is the positive
// Jacobian convention of all of them.
//
// Names and colours of facet markers and regions (CAD faces and solids):
//   .vtu   colours as cell data boundary_color / region_color (UInt8 RGB); no names
//   .ovm   colours as properties face_color / cell_color (vec4f RGBA); no names
//   .msh   names as physical group names; the format has no colour
//   .inp   names as element set and surface names; colours in ** comment lines
//   .node  markers and region ids only: names and colours in # comment lines of .face
//          (markers) and .ele (regions)
//   .mesh  references only: names and colours in # comment lines
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "toolkit/core/error.h"
#include "toolkit/mesh3d/tetra_mesh.h"

namespace delmesh {

struct TetraWriteOptions {
  bool zero_based = false;  ///< TetGen files: number from 0 (TetGen -z) instead of 1
  int gmsh_version = 41;    ///< 41 (Gmsh 4.1) or 22 (Gmsh 2.2) for .msh
  bool quality_fields = true;  ///< .vtu: radius_edge and min_dihedral cell data
  /// .vtu: cell data at_small_angle from this per-tet array (MeshResult::
  /// tet_at_small_angle: 1 or 2 where the tet touches a small input angle, else 0), so the
  /// tets refinement may leave outside the bounds can be shown apart; null: not written.
  const std::vector<std::uint8_t>* tet_at_small_angle = nullptr;
};

/// Writes by extension (.vtu .msh .mesh .node .ele .inp .ovm); returns the files written
/// (X.node also writes X.ele and X.face). Unknown extension: InvalidOption error.
Expected<std::vector<std::filesystem::path>> write_tetra_mesh(const std::filesystem::path& path,
                                                              const TetraMesh& mesh,
                                                              const TetraWriteOptions& options = {});

Expected<void> write_vtu(const std::filesystem::path& path, const TetraMesh& mesh, bool quality_fields = true,
                         const std::vector<std::uint8_t>* tet_at_small_angle = nullptr);
Expected<void> write_gmsh(const std::filesystem::path& path, const TetraMesh& mesh, int version = 41);
Expected<void> write_medit(const std::filesystem::path& path, const TetraMesh& mesh);
/// Writes base.node, base.ele and base.face (base is the path without extension).
Expected<std::vector<std::filesystem::path>> write_tetgen(const std::filesystem::path& base,
                                                          const TetraMesh& mesh, bool zero_based = false);
Expected<void> write_abaqus(const std::filesystem::path& path, const TetraMesh& mesh);
Expected<void> write_ovm(const std::filesystem::path& path, const TetraMesh& mesh);

/// Name of a facet marker / region for physical groups and sets: the mesh's name if it
/// has one, else "facet_<marker>" / "region_<id>".
std::string marker_label(const TetraMesh& mesh, int marker);
std::string region_label(const TetraMesh& mesh, int region);

/// The mesh's marker table (with `markers`) and region table (with `regions`) as comment
/// lines "<prefix> facet_marker <m> name "<name>" color #rrggbb" / "<prefix> region <r>
/// ...", one per named or coloured id; empty when there is nothing to list.
std::string label_table_comments(const TetraMesh& mesh, std::string_view prefix, bool markers, bool regions);

}  // namespace delmesh
