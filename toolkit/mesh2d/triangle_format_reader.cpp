// Reader for Triangle's .node and .poly formats (see triangle_format_reader.h).
#include "toolkit/mesh2d/triangle_format_reader.h"

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <limits>
#include <utility>

#include "toolkit/mesh2d/text_lines.h"

namespace delmesh {
namespace {

/// Ids are 32-bit throughout delmesh; a count beyond this cannot be represented.
constexpr long long kMaxCount = std::numeric_limits<std::uint32_t>::max() - 1;

/// Storage to reserve for `count` records of at least `min_bytes` each: never more than
/// the rest of the file could hold, whatever the (untrusted) count says.
std::size_t reserve_bound(long long count, const TextLines& lines, std::size_t min_bytes) {
  return static_cast<std::size_t>(
      std::min<long long>(count, static_cast<long long>(lines.remaining_bytes() / min_bytes)));
}

/// "<what> <id>", e.g. "x coordinate of vertex 12".
std::string described(std::string_view what, long long id) {
  std::string text(what);
  text.push_back(' ');
  text.append(std::to_string(id));
  return text;
}

std::string fields_word(std::size_t n) {
  if (n > TextLines::kMaxFields) return "more than " + std::to_string(TextLines::kMaxFields) + " fields";
  return std::to_string(n) + (n == 1 ? " field" : " fields");
}

/// Reads a count field (non-negative, at most kMaxCount).
Expected<long long> read_count(const TextLines& lines, std::size_t i, std::string_view what) {
  auto value = lines.integer(i, what);
  if (!value) return value.error();
  if (*value < 0) {
    return lines.error(ErrorCode::InvalidInput,
                       std::string(what) + " is negative (" + std::to_string(*value) + ")");
  }
  if (*value > kMaxCount) {
    return lines.error(ErrorCode::InvalidInput, std::string(what) + " " + std::to_string(*value) +
                                                    " exceeds the supported maximum of " +
                                                    std::to_string(kMaxCount));
  }
  return value;
}

Expected<bool> read_marker_flag(const TextLines& lines, std::size_t i, std::string_view what) {
  if (i >= lines.fields().size()) return false;
  auto value = lines.integer(i, what);
  if (!value) return value.error();
  if (*value != 0 && *value != 1) {
    return lines.error(ErrorCode::InvalidInput,
                       std::string(what) + " must be 0 or 1, not " + std::to_string(*value));
  }
  return *value == 1;
}

Error truncated(const TextLines& lines, std::string_view section, long long found, long long expected) {
  return lines.error(ErrorCode::ParseError,
                     "file ends after " + std::to_string(found) + " of " + std::to_string(expected) +
                         " " + std::string(section));
}

/// Reads the vertex section: the header on the current line, then the vertex lines.
/// Leaves `lines` on the last vertex line (or the header when there are none).
Expected<TriangleInput> read_vertex_section(TextLines& lines, long long count) {
  const auto& f = lines.fields();
  if (f.size() > 4) {
    return lines.error(ErrorCode::ParseError,
                       "vertex header has " + fields_word(f.size()) +
                           "; expected <#vertices> <dimension> <#attributes> <#markers>");
  }
  long long dimension = 2;
  if (f.size() > 1) {
    auto d = lines.integer(1, "dimension");
    if (!d) return d.error();
    dimension = *d;
  }
  if (dimension != 2) {
    return lines.error(ErrorCode::InvalidInput,
                       "dimension is " + std::to_string(dimension) + "; Triangle files are 2D");
  }
  long long num_attributes = 0;
  if (f.size() > 2) {
    auto a = read_count(lines, 2, "number of vertex attributes");
    if (!a) return a.error();
    num_attributes = *a;
  }
  if (num_attributes > static_cast<long long>(TextLines::kMaxFields) - 4) {
    return lines.error(ErrorCode::InvalidInput, "number of vertex attributes " + std::to_string(num_attributes) +
                                                    " exceeds the supported maximum of " +
                                                    std::to_string(TextLines::kMaxFields - 4));
  }
  auto markers = read_marker_flag(lines, 3, "number of vertex boundary markers");
  if (!markers) return markers.error();

  TriangleInput input;
  input.node_file = lines.file_name();
  Pslg& pslg = input.pslg;
  pslg.num_point_attributes = static_cast<int>(num_attributes);
  const std::size_t expected_fields = 3 + static_cast<std::size_t>(num_attributes) + (*markers ? 1 : 0);
  const std::size_t bound = reserve_bound(count, lines, 2 * expected_fields);
  pslg.points.reserve(bound);
  if (*markers) pslg.point_markers.reserve(bound);
  if (num_attributes > 0) {
    pslg.point_attributes.reserve(std::min(bound * static_cast<std::size_t>(num_attributes),
                                           lines.remaining_bytes() / 2));
  }

  for (long long v = 0; v < count; ++v) {
    if (!lines.next()) return truncated(lines, "vertices", v, count);
    const auto& fields = lines.fields();
    auto id = lines.integer(0, "vertex id");
    if (!id) return id.error();
    if (v == 0) {
      if (*id != 0 && *id != 1) {
        return lines.error(ErrorCode::InvalidInput,
                           "first vertex id is " + std::to_string(*id) +
                               "; numbering must start at 0 or 1");
      }
      input.first_index = static_cast<int>(*id);
    }
    const long long expected_id = input.first_index + v;
    if (*id != expected_id) {
      const bool duplicate = *id >= input.first_index && *id < expected_id;
      Error e = lines.error(ErrorCode::InvalidInput,
                            (duplicate ? "duplicate vertex id " : "vertex id ") + std::to_string(*id) +
                                (duplicate ? "" : " out of sequence") +
                                " (ids must be consecutive; expected " + std::to_string(expected_id) + ")");
      e.entity_ids.push_back(static_cast<std::uint32_t>(v));
      return e;
    }
    if (fields.size() != expected_fields) {
      return lines.error(ErrorCode::ParseError,
                         "vertex " + std::to_string(*id) + " has " + fields_word(fields.size()) +
                             "; the header asks for " + std::to_string(expected_fields) +
                             " (id, x, y, " + std::to_string(num_attributes) + " attributes, " +
                             (*markers ? "a marker)" : "no marker)"));
    }
    const long long vid = *id;
    auto x = lines.real(1, [&] { return described("x coordinate of vertex", vid); });
    if (!x) return x.error();
    auto y = lines.real(2, [&] { return described("y coordinate of vertex", vid); });
    if (!y) return y.error();
    pslg.points.push_back({*x, *y});
    for (long long a = 0; a < num_attributes; ++a) {
      auto value = lines.real(3 + static_cast<std::size_t>(a), [&] {
        return described("attribute " + std::to_string(a + 1) + " of vertex", vid);
      });
      if (!value) return value.error();
      pslg.point_attributes.push_back(*value);
    }
    if (*markers) {
      auto marker = lines.integer(expected_fields - 1, [&] { return described("boundary marker of vertex", vid); });
      if (!marker) return marker.error();
      if (*marker < std::numeric_limits<int>::min() || *marker > std::numeric_limits<int>::max()) {
        return lines.error(ErrorCode::InvalidInput, described("boundary marker of vertex", vid) + " is out of range");
      }
      pslg.point_markers.push_back(static_cast<int>(*marker));
    }
  }
  return input;
}

/// The count of the "<count> ..." header line just read: field 0, at most `max_fields` fields.
Expected<long long> section_count(TextLines& lines, std::string_view section, std::size_t max_fields,
                                  std::string_view layout) {
  if (lines.fields().size() > max_fields) {
    return lines.error(ErrorCode::ParseError, std::string(section) + " header has " +
                                                  fields_word(lines.fields().size()) +
                                                  "; expected " + std::string(layout));
  }
  return read_count(lines, 0, "number of " + std::string(section));
}

/// Reads a "<count> ..." header line of a section the file must have.
Expected<long long> read_section_header(TextLines& lines, std::string_view section,
                                        std::size_t max_fields, std::string_view layout) {
  if (!lines.next()) {
    return lines.error(ErrorCode::ParseError,
                       "file ends before the " + std::string(section) + " section (" +
                           std::string(layout) + ")");
  }
  return section_count(lines, section, max_fields, layout);
}

Expected<void> read_segments(TextLines& lines, Pslg& pslg, int first_index) {
  auto count = read_section_header(lines, "segments", 2, "<#segments> <#markers>");
  if (!count) return count.error();
  auto markers = read_marker_flag(lines, 1, "number of segment boundary markers");
  if (!markers) return markers.error();
  const std::size_t expected_fields = *markers ? 4 : 3;
  const std::size_t bound = reserve_bound(*count, lines, 2 * expected_fields);
  pslg.segments.reserve(bound);
  if (*markers) pslg.segment_markers.reserve(bound);
  const long long n = static_cast<long long>(pslg.points.size());

  for (long long s = 0; s < *count; ++s) {
    if (!lines.next()) return truncated(lines, "segments", s, *count);
    const auto& fields = lines.fields();
    if (fields.size() != expected_fields) {
      return lines.error(ErrorCode::ParseError,
                         "segment line has " + fields_word(fields.size()) + "; the header asks for " +
                             std::to_string(expected_fields) +
                             (*markers ? " (id, two endpoints, a marker)" : " (id, two endpoints)"));
    }
    auto id = lines.integer(0, "segment id");
    if (!id) return id.error();
    const long long sid = *id;
    std::array<std::uint32_t, 2> ends{};
    for (std::size_t k = 0; k < 2; ++k) {
      auto v = lines.integer(1 + k, [&] {
        return described(k == 0 ? "first endpoint of segment" : "second endpoint of segment", sid);
      });
      if (!v) return v.error();
      const long long index = *v - first_index;
      if (index < 0 || index >= n) {
        Error e = lines.error(ErrorCode::InvalidInput,
                              described("segment", sid) + " names vertex " + std::to_string(*v) +
                                  ", which does not exist " +
                                  (n == 0 ? std::string("(there are no vertices)")
                                          : "(vertices are numbered " + std::to_string(first_index) +
                                                ".." + std::to_string(first_index + n - 1) + ")"));
        e.entity_ids.push_back(static_cast<std::uint32_t>(s));
        return e;
      }
      ends[k] = static_cast<std::uint32_t>(index);
    }
    if (ends[0] == ends[1]) {
      Error e = lines.error(ErrorCode::DegenerateInput,
                            described("segment", sid) + " joins vertex " + std::to_string(ends[0] + first_index) + " to itself");
      e.entity_ids.push_back(static_cast<std::uint32_t>(s));
      return e;
    }
    pslg.segments.push_back(ends);
    if (*markers) {
      auto marker = lines.integer(3, [&] { return described("boundary marker of segment", sid); });
      if (!marker) return marker.error();
      if (*marker < std::numeric_limits<int>::min() || *marker > std::numeric_limits<int>::max()) {
        return lines.error(ErrorCode::InvalidInput, described("boundary marker of segment", sid) + " is out of range");
      }
      pslg.segment_markers.push_back(static_cast<int>(*marker));
    }
  }
  return {};
}

/// The hole section. A file that ends right after the segments has no holes (CGAL writes
/// such files; Triangle itself would refuse them).
Expected<void> read_holes(TextLines& lines, Pslg& pslg) {
  if (!lines.next()) return {};
  auto count = section_count(lines, "holes", 1, "<#holes>");
  if (!count) return count.error();
  pslg.holes.reserve(reserve_bound(*count, lines, 6));
  for (long long h = 0; h < *count; ++h) {
    if (!lines.next()) return truncated(lines, "holes", h, *count);
    if (lines.fields().size() != 3) {
      return lines.error(ErrorCode::ParseError, "hole line has " + fields_word(lines.fields().size()) +
                                                    "; expected 3 (id, x, y)");
    }
    const std::string label = "hole " + std::string(lines.fields()[0]);
    auto x = lines.real(1, "x coordinate of " + label);
    if (!x) return x.error();
    auto y = lines.real(2, "y coordinate of " + label);
    if (!y) return y.error();
    pslg.holes.push_back({*x, *y});
  }
  return {};
}

/// The optional regional attributes / area constraints section.
Expected<void> read_regions(TextLines& lines, Pslg& pslg) {
  if (!lines.next()) return {};
  auto count = section_count(lines, "regions", 1, "<#regions>");
  if (!count) return count.error();
  pslg.regions.reserve(reserve_bound(*count, lines, 8));
  for (long long r = 0; r < *count; ++r) {
    if (!lines.next()) return truncated(lines, "regions", r, *count);
    const std::size_t nf = lines.fields().size();
    if (nf != 4 && nf != 5) {
      return lines.error(ErrorCode::ParseError, "region line has " + fields_word(nf) +
                                                    "; expected 5 (id, x, y, attribute, max area)");
    }
    const std::string label = "region " + std::string(lines.fields()[0]);
    Pslg::Region region;
    auto x = lines.real(1, "x coordinate of " + label);
    if (!x) return x.error();
    auto y = lines.real(2, "y coordinate of " + label);
    if (!y) return y.error();
    auto attribute = lines.real(3, "attribute of " + label);
    if (!attribute) return attribute.error();
    region.point = {*x, *y};
    region.attribute = *attribute;
    region.max_area = *attribute;
    if (nf == 5) {
      auto area = lines.real(4, "maximum area of " + label);
      if (!area) return area.error();
      region.max_area = *area;
    }
    pslg.regions.push_back(region);
  }
  return {};
}

Error unexpected_trailer(const TextLines& lines, std::string_view after) {
  return lines.error(ErrorCode::ParseError,
                     "unexpected data after the " + std::string(after) + ": '" +
                         std::string(lines.fields()[0].substr(0, 40)) + "'");
}

std::string lower_extension(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

}  // namespace

Expected<TriangleInput> parse_triangle_node(std::string_view text, std::string_view file_name) {
  TextLines lines(text, file_name);
  if (!lines.next()) {
    return make_error(ErrorCode::ParseError,
                      "no data (expected the header <#vertices> <dimension> <#attributes> <#markers>)",
                      std::string(file_name), lines.line());
  }
  auto count = read_count(lines, 0, "number of vertices");
  if (!count) return count.error();
  auto input = read_vertex_section(lines, *count);
  if (!input) return input;
  if (lines.next()) return unexpected_trailer(lines, "vertex list");
  return input;
}

Expected<TriangleInput> parse_triangle_poly(std::string_view text, std::string_view file_name,
                                            const std::function<Expected<TriangleInput>()>& read_node) {
  TextLines lines(text, file_name);
  if (!lines.next()) {
    return make_error(ErrorCode::ParseError,
                      "no data (expected the header <#vertices> <dimension> <#attributes> <#markers>)",
                      std::string(file_name), lines.line());
  }
  auto count = read_count(lines, 0, "number of vertices");
  if (!count) return count.error();
  auto input = read_vertex_section(lines, *count);
  if (!input) return input;
  if (*count == 0) {
    if (!read_node) {
      return lines.error(ErrorCode::InvalidInput,
                         "the .poly lists no vertices and no .node file is available to supply them");
    }
    auto node = read_node();
    if (!node) return node;
    input = std::move(node);
  }
  input->has_segment_section = true;
  if (auto r = read_segments(lines, input->pslg, input->first_index); !r) return r.error();
  if (auto r = read_holes(lines, input->pslg); !r) return r.error();
  if (auto r = read_regions(lines, input->pslg); !r) return r.error();
  if (lines.next()) return unexpected_trailer(lines, "region list");
  return input;
}

Expected<TriangleInput> read_triangle_node(const std::filesystem::path& path) {
  auto text = read_text_file(path);
  if (!text) return text.error();
  return parse_triangle_node(*text, path.string());
}

Expected<TriangleInput> read_triangle_poly(const std::filesystem::path& path) {
  auto text = read_text_file(path);
  if (!text) return text.error();
  std::filesystem::path node_path = path;
  node_path.replace_extension(".node");
  return parse_triangle_poly(*text, path.string(), [&]() -> Expected<TriangleInput> {
    auto node = read_triangle_node(node_path);
    if (!node && node.error().code == ErrorCode::IoError) {
      Error e = node.error();
      e.message += " (the .poly lists no vertices, so they are read from the sibling .node file)";
      return e;
    }
    return node;
  });
}

Expected<TriangleInput> read_triangle_input(const std::filesystem::path& path) {
  const std::string ext = lower_extension(path);
  if (ext == ".poly") return read_triangle_poly(path);
  if (ext == ".node") return read_triangle_node(path);
  std::string message = path.string();
  message.insert(0, 1, '\'');
  message.append("' is neither a .poly nor a .node file");
  return make_error(ErrorCode::Unsupported, std::move(message), path.string(), 0);
}

}  // namespace delmesh
