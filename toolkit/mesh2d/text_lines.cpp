// Line-and-token scanning for plain-text mesh formats (see text_lines.h).
#include "toolkit/mesh2d/text_lines.h"

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>
#include <system_error>

namespace delmesh {

Expected<std::string> read_text_file(const std::filesystem::path& path) {
  const std::string name = path.string();
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) {
    return make_error(ErrorCode::IoError, "cannot read: it is a directory", name, 0);
  }
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> file(std::fopen(name.c_str(), "rb"), &std::fclose);
  if (!file) {
    return make_error(ErrorCode::IoError,
                      std::string("cannot open the file: ") + std::strerror(errno), name, 0);
  }
  std::string text;
  if (const auto size = std::filesystem::file_size(path, ec); !ec) text.reserve(size);
  char buffer[1 << 16];
  for (;;) {
    const std::size_t n = std::fread(buffer, 1, sizeof buffer, file.get());
    text.append(buffer, n);
    if (n < sizeof buffer) break;
  }
  if (std::ferror(file.get())) {
    return make_error(ErrorCode::IoError, "error while reading the file", name, 0);
  }
  return text;
}

TextLines::TextLines(std::string_view text, std::string_view file_name)
    : text_(text), file_(file_name) {}

bool TextLines::next() {
  while (pos_ < text_.size()) {
    const std::size_t end = std::min(text_.find('\n', pos_), text_.size());
    std::string_view content = text_.substr(pos_, end - pos_);
    pos_ = end + (end < text_.size() ? 1 : 0);
    ++line_;
    if (const auto hash = content.find('#'); hash != std::string_view::npos) {
      content = content.substr(0, hash);
    }
    fields_.clear();
    std::size_t i = 0;
    while (i < content.size() && fields_.size() <= kMaxFields) {
      while (i < content.size() && (content[i] == ' ' || content[i] == '\t' || content[i] == '\r' ||
                                    content[i] == '\v' || content[i] == '\f')) {
        ++i;
      }
      const std::size_t start = i;
      while (i < content.size() && !(content[i] == ' ' || content[i] == '\t' || content[i] == '\r' ||
                                     content[i] == '\v' || content[i] == '\f')) {
        ++i;
      }
      if (i > start) fields_.push_back(content.substr(start, i - start));
    }
    if (!fields_.empty()) return true;
  }
  fields_.clear();
  return false;
}

Error TextLines::error(ErrorCode code, std::string message) const {
  Error e = make_error(code, std::move(message), file_, line_);
  return e;
}

namespace {

std::string quoted(std::string_view token) {
  constexpr std::size_t kMaxShown = 40;
  std::string out = "'";
  for (const char c : token.substr(0, kMaxShown)) {
    const auto u = static_cast<unsigned char>(c);
    out.push_back(u >= 0x20 && u < 0x7f ? c : '?');
  }
  if (token.size() > kMaxShown) out += "...";
  out.push_back('\'');
  return out;
}

std::string_view without_plus(std::string_view token) {
  if (token.size() > 1 && token[0] == '+' && token[1] != '-' && token[1] != '+') {
    return token.substr(1);
  }
  return token;
}

}  // namespace

bool parse_real_token(std::string_view token, double& value) {
  token = without_plus(token);
  if (token.empty()) return false;
  const char* end = token.data() + token.size();
  const auto [ptr, ec] = std::from_chars(token.data(), end, value);
  return ec == std::errc() && ptr == end && std::isfinite(value);
}

bool parse_integer_token(std::string_view token, long long& value) {
  token = without_plus(token);
  if (token.empty()) return false;
  const char* end = token.data() + token.size();
  const auto [ptr, ec] = std::from_chars(token.data(), end, value);
  return ec == std::errc() && ptr == end;
}

Expected<double> TextLines::real(std::size_t i, std::string_view what) const {
  double value = 0;
  if (i >= fields_.size()) {
    return error(ErrorCode::ParseError, "missing " + std::string(what));
  }
  if (!parse_real_token(fields_[i], value)) {
    double probe = 0;
    const std::string_view token = without_plus(fields_[i]);
    const auto [ptr, ec] = std::from_chars(token.data(), token.data() + token.size(), probe);
    const bool nonfinite = ptr == token.data() + token.size() &&
                           (ec == std::errc::result_out_of_range || (ec == std::errc() && !std::isfinite(probe)));
    return error(nonfinite ? ErrorCode::InvalidInput : ErrorCode::ParseError,
                 std::string(what) + " is " + quoted(fields_[i]) +
                     (nonfinite ? ", not a finite number" : ", not a number"));
  }
  return value;
}

Expected<long long> TextLines::integer(std::size_t i, std::string_view what) const {
  long long value = 0;
  if (i >= fields_.size()) {
    return error(ErrorCode::ParseError, "missing " + std::string(what));
  }
  if (!parse_integer_token(fields_[i], value)) {
    return error(ErrorCode::ParseError, std::string(what) + " is " + quoted(fields_[i]) +
                                            ", not an integer in range");
  }
  return value;
}

}  // namespace delmesh
