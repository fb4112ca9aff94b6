// Marker and region tables (names and colours of CAD faces and solids, Plc::
// facet_marker_names / facet_marker_colors / region_names / region_colors and the same
// tables of TetraMesh) in the forms file writers need: colours as bytes or "#rrggbb",
// and a table as plain text lines that formats without a field for names or colours
// carry as comments.
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "toolkit/plc/plc.h"

namespace delmesh {

/// Components clamped to [0, 1] and rounded to the nearest of 256 levels.
std::array<std::uint8_t, 3> color_bytes(const Plc::Color& color);

/// "#rrggbb" (lower-case hexadecimal of color_bytes).
std::string color_hex(const Plc::Color& color);

/// One line per id that has a name or a colour, in increasing id order:
/// `<what> <id> name "<name>" color #rrggbb` (the name or the colour part left out when
/// absent; a double quote or line break in a name becomes a space).
std::vector<std::string> label_table_lines(std::string_view what, const std::map<int, std::string>& names,
                                           const std::map<int, Plc::Color>& colors);

}  // namespace delmesh
