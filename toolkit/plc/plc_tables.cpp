// Marker and region tables as bytes, hex strings and comment lines (see plc_tables.h).
#include "toolkit/plc/plc_tables.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <optional>
#include <set>

namespace delmesh {

std::array<std::uint8_t, 3> color_bytes(const Plc::Color& color) {
  const auto byte = [](double x) {
    const double clamped = std::isnan(x) ? 0.0 : std::clamp(x, 0.0, 1.0);
    return static_cast<std::uint8_t>(std::lround(clamped * 255.0));
  };
  return {byte(color.r), byte(color.g), byte(color.b)};
}

std::string color_hex(const Plc::Color& color) {
  static constexpr char kDigits[] = "0123456789abcdef";
  std::string hex = "#";
  for (std::uint8_t b : color_bytes(color)) {
    hex += kDigits[b >> 4];
    hex += kDigits[b & 15];
  }
  return hex;
}

std::vector<std::string> label_table_lines(std::string_view what, const std::map<int, std::string>& names,
                                           const std::map<int, Plc::Color>& colors) {
  std::set<int> ids;
  for (const auto& entry : names) ids.insert(entry.first);
  for (const auto& entry : colors) ids.insert(entry.first);
  std::vector<std::string> lines;
  for (int id : ids) {
    std::string line(what);
    line += ' ';
    line += std::to_string(id);
    if (const auto name = names.find(id); name != names.end()) {
      std::string text = name->second;
      std::replace_if(text.begin(), text.end(), [](char c) { return c == '"' || c == '\n' || c == '\r'; }, ' ');
      line += " name \"" + text + "\"";
    }
    if (const auto color = colors.find(id); color != colors.end()) line += " color " + color_hex(color->second);
    lines.push_back(std::move(line));
  }
  return lines;
}

namespace {

/// Removes `word` from the front of `text`; false (text unchanged) if it is not there.
bool consume(std::string_view& text, std::string_view word) {
  if (text.substr(0, word.size()) != word) return false;
  text.remove_prefix(word.size());
  return true;
}

std::optional<int> hex_digit(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return std::nullopt;
}

struct TableEntry {
  bool region = false;
  int id = 0;
  std::optional<std::string> name;
  std::optional<Plc::Color> color;
};

/// One table line after its comment prefix, or nothing if it is not one.
std::optional<TableEntry> parse_entry(std::string_view line) {
  TableEntry entry;
  if (consume(line, "region ")) {
    entry.region = true;
  } else if (!consume(line, "facet_marker ")) {
    return std::nullopt;
  }
  const auto [end, ec] = std::from_chars(line.data(), line.data() + line.size(), entry.id);
  if (ec != std::errc{} || end == line.data()) return std::nullopt;
  line.remove_prefix(static_cast<std::size_t>(end - line.data()));
  if (consume(line, " name \"")) {
    const std::size_t close = line.find('"');
    if (close == std::string_view::npos) return std::nullopt;
    entry.name = std::string(line.substr(0, close));
    line.remove_prefix(close + 1);
  }
  if (consume(line, " color #")) {
    if (line.size() < 6) return std::nullopt;
    double rgb[3];
    for (int k = 0; k < 3; ++k) {
      const auto hi = hex_digit(line[2 * k]), lo = hex_digit(line[2 * k + 1]);
      if (!hi || !lo) return std::nullopt;
      rgb[k] = (*hi * 16 + *lo) / 255.0;
    }
    entry.color = Plc::Color{rgb[0], rgb[1], rgb[2]};
    line.remove_prefix(6);
  }
  while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) line.remove_suffix(1);
  if (!line.empty() || (!entry.name && !entry.color)) return std::nullopt;
  return entry;
}

}  // namespace

void read_label_table_comments(std::string_view text, std::string_view prefix, Plc& plc) {
  while (!text.empty()) {
    const std::size_t eol = text.find('\n');
    std::string_view line = text.substr(0, eol);
    text.remove_prefix(eol == std::string_view::npos ? text.size() : eol + 1);
    if (!consume(line, prefix) || !consume(line, " ")) continue;
    const std::optional<TableEntry> entry = parse_entry(line);
    if (!entry) continue;
    if (entry->name) (entry->region ? plc.region_names : plc.facet_marker_names)[entry->id] = *entry->name;
    if (entry->color) (entry->region ? plc.region_colors : plc.facet_marker_colors)[entry->id] = *entry->color;
  }
}

}  // namespace delmesh
