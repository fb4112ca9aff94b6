// TetGen .node/.poly/.smesh reader (see tetgen_reader.h).
#include "importers/tetgen/tetgen_reader.h"

#include <charconv>
#include <cmath>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

namespace delmesh {
namespace {

using namespace std::string_literals;

/// Splits text into lines of whitespace-separated tokens, skipping comments and blank
/// lines, and reads numbers from them with file:line errors.
class LineReader {
 public:
  LineReader(std::string_view text, std::string_view file) : text_(text), file_(file) {}

  /// Advances to the next line holding data; false at the end of the text.
  bool next() {
    tokens_.clear();
    pos_ = 0;
    while (offset_ < text_.size()) {
      std::size_t end = text_.find('\n', offset_);
      if (end == std::string_view::npos) end = text_.size();
      std::string_view line = text_.substr(offset_, end - offset_);
      offset_ = end + 1;
      ++line_;
      if (const auto hash = line.find('#'); hash != std::string_view::npos) line = line.substr(0, hash);
      std::size_t i = 0;
      while (i < line.size()) {
        while (i < line.size() && is_space(line[i])) ++i;
        std::size_t j = i;
        while (j < line.size() && !is_space(line[j])) ++j;
        if (j > i) tokens_.push_back(line.substr(i, j - i));
        i = j;
      }
      if (!tokens_.empty()) return true;
    }
    return false;
  }

  /// Moves to the next data line or fails with "expected <what>".
  Expected<void> require_line(const std::string& what) {
    if (next()) return {};
    return error("unexpected end of file, expected "s + what);
  }

  std::size_t remaining() const { return tokens_.size() - pos_; }

  /// Next token of the current record; continues onto following lines when the current
  /// one is exhausted (TetGen allows long polygons to wrap).
  Expected<std::string_view> token(const std::string& what, bool may_wrap) {
    if (pos_ >= tokens_.size()) {
      if (!may_wrap) return error("missing "s + what);
      const std::size_t line = line_;
      if (!next()) return error_at("unexpected end of file, expected "s + what, line);
    }
    return tokens_[pos_++];
  }

  Expected<long long> integer(const std::string& what, bool may_wrap = false) {
    auto t = token(what, may_wrap);
    if (!t) return t.error();
    long long value = 0;
    const char* end = t->data() + t->size();
    auto [ptr, ec] = std::from_chars(t->data(), end, value);
    if (ec != std::errc() || ptr != end) {
      return error("expected an integer for "s + what + ", found '" + std::string(*t) + "'");
    }
    return value;
  }

  Expected<std::size_t> count(const std::string& what) {
    auto v = integer(what);
    if (!v) return v.error();
    if (*v < 0) return error(what + " is negative (" + std::to_string(*v) + ")");
    return static_cast<std::size_t>(*v);
  }

  Expected<double> real(const std::string& what, bool may_wrap = false) {
    auto t = token(what, may_wrap);
    if (!t) return t.error();
    double value = 0;
    const char* end = t->data() + t->size();
    auto [ptr, ec] = std::from_chars(t->data(), end, value);
    if (ec != std::errc() || ptr != end || !std::isfinite(value)) {
      return error("expected a finite number for "s + what + ", found '" + std::string(*t) + "'");
    }
    return value;
  }

  Error error(const std::string& message) const { return error_at(message, line_); }
  Error error_at(const std::string& message, std::size_t line) const {
    return make_error(ErrorCode::ParseError, message, std::string(file_), line);
  }
  std::size_t line() const { return line_; }
  std::string_view file() const { return file_; }

 private:
  static bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

