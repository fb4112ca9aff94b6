// TetGen .poly/.smesh and .off writers (see tetgen_writer.h).
#include "importers/tetgen/tetgen_writer.h"
#include "toolkit/core/str_cat.h"
#include "toolkit/plc/plc_tables.h"

#include <array>
#include <cstdio>
#include <fstream>

namespace delmesh {
namespace {

void append_point(std::string& out, const Vec3& p) {
  char buffer[96];
  std::snprintf(buffer, sizeof buffer, " %.17g %.17g %.17g", p.x(), p.y(), p.z());
  out += buffer;
}

void append_nodes(std::string& out, const Plc& plc) {
  const bool markers = plc.point_markers.size() == plc.points.size() && !plc.points.empty();
  out += "# part 1: node list\n";
  out += std::to_string(plc.points.size()) + " 3 0 " + (markers ? "1" : "0") + "\n";
  for (std::size_t i = 0; i < plc.points.size(); ++i) {
    out += std::to_string(i + 1);
    append_point(out, plc.points[i]);
    if (markers) { out += ' '; out += std::to_string(plc.point_markers[i]); }
    out += '\n';
  }
}

void append_polygon(std::string& out, const Plc::Polygon& polygon) {
  out += std::to_string(polygon.size());
  for (std::uint32_t v : polygon) { out += ' '; out += std::to_string(v + 1); }
}

void append_holes_and_regions(std::string& out, const Plc& plc) {
  out += cat("# part 3: volume hole list\n", plc.holes.size()) + "\n";
  for (std::size_t i = 0; i < plc.holes.size(); ++i) {
    out += std::to_string(i + 1);
    append_point(out, plc.holes[i]);
    out += '\n';
  }
  out += cat("# part 4: region list\n", plc.regions.size()) + "\n";
  for (std::size_t i = 0; i < plc.regions.size(); ++i) {
    const auto& r = plc.regions[i];
    out += std::to_string(i + 1);
    append_point(out, r.point);
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, " %d %.17g\n", r.id, r.max_volume);
    out += buffer;
  }
}

/// The marker and region tables as # comment lines (TetGen has no field for them).
void append_label_tables(std::string& out, const Plc& plc) {
  const auto append = [&](const std::vector<std::string>& lines) {
    for (const std::string& line : lines) out += "# " + line + "\n";
  };
  append(label_table_lines("facet_marker", plc.facet_marker_names, plc.facet_marker_colors));
  append(label_table_lines("region", plc.region_names, plc.region_colors));
}

Error unsupported_facet(std::size_t f, const char* format) {
  return make_error(ErrorCode::Unsupported,
                    cat("facet ", f) + " has several polygons or holes, which " +
                        format + " cannot express (write .poly instead)");
}

}  // namespace

Expected<std::string> format_tetgen_poly(const Plc& plc) {
  std::string out = "# PLC written by delmesh\n";
  append_nodes(out, plc);
  out += "# part 2: facet list\n";
  out += std::to_string(plc.facets.size() + plc.segments.size()) + " 1\n";
  for (const auto& facet : plc.facets) {
    out += std::to_string(facet.polygons.size()) + cat(" ", facet.holes.size()) + " " +
           std::to_string(facet.marker) + "\n";
    for (const auto& polygon : facet.polygons) {
      append_polygon(out, polygon);
      out += '\n';
    }
    for (std::size_t h = 0; h < facet.holes.size(); ++h) {
      out += std::to_string(h + 1);
      append_point(out, facet.holes[h]);
      out += '\n';
    }
  }
  for (const auto& s : plc.segments) {
    out += cat("1 0 ", s.marker) + cat("\n2 ", s.a + 1) + " " +
           std::to_string(s.b + 1) + "\n";
  }
  append_holes_and_regions(out, plc);
  append_label_tables(out, plc);
  return out;
}

Expected<std::string> format_tetgen_smesh(const Plc& plc) {
  std::string out = "# PLC written by delmesh\n";
  append_nodes(out, plc);
  out += "# part 2: facet list\n";
  out += std::to_string(plc.facets.size() + plc.segments.size()) + " 1\n";
  for (std::size_t f = 0; f < plc.facets.size(); ++f) {
    const auto& facet = plc.facets[f];
    if (facet.polygons.size() != 1 || !facet.holes.empty()) return unsupported_facet(f, ".smesh");
    append_polygon(out, facet.polygons[0]);
    out += cat(" ", facet.marker) + "\n";
  }
  for (const auto& s : plc.segments) {
    out += cat("2 ", s.a + 1) + cat(" ", s.b + 1) + " " +
           std::to_string(s.marker) + "\n";
  }
  append_holes_and_regions(out, plc);
  append_label_tables(out, plc);
  return out;
}

Expected<std::string> format_off(const Plc& plc) {
  std::string out = cat("OFF\n", plc.points.size()) + " " +
                    std::to_string(plc.facets.size()) + " 0\n";
  for (const auto& p : plc.points) {
    append_point(out, p);
    out += '\n';
  }
  for (std::size_t f = 0; f < plc.facets.size(); ++f) {
    const auto& facet = plc.facets[f];
    if (facet.polygons.size() != 1 || !facet.holes.empty()) return unsupported_facet(f, ".off");
    out += std::to_string(facet.polygons[0].size());
    for (std::uint32_t v : facet.polygons[0]) { out += ' '; out += std::to_string(v); }
    if (!plc.facet_marker_colors.empty()) {
      const auto color = plc.facet_marker_colors.find(facet.marker);
      const std::array<std::uint8_t, 3> rgb =
          color == plc.facet_marker_colors.end() ? std::array<std::uint8_t, 3>{} : color_bytes(color->second);
      out += cat(" ", int{rgb[0]}) + cat(" ", int{rgb[1]}) + cat(" ", int{rgb[2]});
    }
    out += '\n';
  }
  return out;
}

Expected<void> write_text_file(const std::filesystem::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  if (!out) return make_error(ErrorCode::IoError, "cannot open '" + path.string() + "' for writing");
  out << text;
  out.close();
  if (!out) return make_error(ErrorCode::IoError, "cannot write '" + path.string() + "'");
  return {};
}

}  // namespace delmesh
