// Abaqus/CalculiX .inp writer: nodes, C3D4 elements in one element set per region
// (*Element, elset=<region name>), and one element-based surface per facet marker
// (*Surface, type=ELEMENT) listing (element, face) pairs. C3D4 face numbering:
// S1 = nodes 1-2-3, S2 = 1-4-2, S3 = 2-4-3, S4 = 3-4-1, so the face opposite local
// vertex 0, 1, 2, 3 is S3, S4, S2, S1. The format has no colour: the marker and region
// tables (names and colours) follow the heading as ** comment lines.
#include <cctype>
#include <map>

#include "toolkit/io/text_writer.h"
#include "toolkit/mesh3d/tetra_mesh_writer.h"

namespace delmesh {

namespace {

/// Abaqus labels: letters, digits and underscores, starting with a letter, <= 80 chars.
std::string abaqus_label(const std::string& name) {
  std::string label;
  for (unsigned char c : name) label.push_back(std::isalnum(c) ? static_cast<char>(c) : '_');
  if (label.empty() || !std::isalpha(static_cast<unsigned char>(label[0]))) label.insert(0, "S_");
  if (label.size() > 80) label.resize(80);
  return label;
}

constexpr const char* kFaceOpposite[4] = {"S3", "S4", "S2", "S1"};

}  // namespace

Expected<void> write_abaqus(const std::filesystem::path& path, const TetraMesh& mesh) {
  TextWriter out(path);
  out.put("*Heading\n delmesh tetrahedral mesh\n").put(label_table_comments(mesh, "**", true, true)).put("*Node\n");
  for (std::size_t i = 0; i < mesh.points.size(); ++i) {
    const auto& p = mesh.points[i];
    out.put(static_cast<std::uint64_t>(i + 1)).put(", ").put(p.x()).put(", ").put(p.y()).put(", ").put(p.z()).put('\n');
  }
  std::map<int, std::vector<std::size_t>> tets_of;
  for (std::size_t i = 0; i < mesh.tets.size(); ++i) tets_of[mesh.region_of(i)].push_back(i);
  for (const auto& [region, list] : tets_of) {
    out.put("*Element, type=C3D4, elset=").put(abaqus_label(region_label(mesh, region))).put('\n');
    for (auto i : list) {
      const auto& t = mesh.tets[i];
      out.put(static_cast<std::uint64_t>(i + 1));
      for (auto v : t) out.put(", ").put(v + 1);
      out.put('\n');
    }
  }
  const auto owners = boundary_face_owners(mesh);
  std::map<int, std::vector<std::size_t>> faces_of;
  for (std::size_t i = 0; i < mesh.boundary_faces.size(); ++i)
    faces_of[mesh.boundary_markers.empty() ? 0 : mesh.boundary_markers[i]].push_back(i);
  for (const auto& [marker, list] : faces_of) {
    out.put("*Surface, type=ELEMENT, name=").put(abaqus_label(marker_label(mesh, marker))).put('\n');
    for (auto i : list) {
      const FaceOwner& owner = owners[i];
      if (owner.tet == ~0u)
        return make_error(ErrorCode::InvalidInput,
                          "boundary face " + std::to_string(i) + " is not a face of any tetrahedron");
      out.put(static_cast<std::uint64_t>(owner.tet + 1)).put(", ").put(kFaceOpposite[owner.opposite]).put('\n');
    }
  }
  return out.finish();
}

}  // namespace delmesh
