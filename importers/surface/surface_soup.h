// Polygon soups read from surface mesh files (STL ASCII/binary, OFF, OBJ, PLY), exactly as
// stored: coordinates in double precision (binary float32 values converted exactly, text
// parsed with correctly rounded std::from_chars), one point per vertex record (no
// welding), every face kept (no face dropped for being degenerate). The surface importer
// (surface_importer.h) then welds, repairs, orients and validates explicitly.
//
// delmesh parses these formats itself rather than through OpenMesh's readers: OpenMesh
// 9.0 (Debian 12) hands coordinates to its importer as float (Vec3f) whatever the mesh
// traits (a vertex written 0.1234567890123456 arrives as 0.12345679104328156), welds STL
// vertices inside the reader, silently skips collapsed STL triangles, refuses non-manifold
// faces with a message on stderr, and does not bound its loop on a truncated binary STL.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "toolkit/core/error.h"
#include "toolkit/geometry/vec3.h"

namespace delmesh {

struct SurfaceSoup {
  std::vector<Vec3> points;
  std::vector<std::uint32_t> face_start{0};  ///< face f is face_vertices[face_start[f] .. face_start[f+1])
  std::vector<std::uint32_t> face_vertices;
  std::vector<std::uint32_t> face_line;  ///< source line of each face (text formats), else 0
  std::size_t ignored_elements = 0;      ///< lines/elements skipped (OBJ 'l', PLY edges, ...)

  std::size_t face_count() const { return face_start.size() - 1; }
  void add_face(const std::uint32_t* v, std::size_t n, std::size_t line) {
    face_vertices.insert(face_vertices.end(), v, v + n);
    face_start.push_back(static_cast<std::uint32_t>(face_vertices.size()));
    face_line.push_back(static_cast<std::uint32_t>(line));
  }
};

/// ASCII or binary STL: binary when the file size is exactly 84 + 50 * (triangle count
/// in the header), ASCII when it starts with "solid", an error otherwise.
Expected<SurfaceSoup> parse_stl(std::string_view bytes, std::string_view file_name);
/// ASCII OFF (also COFF/NOFF/CNOFF headers; per-vertex and per-face extras ignored).
Expected<SurfaceSoup> parse_off(std::string_view text, std::string_view file_name);
/// Wavefront OBJ: 'v' and 'f' records (v, v/vt, v//vn, v/vt/vn; negative indices).
Expected<SurfaceSoup> parse_obj(std::string_view text, std::string_view file_name);
/// PLY ascii, binary_little_endian or binary_big_endian: vertex x, y, z and the face
/// list vertex_indices (or vertex_index); other elements and properties skipped.
Expected<SurfaceSoup> parse_ply(std::string_view bytes, std::string_view file_name);

}  // namespace delmesh
