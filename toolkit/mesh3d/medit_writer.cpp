// Medit .mesh writer (MeshVersionFormatted 2, 1-based): vertices with reference 0,
// boundary triangles referenced by facet marker, tetrahedra referenced by region. The
// format has no field for names or colours: the marker and region tables go into #
// comment lines before End.
#include "toolkit/io/text_writer.h"
#include "toolkit/mesh3d/tetra_mesh_writer.h"

namespace delmesh {

Expected<void> write_medit(const std::filesystem::path& path, const TetraMesh& mesh) {
  TextWriter out(path);
  out.put("MeshVersionFormatted 2\n\nDimension 3\n\nVertices\n").line(static_cast<std::uint64_t>(mesh.points.size()));
  for (const auto& p : mesh.points) out.line(p.x(), p.y(), p.z(), 0);
  out.put("\nTriangles\n").line(static_cast<std::uint64_t>(mesh.boundary_faces.size()));
  for (std::size_t i = 0; i < mesh.boundary_faces.size(); ++i) {
    const auto& f = mesh.boundary_faces[i];
    out.line(f[0] + 1, f[1] + 1, f[2] + 1, mesh.boundary_markers.empty() ? 0 : mesh.boundary_markers[i]);
  }
  out.put("\nTetrahedra\n").line(static_cast<std::uint64_t>(mesh.tets.size()));
  for (std::size_t i = 0; i < mesh.tets.size(); ++i) {
    const auto& t = mesh.tets[i];
    out.line(t[0] + 1, t[1] + 1, t[2] + 1, t[3] + 1, mesh.region_of(i));
  }
  const std::string tables = label_table_comments(mesh, "#", true, true);
  if (!tables.empty()) out.put("\n").put(tables);
  out.put("\nEnd\n");
  return out.finish();
}

}  // namespace delmesh
