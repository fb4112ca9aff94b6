// VTK XML unstructured-grid writer (see vtu_writer.h). Layout of the file, following the
// VTK file-format specification: <VTKFile type="UnstructuredGrid"> <UnstructuredGrid>
// <Piece NumberOfPoints NumberOfCells> with <PointData>, <CellData>, <Points>, and <Cells>
// holding connectivity, offsets and types (5 = VTK_TRIANGLE).
#include "toolkit/mesh2d/vtu_writer.h"

#include <string>

#include "toolkit/mesh2d/text_writer.h"
#include "toolkit/mesh2d/triangle_angles.h"
#include "toolkit/mesh2d/triangle_mesh_arrays.h"

namespace delmesh {

Expected<void> write_vtu(const std::filesystem::path& path, const TriangleMesh& mesh) {
  if (auto ok = check_mesh_arrays(mesh); !ok) return ok;
  TextWriter out;
  if (auto opened = out.open(path); !opened) return opened;

  const auto np = static_cast<long long>(mesh.points.size());
  const auto nt = static_cast<long long>(mesh.triangles.size());
  out.text("<?xml version=\"1.0\"?>\n"
           "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" "
           "header_type=\"UInt64\">\n<UnstructuredGrid>\n<Piece NumberOfPoints=\"")
      .integer(np).text("\" NumberOfCells=\"").integer(nt).text("\">\n");

  out.text("<PointData>\n");
  if (!mesh.point_markers.empty()) {
    out.text("<DataArray type=\"Int32\" Name=\"marker\" format=\"ascii\">\n");
    for (const int m : mesh.point_markers) out.integer(m).newline();
    out.text("</DataArray>\n");
  }
  const auto nattr = static_cast<std::size_t>(mesh.num_point_attributes);
  for (std::size_t a = 0; a < nattr; ++a) {
    out.text("<DataArray type=\"Float64\" Name=\"attribute_").integer(static_cast<long long>(a) + 1)
        .text("\" format=\"ascii\">\n");
    for (std::size_t i = 0; i < mesh.points.size(); ++i) out.real(mesh.point_attributes[i * nattr + a]).newline();
    out.text("</DataArray>\n");
  }
  out.text("</PointData>\n<CellData>\n");
  out.text("<DataArray type=\"Float64\" Name=\"min_angle\" format=\"ascii\">\n");
  for (const auto& t : mesh.triangles) {
    out.real(triangle_min_angle_deg(mesh.points[t[0]], mesh.points[t[1]], mesh.points[t[2]])).newline();
  }
  out.text("</DataArray>\n");
  if (!mesh.triangle_attributes.empty()) {
    out.text("<DataArray type=\"Float64\" Name=\"region\" format=\"ascii\">\n");
    for (const double v : mesh.triangle_attributes) out.real(v).newline();
    out.text("</DataArray>\n");
  }
  out.text("</CellData>\n<Points>\n"
           "<DataArray type=\"Float64\" Name=\"Points\" NumberOfComponents=\"3\" format=\"ascii\">\n");
  for (const auto& p : mesh.points) out.real(p[0]).space().real(p[1]).text(" 0\n");
  out.text("</DataArray>\n</Points>\n<Cells>\n"
           "<DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n");
  for (const auto& t : mesh.triangles) {
    out.integer(t[0]).space().integer(t[1]).space().integer(t[2]).newline();
  }
  out.text("</DataArray>\n<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n");
  for (long long i = 1; i <= nt; ++i) out.integer(3 * i).newline();
  out.text("</DataArray>\n<DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n");
  for (long long i = 0; i < nt; ++i) out.text("5\n");
  out.text("</DataArray>\n</Cells>\n</Piece>\n</UnstructuredGrid>\n</VTKFile>\n");
  return out.close();
}

}  // namespace delmesh
