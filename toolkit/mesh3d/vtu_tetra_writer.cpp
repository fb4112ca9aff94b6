// VTK XML unstructured grid (.vtu, ASCII) writer for tet meshes: tets (VTK_TETRA = 10)
// followed by the boundary triangles (VTK_TRIANGLE = 5), with cell data that ParaView can
// threshold on: region (tets; -1 on triangles), boundary_marker (triangles; 0 on tets)
// and, optionally, radius_edge and min_dihedral per tet, and at_small_angle (the
// refiner's per-tet flag of small_angles.h: tets touching a small input angle, where the
// termination floors may leave them outside the bounds; 0 on triangles). When the mesh has colour tables
// (CAD face and solid colours), boundary_color (triangles: the colour of their facet
// marker) and region_color (tets: the colour of their region) as 3-component UInt8 RGB,
// 0 0 0 on the other cells and where no colour is set (show them in ParaView with "Map
// Scalars" off). Names have no place in VTK cell data; .msh and .inp carry them.
#include <algorithm>
#include <limits>
#include <map>
#include <string>

#include "toolkit/io/text_writer.h"
#include "toolkit/mesh3d/tetra_mesh_writer.h"
#include "toolkit/plc/plc_tables.h"
#include "toolkit/quality/tet_quality.h"

namespace delmesh {

namespace {

void put_color(TextWriter& out, const std::map<int, Plc::Color>& colors, int id) {
  const auto it = colors.find(id);
  if (it == colors.end()) {
    out.put("0 0 0\n");
    return;
  }
  const auto rgb = color_bytes(it->second);
  out.line(int{rgb[0]}, int{rgb[1]}, int{rgb[2]});
}

}  // namespace

Expected<void> write_vtu(const std::filesystem::path& path, const TetraMesh& mesh, bool quality_fields,
                         const std::vector<std::uint8_t>* tet_at_small_angle) {
  if (tet_at_small_angle && tet_at_small_angle->size() != mesh.tets.size())
    return make_error(ErrorCode::InvalidOption, path.string() + ": at_small_angle has " +
                                                    std::to_string(tet_at_small_angle->size()) + " entries for " +
                                                    std::to_string(mesh.tets.size()) + " tets");
  TextWriter out(path);
  const std::size_t ntet = mesh.tets.size(), ntri = mesh.boundary_faces.size();
  out.put("<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\">\n");
  out.put("<UnstructuredGrid>\n<Piece NumberOfPoints=\"").put(static_cast<std::uint64_t>(mesh.points.size()))
      .put("\" NumberOfCells=\"").put(static_cast<std::uint64_t>(ntet + ntri)).put("\">\n");
  out.put("<Points>\n<DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n");
  for (const auto& p : mesh.points) out.line(p.x(), p.y(), p.z());
  out.put("</DataArray>\n</Points>\n<Cells>\n<DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n");
  for (const auto& t : mesh.tets) out.line(t[0], t[1], t[2], t[3]);
  for (const auto& f : mesh.boundary_faces) out.line(f[0], f[1], f[2]);
  out.put("</DataArray>\n<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n");
  std::uint64_t offset = 0;
  for (std::size_t i = 0; i < ntet; ++i) out.line(offset += 4);
  for (std::size_t i = 0; i < ntri; ++i) out.line(offset += 3);
  out.put("</DataArray>\n<DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n");
  for (std::size_t i = 0; i < ntet; ++i) out.put("10\n");
  for (std::size_t i = 0; i < ntri; ++i) out.put("5\n");
  out.put("</DataArray>\n</Cells>\n<CellData Scalars=\"region\">\n");
  out.put("<DataArray type=\"Int32\" Name=\"region\" format=\"ascii\">\n");
  for (std::size_t i = 0; i < ntet; ++i) out.line(mesh.region_of(i));
  for (std::size_t i = 0; i < ntri; ++i) out.put("-1\n");
  out.put("</DataArray>\n<DataArray type=\"Int32\" Name=\"boundary_marker\" format=\"ascii\">\n");
  for (std::size_t i = 0; i < ntet; ++i) out.put("0\n");
  for (std::size_t i = 0; i < ntri; ++i) out.line(mesh.boundary_markers.empty() ? 0 : mesh.boundary_markers[i]);
  out.put("</DataArray>\n");
  if (!mesh.marker_colors.empty()) {
    out.put("<DataArray type=\"UInt8\" Name=\"boundary_color\" NumberOfComponents=\"3\" format=\"ascii\">\n");
    for (std::size_t i = 0; i < ntet; ++i) out.put("0 0 0\n");
    for (std::size_t i = 0; i < ntri; ++i)
      put_color(out, mesh.marker_colors, mesh.boundary_markers.empty() ? 0 : mesh.boundary_markers[i]);
    out.put("</DataArray>\n");
  }
  if (!mesh.region_colors.empty()) {
    out.put("<DataArray type=\"UInt8\" Name=\"region_color\" NumberOfComponents=\"3\" format=\"ascii\">\n");
    for (std::size_t i = 0; i < ntet; ++i) put_color(out, mesh.region_colors, mesh.region_of(i));
    for (std::size_t i = 0; i < ntri; ++i) out.put("0 0 0\n");
    out.put("</DataArray>\n");
  }
  if (quality_fields) {
    out.put("<DataArray type=\"Float64\" Name=\"radius_edge\" format=\"ascii\">\n");
    // A tet flat to long double precision has an infinite ratio (tet_quality.h): written
    // as the largest double, which every VTK reader parses.
    for (const auto& t : mesh.tets)
      out.line(std::min(radius_edge_ratio(mesh.points[t[0]], mesh.points[t[1]], mesh.points[t[2]], mesh.points[t[3]]),
                        std::numeric_limits<double>::max()));
    for (std::size_t i = 0; i < ntri; ++i) out.put("0\n");
    out.put("</DataArray>\n<DataArray type=\"Float64\" Name=\"min_dihedral\" format=\"ascii\">\n");
    for (const auto& t : mesh.tets)
      out.line(dihedral_extremes_deg(mesh.points[t[0]], mesh.points[t[1]], mesh.points[t[2]], mesh.points[t[3]]).first);
    for (std::size_t i = 0; i < ntri; ++i) out.put("0\n");
    out.put("</DataArray>\n");
  }
  if (tet_at_small_angle) {
    out.put("<DataArray type=\"UInt8\" Name=\"at_small_angle\" NumberOfComponents=\"1\" format=\"ascii\">\n");
    for (const std::uint8_t flag : *tet_at_small_angle) out.line(int{flag});
    for (std::size_t i = 0; i < ntri; ++i) out.put("0\n");
    out.put("</DataArray>\n");
  }
  out.put("</CellData>\n</Piece>\n</UnstructuredGrid>\n</VTKFile>\n");
  return out.finish();
}

}  // namespace delmesh
