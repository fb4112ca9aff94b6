// Internal to the surface importer: an indexed polygon surface with flat storage, and the
// steps of surface_importer.h that work on it (shell nesting, coplanar merge).
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "toolkit/geometry/vec3.h"
#include "toolkit/plc/plc.h"

namespace delmesh::surface {

struct PolygonSurface {
  std::vector<Vec3> points;
  std::vector<std::uint32_t> start{0};
  std::vector<std::uint32_t> verts;
  std::vector<std::uint32_t> source;  ///< input face number of each face
  std::vector<std::uint32_t> shell;   ///< connected component of each face

  std::size_t size() const { return start.size() - 1; }
  std::size_t degree(std::size_t f) const { return start[f + 1] - start[f]; }
  const std::uint32_t* face(std::size_t f) const { return verts.data() + start[f]; }
  std::uint32_t* face(std::size_t f) { return verts.data() + start[f]; }
  void add(const std::uint32_t* v, std::size_t n, std::uint32_t src) {
    verts.insert(verts.end(), v, v + n);
    start.push_back(static_cast<std::uint32_t>(verts.size()));
    source.push_back(src);
  }
};

enum class Containment : std::uint8_t { Outside, Inside, Unknown };

/// Exact ray-parity test of point p against the closed faces of one shell (faces with
/// surface.shell == s). Unknown when every ray tried touches an edge or p is on the
/// shell.
Containment point_in_shell(const PolygonSurface& surface, std::uint32_t s, const Vec3& p);

/// A point strictly inside shell s and outside every shell in `children`, or nullopt.
/// Candidates are pushed inward from face centroids and verified with point_in_shell().
std::optional<Vec3> interior_point(const PolygonSurface& surface, std::uint32_t s,
                                   const std::vector<std::uint32_t>& children);

/// Facets of the merged surface (coplanar merge of edge-adjacent faces, see
/// surface_importer.h step 8). Faces must be consistently oriented and the surface
/// edge-manifold. Each facet gets marker shell+1; facet_face receives, per facet, one of
/// its faces. Returns the number of merged facets.
std::size_t merge_coplanar_faces(const PolygonSurface& surface, bool merge, Plc& plc,
                                 std::vector<std::uint32_t>* facet_face);

}  // namespace delmesh::surface
