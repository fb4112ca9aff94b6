// Helpers shared by the command-line verbs: a stderr log sink, number parsing with clear
// messages, and timing.
#pragma once

#include <chrono>
#include <optional>
#include <string>
#include <string_view>

#include "toolkit/core/error.h"
#include "toolkit/core/log.h"

namespace delmesh::cli {

/// Writes progress and warnings to stderr; Info and Debug only when verbose.
class StderrLogSink final : public LogSink {
 public:
  explicit StderrLogSink(bool quiet, bool verbose = false) : quiet_(quiet), verbose_(verbose) {}
  void write(LogLevel level, std::string_view message) override;

 private:
  bool quiet_;
  bool verbose_;
};

/// Parses a finite double; nullopt if `text` is not entirely a number.
std::optional<double> parse_double(std::string_view text);
/// Parses a non-negative integer; nullopt on anything else.
std::optional<unsigned long long> parse_count(std::string_view text);

/// Prints "delmesh <verb>: <message>" to stderr and returns exit code 2.
int usage_error(std::string_view verb, std::string_view message);
/// Prints "delmesh: <error.describe()>" to stderr and returns exit code 1.
int report_error(const Error& error);

/// Lower-case extension including the dot (".node"), or "" if none.
std::string extension_of(std::string_view path);
/// `path` without its extension ("out/a.node" -> "out/a").
std::string strip_extension(std::string_view path);

/// Wall-clock stopwatch in seconds.
class Stopwatch {
 public:
  Stopwatch() : start_(std::chrono::steady_clock::now()) {}
  double seconds() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }

 private:
  std::chrono::steady_clock::time_point start_;
};

}  // namespace delmesh::cli
