// TetGen .node reading and .node/.ele writing (see tet_node_io.h).
#include "toolkit/tetmesh/tet_node_io.h"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>
#include <string_view>

namespace delmesh {

namespace {

struct FileCloser {
  void operator()(std::FILE* f) const { std::fclose(f); }
};
using File = std::unique_ptr<std::FILE, FileCloser>;

Expected<std::string> slurp(const std::filesystem::path& path) {
  File f(std::fopen(path.c_str(), "rb"));
  if (!f) return make_error(ErrorCode::IoError, "cannot open '" + path.string() + "' for reading");
  std::string data;
  char buffer[1 << 16];
  std::size_t got;
  while ((got = std::fread(buffer, 1, sizeof buffer, f.get())) > 0) data.append(buffer, got);
  if (std::ferror(f.get())) return make_error(ErrorCode::IoError, "cannot read '" + path.string() + "'");
  return data;
}

// Splits the file into meaningful lines: comments stripped, blank lines skipped.
class LineReader {
 public:
  explicit LineReader(std::string_view text) : text_(text) {}

  /// Next non-empty line (comment removed); false at end of file.
  bool next(std::string_view& line) {
    while (pos_ < text_.size()) {
      const std::size_t end = std::min(text_.find('\n', pos_), text_.size());
      std::string_view raw = text_.substr(pos_, end - pos_);
      pos_ = end + 1;
      ++line_number_;
      const std::size_t hash = raw.find('#');
      if (hash != std::string_view::npos) raw = raw.substr(0, hash);
      std::size_t k = 0;
      while (k < raw.size() && is_space(raw[k])) ++k;
      if (k == raw.size()) continue;
      line = raw.substr(k);
      return true;
    }
    return false;
  }
  std::size_t line_number() const { return line_number_; }

  static bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == ','; }

 private:
  std::string_view text_;
  std::size_t pos_ = 0;
  std::size_t line_number_ = 0;
};

// Whitespace-separated fields of one line.
class Fields {
 public:
  explicit Fields(std::string_view line) : line_(line) {}
  bool next(std::string_view& field) {
    while (pos_ < line_.size() && LineReader::is_space(line_[pos_])) ++pos_;
    if (pos_ >= line_.size()) return false;
    const std::size_t start = pos_;
    while (pos_ < line_.size() && !LineReader::is_space(line_[pos_])) ++pos_;
    field = line_.substr(start, pos_ - start);
    return true;
  }

 private:
  std::string_view line_;
  std::size_t pos_ = 0;
};

bool parse_long(std::string_view s, long long& out) {
  const char* end = s.data() + s.size();
  auto [ptr, ec] = std::from_chars(s.data(), end, out);
  return ec == std::errc() && ptr == end;
}

bool parse_real(std::string_view s, double& out) {
  if (!s.empty() && s[0] == '+') s.remove_prefix(1);
  const char* end = s.data() + s.size();
  auto [ptr, ec] = std::from_chars(s.data(), end, out);
  return ec == std::errc() && ptr == end && std::isfinite(out);
}

// Buffered writer: a fixed chunk filled through a raw pointer (one capacity check per
// line), to_chars for numbers. Writing millions of tets must not cost more than
// computing them.
class Writer {
 public:
  explicit Writer(std::FILE* f) : f_(f), buffer_(new char[kChunk + kLineMax]) {}
  void text(std::string_view s) {
    std::memcpy(buffer_.get() + size_, s.data(), s.size());
    size_ += s.size();
  }
  void integer(unsigned long long x) {
    char* at = buffer_.get() + size_;
    size_ += static_cast<std::size_t>(std::to_chars(at, at + 24, x).ptr - at);
  }
  void real(double x) {
    char* at = buffer_.get() + size_;  // shortest round-trip form
    size_ += static_cast<std::size_t>(std::to_chars(at, at + 40, x).ptr - at);
  }
  /// Ends a line (at most kLineMax characters) and flushes a full chunk.
  void end_line() {
    buffer_[size_++] = '\n';
    if (size_ >= kChunk) flush();
  }
  bool finish() {
    flush();
    return ok_ && std::fflush(f_) == 0;
  }

 private:
  static constexpr std::size_t kChunk = 1 << 20;
  static constexpr std::size_t kLineMax = 512;
  void flush() {
    if (size_ > 0 && std::fwrite(buffer_.get(), 1, size_, f_) != size_) ok_ = false;
    size_ = 0;
  }
  std::FILE* f_;
  std::unique_ptr<char[]> buffer_;
  std::size_t size_ = 0;
  bool ok_ = true;
};

}  // namespace

