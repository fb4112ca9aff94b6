// TetGen switch parsing (see tetgen_switches.h): a left-to-right scan of letters, each
// followed by at most a few '/'-separated numbers, as TetGen's parse_commandline() reads them.
#include "tools/delmesh/tetgen_switches.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <optional>
#include <vector>

#include "tools/delmesh/cli_support.h"

namespace delmesh::cli {

namespace {

bool is_digit(char c) { return c >= '0' && c <= '9'; }

/// Scans the numbers after a switch letter at `pos`: "1.414/18" or "/18" or "". Each number
/// is digits, '.', and an exponent 'e'/'E' followed by a digit or sign. Empty slots
/// ("q/18": no ratio) come back as nullopt. `pos` ends after the last consumed character.
struct Numbers {
  std::vector<std::optional<double>> values;
  std::string error;
};

Numbers scan_numbers(std::string_view text, std::size_t& pos) {
  Numbers numbers;
  auto scan_one = [&]() -> std::optional<std::string_view> {
    const std::size_t start = pos;
    while (pos < text.size()) {
      const char c = text[pos];
      if (is_digit(c) || c == '.') {
        ++pos;
      } else if ((c == 'e' || c == 'E') && pos > start && pos + 1 < text.size() &&
                 (is_digit(text[pos + 1]) || text[pos + 1] == '-' || text[pos + 1] == '+')) {
        pos += 2;
      } else {
        break;
      }
    }
    if (pos == start) return std::nullopt;
    return text.substr(start, pos - start);
  };
  bool first = true;
  while (true) {
    if (!first) {
      if (pos >= text.size() || (text[pos] != '/' && text[pos] != ',')) break;
      ++pos;
    }
    const auto token = scan_one();
    if (first && !token) {
      if (pos >= text.size() || (text[pos] != '/' && text[pos] != ',')) break;
      numbers.values.push_back(std::nullopt);
      first = false;
      continue;
    }
    first = false;
    if (!token) {
      numbers.values.push_back(std::nullopt);
      continue;
    }
    const auto value = parse_double(*token);
    if (!value) {
      numbers.error = "'" + std::string(*token) + "' is not a number";
      return numbers;
    }
    numbers.values.push_back(*value);
  }
  return numbers;
}

Error switch_error(ErrorCode code, std::string_view argument, char letter, const std::string& message) {
  return make_error(code, "TetGen switch -" + std::string(1, letter) + " in '" + std::string(argument) + "': " +
                              message);
}

std::string_view unsupported_reason(char letter) {
  switch (letter) {
    case 'Y': return "preserving the input surface (no boundary Steiner points) is not implemented";
    case 'r': return "refining an existing mesh is not implemented";
    case 'R': return "coarsening is not implemented";
    case 'o': return "quadratic tets are not implemented (use -o FILE for the output name)";
    case 'm': return "sizing from .mtr files is not implemented";
    case 'i': return "inserting extra points from .a.node is not implemented";
    case 'M': return "delmesh does not merge coplanar facets";
    case 'T': return "delmesh uses exact predicates and has no coplanarity tolerance";
    case 'X': return "exact arithmetic cannot be turned off";
    case 'd': return "self-intersections are always detected";
    case 'D': return "conforming Delaunay mode is not implemented";
    case 'w': return "weighted Delaunay is not implemented";
    case 'f': case 'e': case 'n': case 'v': case 'k': case 'J': case 'B': case 'N': case 'E': case 'F':
      return "this output option is not implemented";
    default: return {};
  }
}

}  // namespace

Expected<void> apply_tetgen_switches(std::string_view argument, TetgenSwitches& into) {
  if (argument.size() < 2 || argument[0] != '-') {
    return make_error(ErrorCode::InvalidOption, "'" + std::string(argument) + "' is not a TetGen switch string");
  }
  MeshOptions& options = into.options;
  std::size_t pos = 1;
  while (pos < argument.size()) {
    const char letter = argument[pos++];
    const std::size_t numbers_start = pos;
    const Numbers numbers = scan_numbers(argument, pos);
    if (!numbers.error.empty()) return switch_error(ErrorCode::InvalidOption, argument, letter, numbers.error);
    const auto& v = numbers.values;
    auto no_numbers = [&]() -> Expected<void> {
      if (pos != numbers_start) {
        return switch_error(ErrorCode::InvalidOption, argument, letter, "takes no number");
      }
      return {};
    };
    switch (letter) {
      case 'p':
      case 'A':
      case 'C':
      case 'Q':
      case 'V':
      case 'z':
      case 'I':
      case 'g':
      case 'c': {
        if (auto r = no_numbers(); !r) return r;
        if (letter == 'C') into.check = true;
        if (letter == 'Q') into.quiet = true;
        if (letter == 'V') into.verbose = true;
        if (letter == 'z') into.zero_based = true;
        if (letter == 'I') into.iteration_number = false;
        if (letter == 'g') into.medit = true;
        if (letter == 'c') options.keep_convex_hull = true;
        break;
      }
      case 'q': {
        if (v.size() > 2) return switch_error(ErrorCode::InvalidOption, argument, letter, "takes at most two numbers");
        options.quality = true;
        if (!v.empty() && v[0]) {
          if (!(*v[0] > 0)) {
            return switch_error(ErrorCode::InvalidOption, argument, letter, "the radius-edge bound must be positive");
          }
          options.max_radius_edge = *v[0];
        }
        if (v.size() == 2 && v[1]) {
          if (*v[1] < 0 || *v[1] >= 70.5) {
            return switch_error(ErrorCode::InvalidOption, argument, letter,
                                "the minimum dihedral angle must be in [0, 70.5) degrees");
          }
          options.min_dihedral_deg = *v[1];
        }
        break;
      }
      case 'a': {
        if (v.size() > 1) return switch_error(ErrorCode::InvalidOption, argument, letter, "takes at most one number");
        options.quality = true;
        if (v.empty() || !v[0]) {
          options.region_max_volume = true;
        } else {
          if (!(*v[0] > 0)) {
            return switch_error(ErrorCode::InvalidOption, argument, letter, "the maximum volume must be positive");
          }
          options.max_volume = *v[0];
        }
        break;
      }
      case 'O': {
        if (v.size() > 1) {
          return switch_error(ErrorCode::Unsupported, argument, letter,
                              "choosing the optimization operations is not implemented (use -O0 or -O)");
        }
        if (!v.empty() && v[0] && (*v[0] < 0 || std::floor(*v[0]) != *v[0])) {
          return switch_error(ErrorCode::InvalidOption, argument, letter, "the optimization level must be a count");
        }
        options.improve = v.empty() || !v[0] || *v[0] > 0;
        break;
      }
      case 'S': {
        if (v.size() != 1 || !v[0] || *v[0] < 0 || std::floor(*v[0]) != *v[0]) {
          return switch_error(ErrorCode::InvalidOption, argument, letter, "needs a count of Steiner points (-S1000)");
        }
        options.max_steiner_points = static_cast<long long>(*v[0]);
        break;
      }
      default: {
        const std::string_view reason = unsupported_reason(letter);
        if (!reason.empty()) return switch_error(ErrorCode::Unsupported, argument, letter, std::string(reason));
        return switch_error(ErrorCode::InvalidOption, argument, letter, "unknown switch");
      }
    }
  }
  return {};
}

Expected<TetgenSwitches> parse_tetgen_switches(std::string_view argument) {
  TetgenSwitches switches;
  if (auto r = apply_tetgen_switches(argument, switches); !r) return r.error();
  return switches;
}

std::string tetgen_output_base(std::string_view input, bool iteration_number) {
  std::string base = strip_extension(input);
  if (!iteration_number) return base;
  // "name.3" -> "name.4": an all-digit last extension is TetGen's iteration counter.
  const std::size_t dot = base.find_last_of('.');
  const std::size_t slash = base.find_last_of('/');
  if (dot != std::string::npos && dot + 1 < base.size() && (slash == std::string::npos || dot > slash)) {
    const std::string_view counter = std::string_view(base).substr(dot + 1);
    if (counter.size() < 9 && std::all_of(counter.begin(), counter.end(), is_digit)) {
      return base.substr(0, dot + 1) + std::to_string(std::stol(std::string(counter)) + 1);
    }
  }
  return base + ".1";
}

}  // namespace delmesh::cli
