// Edge extraction from a triangle list (see triangle_mesh_edges.h): all half-edges keyed
// by their sorted endpoints, sorted, then runs of equal keys merged. O(n log n), no hash maps.
#include "toolkit/mesh2d/triangle_mesh_edges.h"

#include <algorithm>
#include <utility>

namespace delmesh {
namespace {

std::uint64_t edge_key(std::uint32_t u, std::uint32_t v) {
  if (u > v) std::swap(u, v);
  return (static_cast<std::uint64_t>(u) << 32) | v;
}

}  // namespace

std::vector<MeshEdge> mesh_edges(const TriangleMesh& mesh) {
  std::vector<std::uint64_t> keys;
  keys.reserve(3 * mesh.triangles.size());
  for (const auto& t : mesh.triangles) {
    keys.push_back(edge_key(t[0], t[1]));
    keys.push_back(edge_key(t[1], t[2]));
    keys.push_back(edge_key(t[2], t[0]));
  }
  std::sort(keys.begin(), keys.end());

  std::vector<std::pair<std::uint64_t, int>> segments;
  segments.reserve(mesh.segments.size());
  for (std::size_t s = 0; s < mesh.segments.size(); ++s) {
    const int marker = mesh.segment_markers.empty() ? 0 : mesh.segment_markers[s];
    segments.emplace_back(edge_key(mesh.segments[s][0], mesh.segments[s][1]), marker);
  }
  std::sort(segments.begin(), segments.end());

  std::vector<MeshEdge> edges;
  edges.reserve(keys.size() / 2 + mesh.segments.size());
  std::size_t s = 0;
  for (std::size_t i = 0; i < keys.size();) {
    std::size_t j = i;
    while (j < keys.size() && keys[j] == keys[i]) ++j;
    MeshEdge e;
    e.a = static_cast<std::uint32_t>(keys[i] >> 32);
    e.b = static_cast<std::uint32_t>(keys[i] & 0xffffffffu);
    e.is_boundary = (j - i) == 1;
    while (s < segments.size() && segments[s].first < keys[i]) ++s;
    e.marker = e.is_boundary ? 1 : 0;
    if (s < segments.size() && segments[s].first == keys[i]) {
      e.is_segment = true;
      if (!mesh.segment_markers.empty()) e.marker = segments[s].second;
    }
    edges.push_back(e);
    i = j;
  }
  return edges;
}

}  // namespace delmesh
