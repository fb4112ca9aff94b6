// Buffered text output (see text_writer.h).
#include "toolkit/io/text_writer.h"

#include <cerrno>
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

TextWriter& TextWriter::put(double value) { return put_number(value); }

TextWriter& TextWriter::put(std::int64_t value) { return put_number(value); }

TextWriter& TextWriter::put(std::uint64_t value) { return put_number(value); }

Expected<void> TextWriter::finish() {
  flush_buffer();
  if (!file_) return make_error(ErrorCode::IoError, "cannot open " + path_ + " for writing: " + std::strerror(open_errno_));
  const bool close_failed = std::fclose(file_) != 0;
  file_ = nullptr;
  if (failed_ || close_failed) return make_error(ErrorCode::IoError, "error while writing " + path_);
  return {};
}

}  // namespace delmesh
