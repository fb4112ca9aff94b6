// OpenVolumeMesh ASCII (.ovm) writer (layout: ../shared/reference/ovm-ascii-format.md).
//
// Undirected edges and triangular faces are deduplicated. A tet (v0,v1,v2,v3) with
// delmesh's positive orientation uses the half-face cycles of OVM's add_cell:
// (v0,v1,v2) (v0,v2,v3) (v0,v3,v1) (v1,v3,v2), whose normals point into the cell, OVM's
// convention. A face is stored with the cycle of the first cell that creates it, which
// therefore uses half-face 2f; the neighbour across it uses 2f+1. Half-edge 2e runs
// along edge e as listed, 2e+1 against it. Properties: CProp int "region" per cell and
// FProp int "boundary_marker" per face (0 on faces that are not boundary faces); with
// colour tables, FProp vec4f "face_color" (RGBA in [0, 1]: the colour of a boundary face's
// marker, 0 0 0 0 on other faces and where no colour is set) and CProp vec4f
// "cell_color" (the region colour), the property names and type OpenVolumeMesh's
// ColorAttrib (OpenFlipper) reads. Names are not written: OVM's string properties have
// no documented ASCII encoding.
#include <algorithm>
#include <unordered_map>

#include "toolkit/io/text_writer.h"
#include "toolkit/mesh3d/tetra_mesh_writer.h"
#include "toolkit/plc/plc_tables.h"

namespace delmesh {

namespace {

std::uint64_t edge_key(std::uint32_t a, std::uint32_t b) {
  if (a > b) std::swap(a, b);
  return (static_cast<std::uint64_t>(a) << 32) | b;
}

/// "r g b 1" with components in [0, 1] (as bytes / 255, so every writer agrees), or
/// "0 0 0 0" for no colour.
void put_rgba(TextWriter& out, const Plc::Color* color) {
  if (color == nullptr) {
    out.put("0 0 0 0\n");
    return;
  }
  const auto rgb = color_bytes(*color);
  out.line(rgb[0] / 255.0, rgb[1] / 255.0, rgb[2] / 255.0, 1);
}

}  // namespace

Expected<void> write_ovm(const std::filesystem::path& path, const TetraMesh& mesh) {
  std::vector<std::array<std::uint32_t, 2>> edges;
  std::unordered_map<std::uint64_t, std::uint32_t> edge_index;
  std::vector<std::array<std::uint32_t, 3>> faces;  // half-edge ids of the stored cycle
  std::unordered_map<FaceKey, std::uint32_t, FaceKeyHash> face_index;
  std::vector<std::array<std::uint32_t, 4>> cells;  // half-face ids
  edge_index.reserve(mesh.tets.size() * 2);
  face_index.reserve(mesh.tets.size() * 3);
  cells.reserve(mesh.tets.size());

  auto halfedge = [&](std::uint32_t from, std::uint32_t to) {
    const auto [it, inserted] = edge_index.try_emplace(edge_key(from, to), static_cast<std::uint32_t>(edges.size()));
    if (inserted) edges.push_back({from, to});
    const std::uint32_t e = it->second;
    return 2 * e + (edges[e][0] == from ? 0u : 1u);
  };
  auto halfface = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    const auto [it, inserted] = face_index.try_emplace(face_key(a, b, c), static_cast<std::uint32_t>(faces.size()));
    if (inserted) {
      faces.push_back({halfedge(a, b), halfedge(b, c), halfedge(c, a)});
      return 2 * it->second;
    }
    return 2 * it->second + 1;
  };
  for (const auto& t : mesh.tets) {
    cells.push_back({halfface(t[0], t[1], t[2]), halfface(t[0], t[2], t[3]), halfface(t[0], t[3], t[1]),
                     halfface(t[1], t[3], t[2])});
  }
  std::vector<int> face_marker(faces.size(), 0);
  for (std::size_t i = 0; i < mesh.boundary_faces.size(); ++i) {
    const auto it = face_index.find(face_key(mesh.boundary_faces[i][0], mesh.boundary_faces[i][1], mesh.boundary_faces[i][2]));
    if (it == face_index.end())
      return make_error(ErrorCode::InvalidInput,
                        "boundary face " + std::to_string(i) + " is not a face of any tetrahedron");
    face_marker[it->second] = mesh.boundary_markers.empty() ? 0 : mesh.boundary_markers[i];
  }

  TextWriter out(path);
  out.put("OVM ASCII\nVertices\n").line(static_cast<std::uint64_t>(mesh.points.size()));
  for (const auto& p : mesh.points) out.line(p.x(), p.y(), p.z());
  out.put("Edges\n").line(static_cast<std::uint64_t>(edges.size()));
  for (const auto& e : edges) out.line(e[0], e[1]);
  out.put("Faces\n").line(static_cast<std::uint64_t>(faces.size()));
  for (const auto& f : faces) out.line(3, f[0], f[1], f[2]);
  out.put("Polyhedra\n").line(static_cast<std::uint64_t>(cells.size()));
  for (const auto& c : cells) out.line(4, c[0], c[1], c[2], c[3]);
  out.put("CProp int \"region\"\n");
  for (std::size_t i = 0; i < cells.size(); ++i) out.line(mesh.region_of(i));
  out.put("FProp int \"boundary_marker\"\n");
  for (int m : face_marker) out.line(m);
  if (!mesh.marker_colors.empty()) {
    std::vector<const Plc::Color*> face_color(faces.size(), nullptr);
    for (std::size_t i = 0; i < mesh.boundary_faces.size(); ++i) {
      const auto color = mesh.marker_colors.find(mesh.boundary_markers.empty() ? 0 : mesh.boundary_markers[i]);
      if (color == mesh.marker_colors.end()) continue;
      const auto& f = mesh.boundary_faces[i];
      face_color[face_index.at(face_key(f[0], f[1], f[2]))] = &color->second;
    }
    out.put("FProp vec4f \"face_color\"\n");
    for (const Plc::Color* c : face_color) put_rgba(out, c);
  }
  if (!mesh.region_colors.empty()) {
    out.put("CProp vec4f \"cell_color\"\n");
    for (std::size_t i = 0; i < cells.size(); ++i) {
      const auto color = mesh.region_colors.find(mesh.region_of(i));
      put_rgba(out, color == mesh.region_colors.end() ? nullptr : &color->second);
    }
  }
  return out.finish();
}

}  // namespace delmesh
