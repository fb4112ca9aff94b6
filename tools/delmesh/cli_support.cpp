// Shared command-line helpers (see cli_support.h).
#include "tools/delmesh/cli_support.h"

#include <cctype>
#include <charconv>
#include <cmath>
#include <iostream>

namespace delmesh::cli {

void StderrLogSink::write(LogLevel level, std::string_view message) {
  switch (level) {
    case LogLevel::Warning: std::cerr << "warning: " << message << '\n'; break;
    case LogLevel::Progress:
      if (!quiet_) std::cerr << message << '\n';
      break;
    case LogLevel::Info:
      if (!quiet_ && verbose_) std::cerr << message << '\n';
      break;
    case LogLevel::Debug:
      if (verbose_) std::cerr << message << '\n';
      break;
  }
}

std::optional<double> parse_double(std::string_view text) {
  double value = 0;
  const char* end = text.data() + text.size();
  auto [ptr, ec] = std::from_chars(text.data(), end, value);
  if (ec != std::errc() || ptr != end || !std::isfinite(value)) return std::nullopt;
  return value;
}

std::optional<unsigned long long> parse_count(std::string_view text) {
  unsigned long long value = 0;
  const char* end = text.data() + text.size();
  auto [ptr, ec] = std::from_chars(text.data(), end, value);
  if (ec != std::errc() || ptr != end) return std::nullopt;
  return value;
}

int usage_error(std::string_view verb, std::string_view message) {
  std::cerr << "delmesh " << verb << ": " << message << "\n(see 'delmesh " << verb
            << " --help')\n";
  return 2;
}

int report_error(const Error& error) {
  std::cerr << "delmesh: " << error.describe() << '\n';
  return 1;
}

std::string extension_of(std::string_view path) {
  const auto slash = path.find_last_of('/');
  const auto dot = path.find_last_of('.');
  if (dot == std::string_view::npos || (slash != std::string_view::npos && dot < slash)) return {};
  std::string ext(path.substr(dot));
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

std::string strip_extension(std::string_view path) {
  const std::string ext = extension_of(path);
  return std::string(path.substr(0, path.size() - ext.size()));
}

}  // namespace delmesh::cli
