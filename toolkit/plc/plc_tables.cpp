// Marker and region tables as bytes, hex strings and comment lines (see plc_tables.h).
#include "toolkit/plc/plc_tables.h"

#include <algorithm>
#include <cmath>
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

}  // namespace delmesh