Expected<NodeFile> read_node_file(const std::filesystem::path& path) {
  auto text = slurp(path);
  if (!text) return text.error();
  const std::string file = path.string();
  LineReader lines(*text);
  std::string_view line;
  auto fail = [&](const std::string& message) {
    return make_error(ErrorCode::ParseError, message, file, lines.line_number());
  };
  if (!lines.next(line)) return fail("empty .node file: expected '<#points> 3 <#attributes> <#markers>'");
  long long header[4] = {0, 3, 0, 0};
  {
    Fields fields(line);
    std::string_view field;
    int count = 0;
    while (fields.next(field)) {
      if (count >= 4) return fail("too many fields in the .node header");
      if (!parse_long(field, header[count]) || header[count] < 0) {
        return fail("invalid number '" + std::string(field) + "' in the .node header");
      }
      ++count;
    }
    if (header[1] != 3) {
      return fail("dimension " + std::to_string(header[1]) + " in the .node header: expected 3");
    }
    if (header[3] > 1) return fail("boundary marker count must be 0 or 1");
    if (header[0] >= static_cast<long long>(kNone) - 2) return fail("too many points");
  }
  const auto n = static_cast<std::size_t>(header[0]);
  const auto extra = static_cast<std::size_t>(header[2] + header[3]);
  NodeFile result;
  result.points.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    if (!lines.next(line)) {
      return make_error(ErrorCode::ParseError,
                        "the header announces " + std::to_string(n) + " points but the file ends after " +
                            std::to_string(i),
                        file, lines.line_number());
    }
    Fields fields(line);
    std::string_view field;
    long long index = 0;
    if (!fields.next(field) || !parse_long(field, index)) {
      return fail("expected a point index, got '" + std::string(line.substr(0, 40)) + "'");
    }
    if (i == 0) {
      if (index != 0 && index != 1) return fail("the first point index must be 0 or 1, got " + std::to_string(index));
      result.first_index = static_cast<int>(index);
    } else if (index != static_cast<long long>(i) + result.first_index) {
      return fail("point index " + std::to_string(index) + " out of sequence: expected " +
                  std::to_string(i + static_cast<std::size_t>(result.first_index)));
    }
    Vec3 p;
    for (int k = 0; k < 3; ++k) {
      if (!fields.next(field)) return fail("point " + std::to_string(index) + ": expected x y z");
      if (!parse_real(field, p[k])) {
        return fail("point " + std::to_string(index) + ": invalid coordinate '" + std::string(field) + "'");
      }
    }
    std::size_t more = 0;
    while (fields.next(field)) ++more;
    if (more > extra) return fail("point " + std::to_string(index) + ": too many fields");
    result.points.push_back(p);
  }
  return result;
}

Expected<void> write_node_file(const std::filesystem::path& path, std::span<const Vec3> points) {
  File f(std::fopen(path.c_str(), "wb"));
  if (!f) return make_error(ErrorCode::IoError, "cannot open '" + path.string() + "' for writing");
  Writer w(f.get());
  w.integer(points.size());
  w.text(" 3 0 0");
  w.end_line();
  for (std::size_t i = 0; i < points.size(); ++i) {
    w.integer(i + 1);
    for (int k = 0; k < 3; ++k) {
      w.text(" ");
      w.real(points[i][k]);
    }
    w.end_line();
  }
  if (!w.finish()) return make_error(ErrorCode::IoError, "cannot write '" + path.string() + "'");
  return {};
}

Expected<void> write_ele_file(const std::filesystem::path& path, const TetMesh& mesh, int first_index) {
  File f(std::fopen(path.c_str(), "wb"));
  if (!f) return make_error(ErrorCode::IoError, "cannot open '" + path.string() + "' for writing");
  Writer w(f.get());
  w.integer(mesh.num_finite_tets());
  w.text(" 4 0");
  w.end_line();
  unsigned long long index = 1;
  const long long shift = first_index - 1;
  for (std::uint32_t t = 0; t < mesh.tet_slots(); ++t) {
    if (mesh.is_dead(t) || mesh.is_infinite(t)) continue;
    w.integer(index++);
    for (const std::uint32_t v : mesh.tet(t).v) {
      w.text(" ");
      w.integer(static_cast<unsigned long long>(static_cast<long long>(v) + shift));
    }
    w.end_line();
  }
  if (!w.finish()) return make_error(ErrorCode::IoError, "cannot write '" + path.string() + "'");
  return {};
}

}  // namespace delmesh
