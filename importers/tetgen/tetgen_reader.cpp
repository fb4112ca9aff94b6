// TetGen .node/.poly/.smesh reader (see tetgen_reader.h).
#include "importers/tetgen/tetgen_reader.h"

#include <cctype>
#include <cmath>
#include <string>
#include <vector>

#include "importers/line_reader.h"
#include "toolkit/core/str_cat.h"
#include "toolkit/plc/plc_tables.h"

namespace delmesh {
namespace {

using namespace std::string_literals;

/// Reads the node list (header already on the current line). Sets `base` from the first
/// index.
Expected<void> read_nodes(LineReader& in, Plc& plc, std::size_t n, int* base) {
  DELMESH_TRY(dim, in.integer("dimension"));
  if (*dim != 3) {
    return in.error(cat("dimension is ", *dim) +
                    ", expected 3 (2D .poly files are read by 'delmesh tri')");
  }
  std::size_t attributes = 0, markers = 0;
  if (in.remaining() > 0) {
    DELMESH_TRY(a, in.count("number of attributes"));
    attributes = *a;
  }
  if (in.remaining() > 0) {
    DELMESH_TRY(m, in.count("boundary marker flag"));
    markers = *m;
  }
  // Labels are built only for an error message (LineReader::label_text).
  for (std::size_t i = 0; i < n; ++i) {
    DELMESH_TRY(ok, in.require_line([i] { return cat("point ", i); }));
    DELMESH_TRY(index, in.integer("point index"));
    if (i == 0) {
      if (*index != 0 && *index != 1) {
        return in.error(cat("the first point is numbered ", *index) + ", expected 0 or 1");
      }
      *base = static_cast<int>(*index);
    }
    if (*index != static_cast<long long>(i) + *base) {
      return in.error(cat("point numbered ", *index) + ", expected " +
                      std::to_string(i + static_cast<std::size_t>(*base)));
    }
    Vec3 p;
    for (int k = 0; k < 3; ++k) {
      DELMESH_TRY(x, in.real([k] { return "coordinate "s + "xyz"[k]; }));
      p[k] = *x;
    }
    plc.points.push_back(p);
    for (std::size_t a = 0; a < attributes; ++a) {
      DELMESH_TRY(attr, in.real("point attribute"));
    }
    if (markers > 0) {
      DELMESH_TRY(marker, in.integer("point boundary marker"));
      plc.point_markers.push_back(static_cast<int>(*marker));
    }
  }
  return {};
}

/// `where` returns the name of the polygon read (called for an error message only).
template <class Where>
Expected<std::uint32_t> vertex_index(LineReader& in, int base, std::size_t n, const Where& where) {
  DELMESH_TRY(v, in.integer([&] { return "vertex number of "s + where(); }, true));
  const long long index = *v - base;
  if (index < 0 || static_cast<std::size_t>(index) >= n) {
    Error error = in.error(where() + cat(" names vertex ", *v) + ", but vertices are numbered " +
                           std::to_string(base) + ".." +
                           std::to_string(static_cast<long long>(n) - 1 + base));
    error.code = ErrorCode::InvalidInput;
    return error;
  }
  return static_cast<std::uint32_t>(index);
}

Expected<Vec3> read_point(LineReader& in, const std::string& what) {
  Vec3 p;
  for (int k = 0; k < 3; ++k) {
    DELMESH_TRY(x, in.real(what + " coordinate " + "xyz"[k]));
    p[k] = *x;
  }
  return p;
}

/// Adds a facet, turning facets of 2-vertex polygons only into free segments.
void add_facet(Plc& plc, Plc::Facet facet) {
  bool only_short = true;
  for (const auto& polygon : facet.polygons) only_short = only_short && polygon.size() < 3;
  if (!only_short || !facet.holes.empty()) {
    plc.facets.push_back(std::move(facet));
    return;
  }
  for (const auto& polygon : facet.polygons) {
    if (polygon.size() == 2) plc.segments.push_back({polygon[0], polygon[1], facet.marker});
  }
}

Expected<void> read_facets(LineReader& in, Plc& plc, int base, bool smesh) {
  DELMESH_TRY(ok, in.require_line("the facet list header"));
  DELMESH_TRY(nf, in.count("number of facets"));
  std::size_t markers = 0;
  if (in.remaining() > 0) {
    DELMESH_TRY(m, in.count("facet marker flag"));
    markers = *m;
  }
  const std::size_t n = plc.points.size();
  for (std::size_t f = 0; f < *nf; ++f) {
    // Names for error messages, built only when one is reported (LineReader::label_text).
    const auto name = [&] { return cat("facet ", f + static_cast<std::size_t>(base)); };
    Plc::Facet facet;
    DELMESH_TRY(line, in.require_line(name));
    if (smesh) {
      DELMESH_TRY(corners, in.count([&] { return "number of corners of "s + name(); }));
      Plc::Polygon polygon;
      for (std::size_t c = 0; c < *corners; ++c) {
        DELMESH_TRY(v, vertex_index(in, base, n, name));
        polygon.push_back(*v);
      }
      if (markers > 0 && in.remaining() > 0) {
        DELMESH_TRY(marker, in.integer([&] { return "marker of "s + name(); }));
        facet.marker = static_cast<int>(*marker);
      }
      facet.polygons.push_back(std::move(polygon));
    } else {
      DELMESH_TRY(polygons, in.count([&] { return "number of polygons of "s + name(); }));
      std::size_t holes = 0;
      if (in.remaining() > 0) {
        DELMESH_TRY(h, in.count([&] { return "number of holes of "s + name(); }));
        holes = *h;
      }
      if (markers > 0 && in.remaining() > 0) {
        DELMESH_TRY(marker, in.integer([&] { return "marker of "s + name(); }));
        facet.marker = static_cast<int>(*marker);
      }
      for (std::size_t k = 0; k < *polygons; ++k) {
        const auto where = [&] { return name() + cat(" polygon ", k); };
        DELMESH_TRY(pline, in.require_line(where));
        DELMESH_TRY(corners, in.count([&] { return "number of corners of "s + where(); }));
        Plc::Polygon polygon;
        for (std::size_t c = 0; c < *corners; ++c) {
          DELMESH_TRY(v, vertex_index(in, base, n, where));
          polygon.push_back(*v);
        }
        facet.polygons.push_back(std::move(polygon));
      }
      for (std::size_t h = 0; h < holes; ++h) {
        const std::string where = name() + cat(" hole ", h);
        DELMESH_TRY(hline, in.require_line(where));
        DELMESH_TRY(index, in.integer("hole number"));
        DELMESH_TRY(p, read_point(in, where));
        facet.holes.push_back(*p);
      }
    }
    add_facet(plc, std::move(facet));
  }
  return {};
}

Expected<void> read_holes_and_regions(LineReader& in, Plc& plc) {
  if (!in.next()) return {};  // TetGen accepts files that end after the facets
  DELMESH_TRY(nh, in.count("number of volume holes"));
  for (std::size_t h = 0; h < *nh; ++h) {
    DELMESH_TRY(line, in.require_line(cat("volume hole ", h)));
    DELMESH_TRY(index, in.integer("hole number"));
    DELMESH_TRY(p, read_point(in, "volume hole"));
    plc.holes.push_back(*p);
  }
  if (!in.next()) return {};
  DELMESH_TRY(nr, in.count("number of regions"));
  for (std::size_t r = 0; r < *nr; ++r) {
    DELMESH_TRY(line, in.require_line(cat("region ", r)));
    DELMESH_TRY(index, in.integer("region number"));
    DELMESH_TRY(p, read_point(in, "region"));
    Plc::Region region;
    region.point = *p;
    if (in.remaining() > 0) {
      DELMESH_TRY(attribute, in.real("region attribute"));
      if (*attribute != std::floor(*attribute) || std::fabs(*attribute) > 2e9) {
        return in.error(cat("region attribute ", *attribute) + " is not an integer");
      }
      region.id = static_cast<int>(*attribute);
    }
    if (in.remaining() > 0) {
      DELMESH_TRY(volume, in.real("region maximum volume"));
      region.max_volume = *volume;
    }
    plc.regions.push_back(region);
  }
  if (in.next()) return in.error("unexpected data after the region list");
  return {};
}

}  // namespace

Expected<Plc> parse_tetgen(std::string_view text, TetgenFileKind kind, std::string_view file_name,
                           const std::filesystem::path& node_file) {
  LineReader in(text, file_name);
  Plc plc;
  int base = 0;
  DELMESH_TRY(header, in.require_line("the node list header"));
  DELMESH_TRY(n, in.count("number of points"));
  if (*n > 0 || kind == TetgenFileKind::Node) {
    DELMESH_TRY(nodes, read_nodes(in, plc, *n, &base));
  } else {
    if (node_file.empty()) return in.error("the node list is empty and there is no .node file to read");
    DELMESH_TRY(node_text, read_text(node_file));
    const std::string node_name = node_file.string();
    LineReader node_in(*node_text, node_name);
    DELMESH_TRY(node_header, node_in.require_line("the node list header"));
    DELMESH_TRY(nn, node_in.count("number of points"));
    DELMESH_TRY(nodes, read_nodes(node_in, plc, *nn, &base));
  }
  if (kind == TetgenFileKind::Node) {
    if (in.next()) return in.error("unexpected data after the node list");
    return plc;
  }
  DELMESH_TRY(facets, read_facets(in, plc, base, kind == TetgenFileKind::Smesh));
  DELMESH_TRY(rest, read_holes_and_regions(in, plc));
  read_label_table_comments(text, "#", plc);
  return plc;
}

Expected<Plc> read_tetgen(const std::filesystem::path& path, TetgenFileKind kind) {
  DELMESH_TRY(text, read_text(path));
  std::filesystem::path node_file = path;
  node_file.replace_extension(".node");
  return parse_tetgen(*text, kind, path.string(), kind == TetgenFileKind::Node ? std::filesystem::path{} : node_file);
}

Expected<Plc> read_tetgen(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (ext == ".node") return read_tetgen(path, TetgenFileKind::Node);
  if (ext == ".smesh") return read_tetgen(path, TetgenFileKind::Smesh);
  if (ext == ".poly") return read_tetgen(path, TetgenFileKind::Poly);
  return make_error(ErrorCode::Unsupported, "'"s + path.string() + "' is not a .node, .poly or .smesh file");
}

}  // namespace delmesh
