// A tetrahedral mesh as delmesh returns it to users and writes to files: plain arrays,
// 0-based ids, every tetrahedron positively oriented (predicates::orient3d Positive, i.e.
// det[b-a, c-a, d-a] > 0, the convention of VTK, Gmsh, Medit, Abaqus and TetGen's files),
// region ids per tet, and the boundary triangles with the markers of the input facets
// they lie on (CAD face ids). On the outer boundary a face's normal (right-hand rule)
// points out of the domain; faces inside the domain (interfaces between regions,
// internal facets) carry an arbitrary orientation.
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "toolkit/geometry/vec3.h"
#include "toolkit/plc/plc.h"

namespace delmesh {

struct TetraMesh {
  std::vector<Vec3> points;
  std::vector<std::array<std::uint32_t, 4>> tets;
  std::vector<int> tet_regions;                              ///< empty or one per tet
  std::vector<std::array<std::uint32_t, 3>> boundary_faces;  ///< boundary triangles
  std::vector<int> boundary_markers;                         ///< one per boundary face
  std::map<int, std::string> marker_names;                   ///< e.g. CAD face names
  std::map<int, std::string> region_names;                   ///< e.g. CAD solid names
  std::map<int, Plc::Color> marker_colors;                   ///< e.g. CAD face colours
  std::map<int, Plc::Color> region_colors;                   ///< e.g. CAD solid colours

  int region_of(std::size_t tet) const { return tet_regions.empty() ? 0 : tet_regions[tet]; }
};

/// A triangle's vertex ids in increasing order: the key of an unoriented face.
using FaceKey = std::array<std::uint32_t, 3>;
inline FaceKey face_key(std::uint32_t a, std::uint32_t b, std::uint32_t c) {
  if (a > b) std::swap(a, b);
  if (b > c) std::swap(b, c);
  if (a > b) std::swap(a, b);
  return {a, b, c};
}
struct FaceKeyHash {
  std::size_t operator()(const FaceKey& key) const {
    std::uint64_t h = key[0];
    h = h * 0x9E3779B97F4A7C15ull ^ key[1];
    h = h * 0x9E3779B97F4A7C15ull ^ key[2];
    return static_cast<std::size_t>(h ^ (h >> 29));
  }
};

/// For every boundary face, the tet that has it and the local index of the vertex
/// opposite it (-1 / 255 when no tet has the face, which a valid mesh never shows).
struct FaceOwner {
  std::uint32_t tet = ~0u;
  std::uint8_t opposite = 255;
};
std::vector<FaceOwner> boundary_face_owners(const TetraMesh& mesh);

}  // namespace delmesh
