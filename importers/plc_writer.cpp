// PLC file output by extension (see plc_writer.h).
#include "importers/plc_writer.h"

#include <cstdio>

#include "importers/tetgen/tetgen_writer.h"
#include "toolkit/core/str_cat.h"
#include "toolkit/plc/plc_tables.h"

namespace delmesh {

std::string format_plc_vtu(const Plc& plc) {
  std::vector<std::vector<std::uint32_t>> cells;
  std::vector<int> cell_facet, cell_marker;
  const bool colored = !plc.facet_marker_colors.empty();
  for (std::size_t f = 0; f < plc.facets.size(); ++f) {
    for (const auto& polygon : plc.facets[f].polygons) {
      if (polygon.size() < 2) continue;
      cells.push_back(polygon);
      cell_facet.push_back(static_cast<int>(f));
      cell_marker.push_back(plc.facets[f].marker);
    }
  }
  for (const auto& s : plc.segments) {
    cells.push_back({s.a, s.b});
    cell_facet.push_back(-1);
    cell_marker.push_back(s.marker);
  }
  std::string out;
  out += "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\">\n";
  out += cat("<UnstructuredGrid>\n<Piece NumberOfPoints=\"", plc.points.size(), "\" NumberOfCells=\"", cells.size(), "\">\n");
  out += "<Points>\n<DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n";
  char buffer[96];
  for (const Vec3& p : plc.points) {
    std::snprintf(buffer, sizeof buffer, "%.17g %.17g %.17g\n", p.x(), p.y(), p.z());
    out += buffer;
  }
  out += "</DataArray>\n</Points>\n<Cells>\n<DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n";
  for (const auto& c : cells) {
    for (std::uint32_t v : c) out += cat(v, ' ');
    out += '\n';
  }
  out += "</DataArray>\n<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n";
  std::size_t offset = 0;
  for (const auto& c : cells) {
    offset += c.size();
    out += cat(offset, '\n');
  }
  out += "</DataArray>\n<DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n";
  for (const auto& c : cells) out += c.size() == 2 ? "3\n" : "7\n";
  out += "</DataArray>\n</Cells>\n<CellData>\n<DataArray type=\"Int32\" Name=\"facet\" format=\"ascii\">\n";
  for (int f : cell_facet) out += cat(f, '\n');
  out += "</DataArray>\n<DataArray type=\"Int32\" Name=\"marker\" format=\"ascii\">\n";
  for (int m : cell_marker) out += cat(m, '\n');
  out += "</DataArray>\n";
  if (colored) {
    out += "<DataArray type=\"UInt8\" Name=\"color\" NumberOfComponents=\"3\" format=\"ascii\">\n";
    for (std::size_t c = 0; c < cells.size(); ++c) {
      const auto color = plc.facet_marker_colors.find(cell_marker[c]);
      if (cell_facet[c] < 0 || color == plc.facet_marker_colors.end()) {
        out += "0 0 0\n";
        continue;
      }
      const auto rgb = color_bytes(color->second);
      out += cat(int{rgb[0]}, ' ', int{rgb[1]}, ' ', int{rgb[2]}, '\n');
    }
    out += "</DataArray>\n";
  }
  out += "</CellData>\n</Piece>\n</UnstructuredGrid>\n</VTKFile>\n";
  return out;
}

Expected<void> write_plc(const Plc& plc, const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  Expected<std::string> text = make_error(
      ErrorCode::Unsupported, cat("cannot write '", path.string(), "': expected .poly, .smesh, .off or .vtu"));
  if (ext == ".poly") text = format_tetgen_poly(plc);
  if (ext == ".smesh") text = format_tetgen_smesh(plc);
  if (ext == ".off") text = format_off(plc);
  if (ext == ".vtu") text = format_plc_vtu(plc);
  if (!text) return text.error();
  return write_text_file(path, *text);
}

}  // namespace delmesh
