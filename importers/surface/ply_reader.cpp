// PLY reader: ascii and binary, vertex positions and face lists (see surface_soup.h).
#include <cstring>
#include <optional>

#include "importers/line_reader.h"
#include "importers/surface/surface_soup.h"
#include "toolkit/core/str_cat.h"

namespace delmesh {
namespace {

enum class Type { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };

std::optional<Type> type_of(std::string_view name) {
  if (name == "char" || name == "int8") return Type::Int8;
  if (name == "uchar" || name == "uint8") return Type::UInt8;
  if (name == "short" || name == "int16") return Type::Int16;
  if (name == "ushort" || name == "uint16") return Type::UInt16;
  if (name == "int" || name == "int32") return Type::Int32;
  if (name == "uint" || name == "uint32") return Type::UInt32;
  if (name == "float" || name == "float32") return Type::Float32;
  if (name == "double" || name == "float64") return Type::Float64;
  return std::nullopt;
}

std::size_t size_of(Type t) {
  switch (t) {
    case Type::Int8:
    case Type::UInt8: return 1;
    case Type::Int16:
    case Type::UInt16: return 2;
    case Type::Int32:
    case Type::UInt32:
    case Type::Float32: return 4;
    case Type::Float64: return 8;
  }
  return 1;
}

struct Property {
  std::string name;
  Type type = Type::Float32;
  bool is_list = false;
  Type count_type = Type::UInt8;
};

struct Element {
  std::string name;
  std::size_t count = 0;
  std::vector<Property> properties;
};

/// Reads binary values from a byte range.
class BinaryCursor {
 public:
  BinaryCursor(std::string_view bytes, bool big_endian) : bytes_(bytes), big_(big_endian) {}
  bool read(Type t, double* out) {
    const std::size_t n = size_of(t);
    if (pos_ + n > bytes_.size()) return false;
    unsigned char b[8];
    std::memcpy(b, bytes_.data() + pos_, n);
    pos_ += n;
    if (big_) std::reverse(b, b + n);
    switch (t) {
      case Type::Int8: *out = static_cast<std::int8_t>(b[0]); break;
      case Type::UInt8: *out = b[0]; break;
      case Type::Int16: { std::int16_t v; std::memcpy(&v, b, 2); *out = v; break; }
      case Type::UInt16: { std::uint16_t v; std::memcpy(&v, b, 2); *out = v; break; }
      case Type::Int32: { std::int32_t v; std::memcpy(&v, b, 4); *out = v; break; }
      case Type::UInt32: { std::uint32_t v; std::memcpy(&v, b, 4); *out = v; break; }
      case Type::Float32: { float v; std::memcpy(&v, b, 4); *out = v; break; }
      case Type::Float64: { double v; std::memcpy(&v, b, 8); *out = v; break; }
    }
    return true;
  }
  std::size_t offset() const { return pos_; }

