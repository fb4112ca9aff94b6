// Shared oracle of the surface-format fuzz targets (stl/off/obj/ply_fuzz.cpp): a parse either
// fails with an Error located in the file, or yields a SurfaceSoup whose arrays agree with
// each other (face_start monotone from 0, every face vertex index naming an existing point,
// one source line per face).
#pragma once

#include <cstddef>

#include "importers/surface/surface_soup.h"

namespace delmesh::fuzz {

inline void check_surface_soup(const Expected<SurfaceSoup>& result) {
  if (!result) {
    if (!result.error().location) __builtin_trap();
    return;
  }
  const SurfaceSoup& s = *result;
  if (s.face_start.empty() || s.face_start.front() != 0) __builtin_trap();
  if (s.face_start.back() != s.face_vertices.size()) __builtin_trap();
  if (s.face_line.size() != s.face_count()) __builtin_trap();
  for (std::size_t f = 0; f + 1 < s.face_start.size(); ++f) {
    if (s.face_start[f] > s.face_start[f + 1]) __builtin_trap();
  }
  for (const auto v : s.face_vertices) {
    if (v >= s.points.size()) __builtin_trap();
  }
}

}  // namespace delmesh::fuzz
