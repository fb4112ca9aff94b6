// Line-oriented tokenizer for the text formats delmesh reads (TetGen files, OFF, OBJ,
// ASCII STL/PLY): splits text into lines of whitespace-separated tokens, skips comments
// ('#' to the end of the line, when enabled) and blank lines, and reads numbers with
// errors that carry file:line. Also the whole-file reader the importers share.
#pragma once

#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "toolkit/core/error.h"
#include "toolkit/core/str_cat.h"

namespace delmesh {

/// Returns early with the error of an Expected: `DELMESH_TRY(x, f());` declares x.
#define DELMESH_TRY(var, expr) \
  auto var = (expr);           \
  if (!var) return var.error();

/// The whole content of a file (IoError naming the path if it cannot be read).
inline Expected<std::string> read_text(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return make_error(ErrorCode::IoError, "cannot open '" + path.string() + "'");
  std::ostringstream buffer;
  buffer << in.rdbuf();
  if (in.bad()) return make_error(ErrorCode::IoError, "cannot read '" + path.string() + "'");
  return buffer.str();
}

/// Splits text into lines of whitespace-separated tokens, skipping comments and blank
/// lines, and reads numbers from them with file:line errors.
class LineReader {
 public:
  LineReader(std::string_view text, std::string_view file, bool hash_comments = true)
      : text_(text), file_(file), hash_comments_(hash_comments) {}

  /// Advances to the next line holding data; false at the end of the text.
  bool next() {
    tokens_.clear();
    pos_ = 0;
    while (offset_ < text_.size()) {
      std::size_t end = text_.find('\n', offset_);
      if (end == std::string_view::npos) end = text_.size();
      std::string_view line = text_.substr(offset_, end - offset_);
      offset_ = end + 1;
      ++line_;
      if (const auto hash = line.find('#'); hash_comments_ && hash != std::string_view::npos) {
        line = line.substr(0, hash);
      }
      std::size_t i = 0;
      while (i < line.size()) {
        while (i < line.size() && is_space(line[i])) ++i;
        std::size_t j = i;
        while (j < line.size() && !is_space(line[j])) ++j;
        if (j > i) tokens_.push_back(line.substr(i, j - i));
        i = j;
      }
      if (!tokens_.empty()) return true;
    }
    return false;
  }

  /// The `what` of the readers below names the value read, for error messages only: a
  /// string, or a callable returning one, called only when an error is reported (readers
  /// of long lists then build no message per value).
  template <class Label>
  static std::string label_text(const Label& what) {
    if constexpr (std::is_invocable_v<const Label&>)
      return what();
    else
      return std::string(what);
  }

  /// Moves to the next data line or fails with "expected <what>".
  template <class Label>
  Expected<void> require_line(const Label& what) {
    if (next()) return {};
    return error(std::string("unexpected end of file, expected ") + label_text(what));
  }

  std::size_t remaining() const { return tokens_.size() - pos_; }

  /// Next token of the current record; continues onto following lines when the current
  /// one is exhausted (TetGen allows long polygons to wrap).
  template <class Label>
  Expected<std::string_view> token(const Label& what, bool may_wrap) {
    if (pos_ >= tokens_.size()) {
      if (!may_wrap) return error(std::string("missing ") + label_text(what));
      const std::size_t line = line_;
      if (!next()) return error_at(std::string("unexpected end of file, expected ") + label_text(what), line);
    }
    return tokens_[pos_++];
  }

  template <class Label>
  Expected<long long> integer(const Label& what, bool may_wrap = false) {
    auto t = token(what, may_wrap);
    if (!t) return t.error();
    long long value = 0;
    const char* end = t->data() + t->size();
    auto [ptr, ec] = std::from_chars(t->data(), end, value);
    if (ec != std::errc() || ptr != end) {
      return error(std::string("expected an integer for ") + label_text(what) + cat(", found '", *t) + "'");
    }
    return value;
  }

  template <class Label>
  Expected<std::size_t> count(const Label& what) {
    auto v = integer(what);
    if (!v) return v.error();
    if (*v < 0) return error(label_text(what) + cat(" is negative (", *v) + ")");
    return static_cast<std::size_t>(*v);
  }

  template <class Label>
  Expected<double> real(const Label& what, bool may_wrap = false) {
    auto t = token(what, may_wrap);
    if (!t) return t.error();
    double value = 0;
    const char* end = t->data() + t->size();
    auto [ptr, ec] = std::from_chars(t->data(), end, value);
    if (ec != std::errc() || ptr != end || !std::isfinite(value)) {
      return error(std::string("expected a finite number for ") + label_text(what) + cat(", found '", *t) + "'");
    }
    return value;
  }

  Error error(const std::string& message) const { return error_at(message, line_); }
  Error error_at(const std::string& message, std::size_t line) const {
    return make_error(ErrorCode::ParseError, message, std::string(file_), line);
  }
  std::size_t line() const { return line_; }
  std::string_view file() const { return file_; }

 private:
  static bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

  std::string_view text_;
  std::string_view file_;
  bool hash_comments_ = true;
  std::size_t offset_ = 0;
  std::size_t line_ = 0;
  std::vector<std::string_view> tokens_;
  std::size_t pos_ = 0;
};

}  // namespace delmesh
