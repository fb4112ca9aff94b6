// Buffered text output (see text_writer.h).
#include "toolkit/io/text_writer.h"

#include <cerrno>
#include <charconv>
#include <cstring>

namespace delmesh {

namespace {
constexpr std::size_t kBufferSize = 1 << 16;
}

TextWriter::TextWriter(const std::filesystem::path& path)
    : path_(path.string()), file_(std::fopen(path_.c_str(), "wb")), buffer_(kBufferSize) {
  if (!file_) {
    open_errno_ = errno;
    failed_ = true;
  }
}

TextWriter::~TextWriter() {
  if (file_) std::fclose(file_);
}

void TextWriter::flush_buffer() {
  if (used_ == 0) return;
  if (file_ && std::fwrite(buffer_.data(), 1, used_, file_) != used_) failed_ = true;
  used_ = 0;
}

TextWriter& TextWriter::put(std::string_view text) {
  if (text.size() > buffer_.size() - used_) {
    flush_buffer();
    if (text.size() > buffer_.size()) {
      if (file_ && std::fwrite(text.data(), 1, text.size(), file_) != text.size()) failed_ = true;
      return *this;
    }
  }
  std::memcpy(buffer_.data() + used_, text.data(), text.size());
  used_ += text.size();
  return *this;
}

TextWriter& TextWriter::put(char c) {
  if (used_ == buffer_.size()) flush_buffer();
  buffer_[used_++] = c;
  return *this;
}

TextWriter& TextWriter::put(double value) {
  char text[32];
  const auto result = std::to_chars(text, text + sizeof text, value);
  return put(std::string_view(text, static_cast<std::size_t>(result.ptr - text)));
}

TextWriter& TextWriter::put(std::int64_t value) {
  char text[24];
  const auto result = std::to_chars(text, text + sizeof text, value);
  return put(std::string_view(text, static_cast<std::size_t>(result.ptr - text)));
}

TextWriter& TextWriter::put(std::uint64_t value) {
  char text[24];
  const auto result = std::to_chars(text, text + sizeof text, value);
  return put(std::string_view(text, static_cast<std::size_t>(result.ptr - text)));
}

Expected<void> TextWriter::finish() {
  flush_buffer();
  if (!file_) return make_error(ErrorCode::IoError, "cannot open " + path_ + " for writing: " + std::strerror(open_errno_));
  const bool close_failed = std::fclose(file_) != 0;
  file_ = nullptr;
  if (failed_ || close_failed) return make_error(ErrorCode::IoError, "error while writing " + path_);
  return {};
}

}  // namespace delmesh
