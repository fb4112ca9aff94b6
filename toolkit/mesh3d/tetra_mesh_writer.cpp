// Format dispatch and naming for tet mesh writers (see tetra_mesh_writer.h).
#include "toolkit/mesh3d/tetra_mesh_writer.h"

#include "toolkit/plc/plc_tables.h"

#include <algorithm>
#include <cctype>

namespace delmesh {

std::string marker_label(const TetraMesh& mesh, int marker) {
  const auto it = mesh.marker_names.find(marker);
  if (it != mesh.marker_names.end() && !it->second.empty()) return it->second;
  return "facet_" + std::to_string(marker);
}

std::string region_label(const TetraMesh& mesh, int region) {
  const auto it = mesh.region_names.find(region);
  if (it != mesh.region_names.end() && !it->second.empty()) return it->second;
  return "region_" + std::to_string(region);
}

std::string label_table_comments(const TetraMesh& mesh, std::string_view prefix, bool markers, bool regions) {
  std::string text;
  const auto append = [&](std::string_view what, const auto& names, const auto& colors) {
    for (const std::string& line : label_table_lines(what, names, colors)) {
      text += prefix;
      text += ' ';
      text += line;
      text += '\n';
    }
  };
  if (markers) append("facet_marker", mesh.marker_names, mesh.marker_colors);
  if (regions) append("region", mesh.region_names, mesh.region_colors);
  return text;
}

Expected<std::vector<std::filesystem::path>> write_tetra_mesh(const std::filesystem::path& path,
                                                              const TetraMesh& mesh,
                                                              const TetraWriteOptions& options) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  auto single = [&](Expected<void> result) -> Expected<std::vector<std::filesystem::path>> {
    if (!result) return result.error();
    return std::vector<std::filesystem::path>{path};
  };
  if (ext == ".vtu") return single(write_vtu(path, mesh, options.quality_fields, options.tet_at_small_angle));
  if (ext == ".msh") return single(write_gmsh(path, mesh, options.gmsh_version));
  if (ext == ".mesh") return single(write_medit(path, mesh));
  if (ext == ".inp") return single(write_abaqus(path, mesh));
  if (ext == ".ovm") return single(write_ovm(path, mesh));
  if (ext == ".node" || ext == ".ele" || ext == ".face") {
    std::filesystem::path base = path;
    base.replace_extension();
    return write_tetgen(base, mesh, options.zero_based);
  }
  return make_error(ErrorCode::InvalidOption,
                    "unknown output format '" + ext + "' for " + path.string() +
                        " (use .vtu, .msh, .mesh, .node, .inp or .ovm)");
}

}  // namespace delmesh
