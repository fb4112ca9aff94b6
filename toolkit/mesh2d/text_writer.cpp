// Buffered text output (see text_writer.h).
#include "toolkit/mesh2d/text_writer.h"

#include <cerrno>
#include <charconv>
#include <cstring>

namespace delmesh {
namespace {
constexpr std::size_t kBufferSize = 1 << 20;
}  // namespace

TextWriter::~TextWriter() {
  if (file_) std::fclose(file_);
}

Expected<void> TextWriter::open(const std::filesystem::path& path) {
  path_ = path.string();
  file_ = std::fopen(path_.c_str(), "wb");
  if (!file_) {
    return make_error(ErrorCode::IoError, "cannot create '" + path_ + "': " + std::strerror(errno),
                      path_, 0);
  }
  buffer_.reserve(kBufferSize + 64);
  failed_ = false;
  return {};
}

Expected<void> TextWriter::close() {
  if (!file_) return make_error(ErrorCode::IoError, "'" + path_ + "' is not open", path_, 0);
  flush_buffer();
  const bool close_failed = std::fclose(file_) != 0;
  file_ = nullptr;
  if (failed_ || close_failed) {
    return make_error(ErrorCode::IoError, "error while writing '" + path_ + "' (disk full?)", path_, 0);
  }
  return {};
}

void TextWriter::flush_buffer() {
  if (file_ && !buffer_.empty()) {
    if (std::fwrite(buffer_.data(), 1, buffer_.size(), file_) != buffer_.size()) failed_ = true;
  }
  buffer_.clear();
}

TextWriter& TextWriter::put(char c) {
  buffer_.push_back(c);
  if (buffer_.size() >= kBufferSize) flush_buffer();
  return *this;
}

TextWriter& TextWriter::text(std::string_view s) {
  buffer_.append(s);
  if (buffer_.size() >= kBufferSize) flush_buffer();
  return *this;
}

TextWriter& TextWriter::integer(long long value) {
  char digits[24];
  const auto result = std::to_chars(digits, digits + sizeof digits, value);
  return text(std::string_view(digits, static_cast<std::size_t>(result.ptr - digits)));
}

TextWriter& TextWriter::real(double value) {
  char digits[32];
  const auto result = std::to_chars(digits, digits + sizeof digits, value);
  return text(std::string_view(digits, static_cast<std::size_t>(result.ptr - digits)));
}

TextWriter& TextWriter::fixed(double value, int decimals) {
  char digits[64];
  const auto result =
      std::to_chars(digits, digits + sizeof digits, value, std::chars_format::fixed, decimals);
  if (result.ec != std::errc()) return real(value);
  return text(std::string_view(digits, static_cast<std::size_t>(result.ptr - digits)));
}

}  // namespace delmesh