  std::string_view text_;
  std::string_view file_;
  std::size_t offset_ = 0;
  std::size_t line_ = 0;
  std::vector<std::string_view> tokens_;
  std::size_t pos_ = 0;
};

#define DELMESH_TRY(var, expr)          \
  auto var = (expr);                    \
  if (!var) return var.error();

Expected<std::string> read_text(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return make_error(ErrorCode::IoError, "cannot open '"s + path.string() + "'");
  std::ostringstream buffer;
  buffer << in.rdbuf();
  if (in.bad()) return make_error(ErrorCode::IoError, "cannot read '"s + path.string() + "'");
  return buffer.str();
}

/// Reads the node list (header already on the current line). Sets `base` from the first
/// index.
Expected<void> read_nodes(LineReader& in, Plc& plc, std::size_t n, int* base) {
  DELMESH_TRY(dim, in.integer("dimension"));
  if (*dim != 3) {
    return in.error("dimension is "s + std::to_string(*dim) +
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
  for (std::size_t i = 0; i < n; ++i) {
    DELMESH_TRY(ok, in.require_line("point "s + std::to_string(i)));
    DELMESH_TRY(index, in.integer("point index"));
    if (i == 0) {
      if (*index != 0 && *index != 1) {
        return in.error("the first point is numbered "s + std::to_string(*index) + ", expected 0 or 1");
      }
      *base = static_cast<int>(*index);
    }
    if (*index != static_cast<long long>(i) + *base) {
      return in.error("point numbered "s + std::to_string(*index) + ", expected " +
                      std::to_string(i + static_cast<std::size_t>(*base)));
    }
    Vec3 p;
    for (int k = 0; k < 3; ++k) {
      DELMESH_TRY(x, in.real("coordinate "s + "xyz"[k]));
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

Expected<std::uint32_t> vertex_index(LineReader& in, int base, std::size_t n, const std::string& where) {
  DELMESH_TRY(v, in.integer("vertex number of "s + where, true));
  const long long index = *v - base;
  if (index < 0 || static_cast<std::size_t>(index) >= n) {
    Error error = in.error(where + " names vertex " + std::to_string(*v) + ", but vertices are numbered " +
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
    const std::string name = "facet "s + std::to_string(f + static_cast<std::size_t>(base));
    Plc::Facet facet;
    DELMESH_TRY(line, in.require_line(name));
    if (smesh) {
      DELMESH_TRY(corners, in.count("number of corners of "s + name));
      Plc::Polygon polygon;
      for (std::size_t c = 0; c < *corners; ++c) {
        DELMESH_TRY(v, vertex_index(in, base, n, name));
        polygon.push_back(*v);
      }
      if (markers > 0 && in.remaining() > 0) {
        DELMESH_TRY(marker, in.integer("marker of "s + name));
        facet.marker = static_cast<int>(*marker);
      }
      facet.polygons.push_back(std::move(polygon));
    } else {
      DELMESH_TRY(polygons, in.count("number of polygons of "s + name));
      std::size_t holes = 0;
      if (in.remaining() > 0) {
        DELMESH_TRY(h, in.count("number of holes of "s + name));
        holes = *h;
      }
      if (markers > 0 && in.remaining() > 0) {
        DELMESH_TRY(marker, in.integer("marker of "s + name));
        facet.marker = static_cast<int>(*marker);
      }
      for (std::size_t k = 0; k < *polygons; ++k) {
        const std::string where = name + " polygon " + std::to_string(k);
        DELMESH_TRY(pline, in.require_line(where));
        DELMESH_TRY(corners, in.count("number of corners of "s + where));
        Plc::Polygon polygon;
        for (std::size_t c = 0; c < *corners; ++c) {
          DELMESH_TRY(v, vertex_index(in, base, n, where));
          polygon.push_back(*v);
        }
        facet.polygons.push_back(std::move(polygon));
      }
      for (std::size_t h = 0; h < holes; ++h) {
        const std::string where = name + " hole " + std::to_string(h);
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
    DELMESH_TRY(line, in.require_line("volume hole "s + std::to_string(h)));
    DELMESH_TRY(index, in.integer("hole number"));
    DELMESH_TRY(p, read_point(in, "volume hole"));
    plc.holes.push_back(*p);
  }
  if (!in.next()) return {};
  DELMESH_TRY(nr, in.count("number of regions"));
  for (std::size_t r = 0; r < *nr; ++r) {
    DELMESH_TRY(line, in.require_line("region "s + std::to_string(r)));
    DELMESH_TRY(index, in.integer("region number"));
    DELMESH_TRY(p, read_point(in, "region"));
    Plc::Region region;
    region.point = *p;
    if (in.remaining() > 0) {
      DELMESH_TRY(attribute, in.real("region attribute"));
      if (*attribute != std::floor(*attribute) || std::fabs(*attribute) > 2e9) {
        return in.error("region attribute "s + std::to_string(*attribute) + " is not an integer");
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
