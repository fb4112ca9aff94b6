// Recursive-descent JSON reader for tests (see json_value.h).
#include "tests/support/json_value.h"

#include <cctype>
#include <cstdlib>

namespace delmesh::test {

namespace {

class Parser {
 public:
  explicit Parser(std::string_view text) : text_(text) {}

  std::optional<JsonValue> document(std::string* error) {
    JsonValue value;
    const bool ok = parse_value(value) && (skip_space(), pos_ == text_.size());
    if (!ok) {
      if (error) *error = "JSON syntax error at offset " + std::to_string(pos_);
      return std::nullopt;
    }
    return value;
  }

 private:
  void skip_space() {
    while (pos_ < text_.size() && std::isspace(static_cast<unsigned char>(text_[pos_]))) ++pos_;
  }
  bool eat(char c) {
    skip_space();
    if (pos_ < text_.size() && text_[pos_] == c) {
      ++pos_;
      return true;
    }
    return false;
  }
  bool literal(std::string_view word) {
    if (text_.substr(pos_, word.size()) != word) return false;
    pos_ += word.size();
    return true;
  }

  bool parse_string(std::string& out) {
    if (!eat('"')) return false;
    while (pos_ < text_.size()) {
      const char c = text_[pos_++];
      if (c == '"') return true;
      if (static_cast<unsigned char>(c) < 0x20) return false;
      if (c != '\\') {
        out += c;
        continue;
      }
      if (pos_ >= text_.size()) return false;
      const char e = text_[pos_++];
      switch (e) {
        case '"': out += '"'; break;
        case '\\': out += '\\'; break;
        case '/': out += '/'; break;
        case 'n': out += '\n'; break;
        case 't': out += '\t'; break;
        case 'r': out += '\r'; break;
        case 'b': out += '\b'; break;
        case 'f': out += '\f'; break;
        case 'u': {
          if (pos_ + 4 > text_.size()) return false;
          const long code = std::strtol(std::string(text_.substr(pos_, 4)).c_str(), nullptr, 16);
          if (code > 0x7f) return false;
          out += static_cast<char>(code);
          pos_ += 4;
          break;
        }
        default: return false;
      }
    }
    return false;
  }

  bool parse_number(double& out) {
    const std::size_t start = pos_;
    if (pos_ < text_.size() && text_[pos_] == '-') ++pos_;
    const std::size_t digits = pos_;
    while (pos_ < text_.size() && std::isdigit(static_cast<unsigned char>(text_[pos_]))) ++pos_;
    if (pos_ == digits) return false;
    if (text_[digits] == '0' && pos_ - digits > 1) return false;
    if (pos_ < text_.size() && text_[pos_] == '.') {
      const std::size_t frac = ++pos_;
      while (pos_ < text_.size() && std::isdigit(static_cast<unsigned char>(text_[pos_]))) ++pos_;
      if (pos_ == frac) return false;
    }
    if (pos_ < text_.size() && (text_[pos_] == 'e' || text_[pos_] == 'E')) {
      ++pos_;
      if (pos_ < text_.size() && (text_[pos_] == '+' || text_[pos_] == '-')) ++pos_;
      const std::size_t exp = pos_;
      while (pos_ < text_.size() && std::isdigit(static_cast<unsigned char>(text_[pos_]))) ++pos_;
      if (pos_ == exp) return false;
    }
    out = std::strtod(std::string(text_.substr(start, pos_ - start)).c_str(), nullptr);
    return true;
  }

  bool parse_value(JsonValue& value) {
    skip_space();
    if (pos_ >= text_.size()) return false;
    const char c = text_[pos_];
    if (c == '{') {
      ++pos_;
      value.type = JsonValue::Type::Object;
      if (eat('}')) return true;
      do {
        std::string key;
        skip_space();
        if (!parse_string(key) || !eat(':')) return false;
        JsonValue member;
        if (!parse_value(member)) return false;
        if (!value.object.emplace(key, std::move(member)).second) return false;  // duplicate key
      } while (eat(','));
      return eat('}');
    }
    if (c == '[') {
      ++pos_;
      value.type = JsonValue::Type::Array;
      if (eat(']')) return true;
      do {
        JsonValue element;
        if (!parse_value(element)) return false;
        value.array.push_back(std::move(element));
      } while (eat(','));
      return eat(']');
    }
    if (c == '"') {
      value.type = JsonValue::Type::String;
      return parse_string(value.string);
    }
    if (literal("true")) {
      value.type = JsonValue::Type::Bool;
      value.boolean = true;
      return true;
    }
    if (literal("false")) {
      value.type = JsonValue::Type::Bool;
      return true;
    }
    if (literal("null")) return true;
    value.type = JsonValue::Type::Number;
    return parse_number(value.number);
  }

  std::string_view text_;
  std::size_t pos_ = 0;
};

}  // namespace

std::optional<JsonValue> parse_json(std::string_view text, std::string* error) {
  return Parser(text).document(error);
}

}  // namespace delmesh::test
