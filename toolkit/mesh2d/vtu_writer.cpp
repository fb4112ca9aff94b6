// VTK XML unstructured-grid writer (see vtu_writer.h). Layout of the file, following the
// VTK file-format specification: <VTKFile type="UnstructuredGrid"> <UnstructuredGrid>
// <Piece NumberOfPoints NumberOfCells> with <PointData>, <CellData>, <Points>, and <Cells>
// holding connectivity, offsets and types (5 = VTK_TRIANGLE).
#include "toolkit/mesh2d/vtu_writer.h"

#include <string>

#include "toolkit/io/text_writer.h"
#include "toolkit/mesh2d/triangle_angles.h"
#include "toolkit/mesh2d/triangle_mesh_arrays.h"

namespace delmesh {

Expected<void> write_vtu(const std::filesystem::path& path, const TriangleMesh& mesh) {
  if (auto ok = check_mesh_arrays(mesh); !ok) return ok;
  TextWriter out(path);

  const auto np = static_cast<std::int64_t>(mesh.points.size());
  const auto nt = static_cast<std::int64_t>(mesh.triangles.size());
  out.put("<?xml version=\"1.0\"?>\n"
           "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" "
           "header_type=\"UInt64\">\n<UnstructuredGrid>\n<Piece NumberOfPoints=\"")
      .put(static_cast<std::int64_t>(np)).put("\" NumberOfCells=\"").put(static_cast<std::int64_t>(nt)).put("\">\n");

  out.put("<PointData>\n");
  if (!mesh.point_markers.empty()) {
    out.put("<DataArray type=\"Int32\" Name=\"marker\" format=\"ascii\">\n");
    for (const int m : mesh.point_markers) out.put(static_cast<std::int64_t>(m)).put('\n');
    out.put("</DataArray>\n");
  }
  const auto nattr = static_cast<std::size_t>(mesh.num_point_attributes);
  for (std::size_t a = 0; a < nattr; ++a) {
    out.put("<DataArray type=\"Float64\" Name=\"attribute_").put(static_cast<std::int64_t>(static_cast<std::int64_t>(a) + 1))
        .put("\" format=\"ascii\">\n");
    for (std::size_t i = 0; i < mesh.points.size(); ++i) out.put(mesh.point_attributes[i * nattr + a]).put('\n');
    out.put("</DataArray>\n");
  }
  out.put("</PointData>\n<CellData>\n");
  out.put("<DataArray type=\"Float64\" Name=\"min_angle\" format=\"ascii\">\n");
  for (const auto& t : mesh.triangles) {
    out.put(triangle_min_angle_deg(mesh.points[t[0]], mesh.points[t[1]], mesh.points[t[2]])).put('\n');
  }
  out.put("</DataArray>\n");
  if (!mesh.triangle_attributes.empty()) {
    out.put("<DataArray type=\"Float64\" Name=\"region\" format=\"ascii\">\n");
    for (const double v : mesh.triangle_attributes) out.put(v).put('\n');
    out.put("</DataArray>\n");
  }
  out.put("</CellData>\n<Points>\n"
           "<DataArray type=\"Float64\" Name=\"Points\" NumberOfComponents=\"3\" format=\"ascii\">\n");
  for (const auto& p : mesh.points) out.put(p[0]).put(' ').put(p[1]).put(" 0\n");
  out.put("</DataArray>\n</Points>\n<Cells>\n"
           "<DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n");
  for (const auto& t : mesh.triangles) {
    out.put(static_cast<std::int64_t>(t[0])).put(' ').put(static_cast<std::int64_t>(t[1])).put(' ').put(static_cast<std::int64_t>(t[2])).put('\n');
  }
  out.put("</DataArray>\n<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n");
  for (std::int64_t i = 1; i <= nt; ++i) out.put(static_cast<std::int64_t>(3 * i)).put('\n');
  out.put("</DataArray>\n<DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n");
  for (std::int64_t i = 0; i < nt; ++i) out.put("5\n");
  out.put("</DataArray>\n</Cells>\n</Piece>\n</UnstructuredGrid>\n</VTKFile>\n");
  return out.finish();
}

}  // namespace delmesh