 private:
  std::string_view bytes_;
  bool big_;
  std::size_t pos_ = 0;
};

}  // namespace

Expected<SurfaceSoup> parse_ply(std::string_view bytes, std::string_view file_name) {
  const std::string file(file_name);
  auto fail = [&](const std::string& message, std::size_t line) {
    return make_error(ErrorCode::ParseError, message, file, line);
  };
  // Header: text lines up to "end_header".
  std::size_t pos = 0, line_no = 0;
  std::string format;
  std::vector<Element> elements;
  bool ended = false;
  while (pos < bytes.size() && !ended) {
    std::size_t end = bytes.find('\n', pos);
    if (end == std::string_view::npos) end = bytes.size();
    std::string_view line = bytes.substr(pos, end - pos);
    pos = end + 1;
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    std::vector<std::string_view> t;
    for (std::size_t i = 0; i < line.size();) {
      while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
      std::size_t j = i;
      while (j < line.size() && line[j] != ' ' && line[j] != '\t') ++j;
      if (j > i) t.push_back(line.substr(i, j - i));
      i = j;
    }
    if (line_no == 1) {
      if (t.size() != 1 || t[0] != "ply") return fail("not a PLY file (no 'ply' magic line)", 1);
      continue;
    }
    if (t.empty() || t[0] == "comment" || t[0] == "obj_info") continue;
    if (t[0] == "format") {
      if (t.size() < 2) return fail("incomplete 'format' line", line_no);
      format = std::string(t[1]);
      if (format != "ascii" && format != "binary_little_endian" && format != "binary_big_endian") {
        return fail("unknown PLY format '" + format + "'", line_no);
      }
    } else if (t[0] == "element") {
      if (t.size() != 3) return fail("malformed 'element' line", line_no);
      unsigned long long count = 0;
      auto [ptr, ec] = std::from_chars(t[2].data(), t[2].data() + t[2].size(), count);
      if (ec != std::errc() || ptr != t[2].data() + t[2].size()) return fail("bad element count", line_no);
      elements.push_back({std::string(t[1]), static_cast<std::size_t>(count), {}});
    } else if (t[0] == "property") {
      if (elements.empty()) return fail("'property' before any 'element'", line_no);
      Property p;
      if (t.size() == 5 && t[1] == "list") {
        const auto ct = type_of(t[2]), it = type_of(t[3]);
        if (!ct || !it) return fail("unknown property type", line_no);
        p.is_list = true;
        p.count_type = *ct;
        p.type = *it;
        p.name = std::string(t[4]);
      } else if (t.size() == 3) {
        const auto ty = type_of(t[1]);
        if (!ty) return fail(cat("unknown property type '", t[1]) + "'", line_no);
        p.type = *ty;
        p.name = std::string(t[2]);
      } else {
        return fail("malformed 'property' line", line_no);
      }
      elements.back().properties.push_back(std::move(p));
    } else if (t[0] == "end_header") {
      ended = true;
    } else {
      return fail(cat("unexpected '", t[0]) + "' in the PLY header", line_no);
    }
  }
  if (!ended) return fail("PLY header without 'end_header'", line_no);
  if (format.empty()) return fail("PLY header without 'format'", line_no);

  SurfaceSoup soup;
  const std::string_view body = bytes.substr(std::min(pos, bytes.size()));
  const bool ascii = format == "ascii";
  LineReader text(ascii ? body : std::string_view{}, file_name);
  BinaryCursor binary(ascii ? std::string_view{} : body, format == "binary_big_endian");
  auto value = [&](Type type, const std::string& what) -> Expected<double> {
    if (ascii) {
      if (text.remaining() == 0 && !text.next()) {
        return make_error(ErrorCode::ParseError, "unexpected end of file, expected " + what, file,
                          line_no + text.line());
      }
      return text.real(what);
    }
    double v = 0;
    if (!binary.read(type, &v)) {
      return make_error(ErrorCode::ParseError, "unexpected end of binary data, expected " + what, file, 0);
    }
    return v;
  };
  bool have_vertices = false;
  std::vector<std::uint32_t> face;
  for (const Element& element : elements) {
    const bool vertex = element.name == "vertex";
    const bool is_face = element.name == "face";
    int xyz[3] = {-1, -1, -1};
    int list = -1;
    for (std::size_t k = 0; k < element.properties.size(); ++k) {
      const auto& p = element.properties[k];
      if (vertex && !p.is_list && (p.name == "x" || p.name == "y" || p.name == "z")) {
        xyz[p.name[0] - 'x'] = static_cast<int>(k);
      }
      if (is_face && p.is_list && (p.name == "vertex_indices" || p.name == "vertex_index")) {
        list = static_cast<int>(k);
      }
    }
    if (vertex && (xyz[0] < 0 || xyz[1] < 0 || xyz[2] < 0)) {
      return fail("the vertex element lacks an x, y or z property", 0);
    }
    if (is_face && list < 0) return fail("the face element has no vertex_indices list", 0);
    if (!vertex && !is_face) soup.ignored_elements += element.count;
    if (is_face && !have_vertices) return fail("the face element comes before the vertex element", 0);
    // An element without properties has nothing to read, whatever its count says.
    const std::size_t count = element.properties.empty() ? 0 : element.count;
    for (std::size_t i = 0; i < count; ++i) {
      Vec3 p = Vec3::Zero();
      face.clear();
      const std::size_t record_line = ascii ? line_no + text.line() + 1 : 0;
      for (std::size_t k = 0; k < element.properties.size(); ++k) {
        const Property& prop = element.properties[k];
        if (prop.is_list) {
          DELMESH_TRY(n, value(prop.count_type, "list length"));
          if (*n < 0 || *n != std::floor(*n) || *n > 1e6) {
            return fail("bad list length in element '" + element.name + cat("' ", i), record_line);
          }
          for (std::size_t j = 0; j < static_cast<std::size_t>(*n); ++j) {
            DELMESH_TRY(v, value(prop.type, "list item"));
            if (static_cast<int>(k) != list) continue;
            if (*v < 0 || *v != std::floor(*v) || *v >= static_cast<double>(soup.points.size())) {
              Error e = make_error(ErrorCode::InvalidInput,
                                   cat("face ", i) + cat(" names vertex ", *v) +
                                       cat(", but there are ", soup.points.size()) + " vertices",
                                   file, record_line);
              return e;
            }
            face.push_back(static_cast<std::uint32_t>(*v));
          }
        } else {
          DELMESH_TRY(v, value(prop.type, "property '" + prop.name + "'"));
          if (vertex) {
            for (int c = 0; c < 3; ++c) {
              if (xyz[c] == static_cast<int>(k)) p[c] = *v;
            }
          }
        }
      }
      if (vertex) {
        if (!p.allFinite()) return fail(cat("vertex ", i) + " has a non-finite coordinate", record_line);
        soup.points.push_back(p);
      }
      if (is_face) {
        if (face.size() < 3) return fail(cat("face ", i) + " has fewer than 3 vertices", record_line);
        soup.add_face(face.data(), face.size(), record_line);
      }
    }
    if (vertex) have_vertices = true;
  }
  return soup;
}

}  // namespace delmesh
