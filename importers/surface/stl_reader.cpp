// STL reader, ASCII and binary (see surface_soup.h).
#include <cctype>
#include <cstring>

#include "importers/line_reader.h"
#include "importers/surface/surface_soup.h"
#include "toolkit/core/str_cat.h"

namespace delmesh {
namespace {

float read_float_le(const unsigned char* p) {
  std::uint32_t bits = static_cast<std::uint32_t>(p[0]) | (static_cast<std::uint32_t>(p[1]) << 8) |
                       (static_cast<std::uint32_t>(p[2]) << 16) | (static_cast<std::uint32_t>(p[3]) << 24);
  float value;
  std::memcpy(&value, &bits, sizeof value);
  return value;
}

Expected<SurfaceSoup> parse_binary(std::string_view bytes, std::string_view file, std::uint32_t n) {
  SurfaceSoup soup;
  const auto* data = reinterpret_cast<const unsigned char*>(bytes.data()) + 84;
  soup.points.reserve(3 * static_cast<std::size_t>(n));
  for (std::uint32_t t = 0; t < n; ++t, data += 50) {
    std::uint32_t ids[3];
    for (int k = 0; k < 3; ++k) {
      const unsigned char* v = data + 12 + 12 * k;
      const Vec3 p(read_float_le(v), read_float_le(v + 4), read_float_le(v + 8));
      if (!p.allFinite()) {
        return make_error(ErrorCode::InvalidInput, cat("triangle ", t) +
                                                       " has a non-finite vertex coordinate",
                          std::string(file), 0);
      }
      ids[k] = static_cast<std::uint32_t>(soup.points.size());
      soup.points.push_back(p);
    }
    soup.add_face(ids, 3, 0);
  }
  return soup;
}

bool is_keyword(std::string_view token, std::string_view keyword) {
  if (token.size() != keyword.size()) return false;
  for (std::size_t i = 0; i < token.size(); ++i) {
    if (std::tolower(static_cast<unsigned char>(token[i])) != keyword[i]) return false;
  }
  return true;
}

Expected<SurfaceSoup> parse_ascii(std::string_view text, std::string_view file) {
  SurfaceSoup soup;
  LineReader in(text, file, false);
  std::vector<std::uint32_t> loop;
  bool in_loop = false;
  std::size_t loop_line = 0;
  bool solid = false;
  while (in.next()) {
    DELMESH_TRY(keyword, in.token("a keyword", false));
    if (is_keyword(*keyword, "solid")) {
      solid = true;
    } else if (is_keyword(*keyword, "outer")) {
      if (in_loop) return in.error("'outer loop' inside an open loop");
      in_loop = true;
      loop.clear();
      loop_line = in.line();
    } else if (is_keyword(*keyword, "vertex")) {
      if (!in_loop) return in.error("'vertex' outside 'outer loop' ... 'endloop'");
      Vec3 p;
      for (int k = 0; k < 3; ++k) {
        DELMESH_TRY(x, in.real(std::string("vertex coordinate ") + "xyz"[k]));
        p[k] = *x;
      }
      loop.push_back(static_cast<std::uint32_t>(soup.points.size()));
      soup.points.push_back(p);
    } else if (is_keyword(*keyword, "endloop")) {
      if (!in_loop) return in.error("'endloop' without 'outer loop'");
      if (loop.size() != 3) {
        return in.error(cat("facet has ", loop.size()) + " vertices, STL facets have 3");
      }
      soup.add_face(loop.data(), 3, loop_line);
      in_loop = false;
    } else if (is_keyword(*keyword, "facet") || is_keyword(*keyword, "endfacet") ||
               is_keyword(*keyword, "endsolid")) {
      if (in_loop) return in.error(cat("'", *keyword) + "' inside 'outer loop' ... 'endloop'");
    } else {
      return in.error(cat("unexpected '", *keyword) + "' in ASCII STL");
    }
  }
  if (in_loop) return in.error_at("unexpected end of file inside a facet", loop_line);
  if (!solid) return in.error_at("ASCII STL without 'solid'", 1);
  return soup;
}

}  // namespace

Expected<SurfaceSoup> parse_stl(std::string_view bytes, std::string_view file_name) {
  if (bytes.size() >= 84) {
    const auto* p = reinterpret_cast<const unsigned char*>(bytes.data()) + 80;
    const std::uint32_t n = static_cast<std::uint32_t>(p[0]) | (static_cast<std::uint32_t>(p[1]) << 8) |
                            (static_cast<std::uint32_t>(p[2]) << 16) |
                            (static_cast<std::uint32_t>(p[3]) << 24);
    if (bytes.size() == 84 + 50 * static_cast<std::uint64_t>(n)) return parse_binary(bytes, file_name, n);
  }
  std::size_t i = 0;
  while (i < bytes.size() && std::isspace(static_cast<unsigned char>(bytes[i]))) ++i;
  if (bytes.substr(i, 5) == "solid") return parse_ascii(bytes, file_name);
  if (bytes.size() >= 84) {
    const auto* p = reinterpret_cast<const unsigned char*>(bytes.data()) + 80;
    const std::uint64_t n = p[0] | (p[1] << 8) | (p[2] << 16) | (static_cast<std::uint64_t>(p[3]) << 24);
    return make_error(ErrorCode::ParseError,
                      cat("binary STL header announces ", n) + " triangles (" +
                          std::to_string(84 + 50 * n) + " bytes) but the file has " +
                          std::to_string(bytes.size()) + " bytes",
                      std::string(file_name), 0);
  }
  return make_error(ErrorCode::ParseError, "neither ASCII STL (no 'solid') nor binary STL (shorter than 84 bytes)",
                    std::string(file_name), 0);
}

}  // namespace delmesh
