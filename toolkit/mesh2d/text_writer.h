// Buffered text output for the mesh writers: numbers formatted with std::to_chars (doubles
// in the shortest form that reads back to the same value, so a written mesh re-reads
// bit-exactly), large writes through one buffer, and every I/O failure returned as an
// Error naming the file.
#pragma once

#include <cstdio>
#include <filesystem>
#include <string>
#include <string_view>

#include "toolkit/core/error.h"

namespace delmesh {

class TextWriter {
 public:
  TextWriter() = default;
  TextWriter(const TextWriter&) = delete;
  TextWriter& operator=(const TextWriter&) = delete;
  ~TextWriter();

  /// Creates (truncates) the file.
  Expected<void> open(const std::filesystem::path& path);
  /// Flushes and closes; reports a write error that happened at any point.
  Expected<void> close();

  TextWriter& text(std::string_view s);
  TextWriter& integer(long long value);
  /// Shortest round-trip form ("0.1", "1e-05").
  TextWriter& real(double value);
  /// Fixed notation with `decimals` digits after the point (for pictures).
  TextWriter& fixed(double value, int decimals);
  TextWriter& space() { return put(' '); }
  TextWriter& newline() { return put('\n'); }

 private:
  TextWriter& put(char c);
  void flush_buffer();

  std::FILE* file_ = nullptr;
  std::string path_;
  std::string buffer_;
  bool failed_ = false;
};

}  // namespace delmesh
