// Consistency checks of TriangleMesh arrays (see triangle_mesh_arrays.h).
#include "toolkit/mesh2d/triangle_mesh_arrays.h"

#include <cmath>
#include <string>

namespace delmesh {

Expected<void> check_mesh_arrays(const TriangleMesh& mesh) {
  const std::size_t n = mesh.points.size();
  auto sizes = [](const char* what, std::size_t have, std::size_t want) {
    return make_error(ErrorCode::InvalidInput, std::string("mesh has ") + std::to_string(have) + " " +
                                                   what + " where " + std::to_string(want) +
                                                   " are expected");
  };
  if (!mesh.point_markers.empty() && mesh.point_markers.size() != n) {
    return sizes("point markers", mesh.point_markers.size(), n);
  }
  if (mesh.num_point_attributes < 0) {
    return make_error(ErrorCode::InvalidInput, "mesh has a negative number of point attributes");
  }
  if (mesh.point_attributes.size() != n * static_cast<std::size_t>(mesh.num_point_attributes)) {
    return sizes("point attribute values", mesh.point_attributes.size(),
                 n * static_cast<std::size_t>(mesh.num_point_attributes));
  }
  if (!mesh.triangle_attributes.empty() && mesh.triangle_attributes.size() != mesh.triangles.size()) {
    return sizes("triangle attributes", mesh.triangle_attributes.size(), mesh.triangles.size());
  }
  if (!mesh.segment_markers.empty() && mesh.segment_markers.size() != mesh.segments.size()) {
    return sizes("segment markers", mesh.segment_markers.size(), mesh.segments.size());
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (!std::isfinite(mesh.points[i][0]) || !std::isfinite(mesh.points[i][1])) {
      Error e = make_error(ErrorCode::InvalidInput, "mesh point " + std::to_string(i) + " is not finite");
      e.entity_ids.push_back(static_cast<std::uint32_t>(i));
      return e;
    }
  }
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    for (const std::uint32_t v : mesh.triangles[t]) {
      if (v >= n) {
        Error e = make_error(ErrorCode::InvalidInput, "mesh triangle " + std::to_string(t) +
                                                          " names point " + std::to_string(v) +
                                                          " of " + std::to_string(n));
        e.entity_ids.push_back(static_cast<std::uint32_t>(t));
        return e;
      }
    }
  }
  for (std::size_t s = 0; s < mesh.segments.size(); ++s) {
    for (const std::uint32_t v : mesh.segments[s]) {
      if (v >= n) {
        Error e = make_error(ErrorCode::InvalidInput, "mesh segment " + std::to_string(s) +
                                                          " names point " + std::to_string(v) +
                                                          " of " + std::to_string(n));
        e.entity_ids.push_back(static_cast<std::uint32_t>(s));
        return e;
      }
    }
  }
  return {};
}

}  // namespace delmesh
