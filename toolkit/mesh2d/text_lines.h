// Line-and-token scanning for the plain-text mesh formats (Triangle .node/.poly and the
// like): comments from '#' to the end of the line, blank lines skipped, fields separated by
// blanks, every number parsed completely (a token that is only partly a number is refused).
// Errors name the file and the 1-based line.
#pragma once

#include <cstddef>
#include <concepts>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "toolkit/core/error.h"

namespace delmesh {

/// Reads a whole file into memory; an IoError naming the file when it cannot be read.
Expected<std::string> read_text_file(const std::filesystem::path& path);

/// Parses a whole token as a finite double ("+1.5e3", "-.5"); false on anything else,
/// including NaN, infinities and out-of-range values.
bool parse_real_token(std::string_view token, double& value);
/// Parses a whole token as a decimal integer with an optional sign.
bool parse_integer_token(std::string_view token, long long& value);

/// Walks the data lines of a text (lines that hold something besides blanks and comments)
/// and splits each into fields.
class TextLines {
 public:
  /// At most this many fields of a line are kept; a longer line shows kMaxFields + 1
  /// fields, which no format accepts (so a huge line costs no memory beyond that).
  static constexpr std::size_t kMaxFields = 1 << 16;

  TextLines(std::string_view text, std::string_view file_name);

  /// Moves to the next data line. False at the end of the text.
  bool next();
  /// 1-based number of the current line (of the last line when the text is exhausted).
  std::size_t line() const { return line_; }
  const std::vector<std::string_view>& fields() const { return fields_; }
  /// Bytes not yet scanned (an upper bound for reserving storage by content, not by count).
  std::size_t remaining_bytes() const { return text_.size() - pos_; }
  const std::string& file_name() const { return file_; }

  /// An error located at the current line.
  Error error(ErrorCode code, std::string message) const;

  /// Field `i` as a finite double, or an error naming `what` (e.g. "x coordinate of vertex 3").
  Expected<double> real(std::size_t i, std::string_view what) const;
  /// Field `i` as an integer, or an error naming `what`.
  Expected<long long> integer(std::size_t i, std::string_view what) const;

  /// As above, with the description built by `describe()` only when the field is bad, so
  /// that the per-line fast path allocates nothing.
  template <class Describe>
    requires std::invocable<Describe>
  Expected<double> real(std::size_t i, Describe&& describe) const {
    double value = 0;
    if (i < fields_.size() && parse_real_token(fields_[i], value)) return value;
    return real(i, std::string_view(describe()));
  }
  template <class Describe>
    requires std::invocable<Describe>
  Expected<long long> integer(std::size_t i, Describe&& describe) const {
    long long value = 0;
    if (i < fields_.size() && parse_integer_token(fields_[i], value)) return value;
    return integer(i, std::string_view(describe()));
  }

 private:
  std::string_view text_;
  std::string file_;
  std::size_t pos_ = 0;
  std::size_t line_ = 0;
  std::vector<std::string_view> fields_;
};

}  // namespace delmesh
