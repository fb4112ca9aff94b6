// Buffered text output for mesh files: numbers are formatted with std::to_chars (the
// shortest representation that reads back to the same double, locale-independent), and
// write errors are reported as delmesh::Error values naming the file.
#pragma once

#include <charconv>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "toolkit/core/error.h"

namespace delmesh {

class TextWriter {
 public:
  /// Opens `path` for writing (truncating). Check ok() / finish() for errors.
  explicit TextWriter(const std::filesystem::path& path);
  ~TextWriter();
  TextWriter(const TextWriter&) = delete;
  TextWriter& operator=(const TextWriter&) = delete;

  bool ok() const { return file_ != nullptr && !failed_; }

  TextWriter& put(std::string_view text);
  TextWriter& put(char c) {
    if (used_ == buffer_.size()) flush_buffer();
    buffer_[used_++] = c;
    return *this;
  }
  TextWriter& put(double value);
  TextWriter& put(std::int64_t value);
  TextWriter& put(int value) { return put(static_cast<std::int64_t>(value)); }
  TextWriter& put(std::uint32_t value) { return put(static_cast<std::int64_t>(value)); }
  TextWriter& put(std::uint64_t value);

  /// Writes values separated by single spaces, then a newline.
  template <class... Ts>
  TextWriter& line(const Ts&... values) {
    bool first = true;
    ((first ? (first = false, put(values)) : (put(' '), put(values))), ...);
    return put('\n');
  }

  /// Flushes and closes; an IoError naming the file if anything failed.
  Expected<void> finish();

 private:
  void flush_buffer();
  /// Formats a number with std::to_chars straight into the buffer (no intermediate copy):
  /// the longest a double or a 64-bit integer takes is 24 characters.
  template <class Number>
  TextWriter& put_number(Number value) {
    constexpr std::size_t kLongest = 32;
    if (buffer_.size() - used_ < kLongest) flush_buffer();
    const auto result = std::to_chars(buffer_.data() + used_, buffer_.data() + buffer_.size(), value);
    used_ = static_cast<std::size_t>(result.ptr - buffer_.data());
    return *this;
  }

  std::string path_;
  std::FILE* file_ = nullptr;
  int open_errno_ = 0;
  bool failed_ = false;
  std::vector<char> buffer_;
  std::size_t used_ = 0;
};

}  // namespace delmesh
