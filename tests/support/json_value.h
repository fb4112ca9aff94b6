// A minimal strict JSON reader for tests (RFC 8259 subset: no \u escapes beyond ASCII),
// used to check that the CLI's --stats files parse and hold the expected keys.
#pragma once

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace delmesh::test {

struct JsonValue {
  enum class Type { Null, Bool, Number, String, Array, Object } type = Type::Null;
  bool boolean = false;
  double number = 0.0;
  std::string string;
  std::vector<JsonValue> array;
  std::map<std::string, JsonValue> object;

  bool has(const std::string& key) const { return type == Type::Object && object.count(key) > 0; }
  const JsonValue& operator[](const std::string& key) const { return object.at(key); }
};

/// Parses a whole document; nullopt (with `error` set) on any syntax error or trailing text.
std::optional<JsonValue> parse_json(std::string_view text, std::string* error = nullptr);

}  // namespace delmesh::test
