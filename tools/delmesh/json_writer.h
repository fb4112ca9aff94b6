// A small streaming JSON writer for the --stats files of the CLI (RFC 8259 output: strings
// escaped, non-finite numbers written as null). Commas and nesting are tracked for the
// caller; keys are written with key() before each member value of an object.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace delmesh::cli {

class JsonWriter {
 public:
  JsonWriter& begin_object();
  JsonWriter& end_object();
  JsonWriter& begin_array();
  JsonWriter& end_array();
  JsonWriter& key(std::string_view name);
  JsonWriter& value(std::string_view text);
  JsonWriter& value(const char* text) { return value(std::string_view(text)); }
  JsonWriter& value(double number);
  JsonWriter& value(std::int64_t number);
  JsonWriter& value(std::uint64_t number);
  JsonWriter& value(int number) { return value(static_cast<std::int64_t>(number)); }
  JsonWriter& value(bool flag);
  JsonWriter& null();

  /// The document so far (complete once every object and array is closed), with a newline.
  std::string str() const { return out_ + "\n"; }

 private:
  void separate();
  JsonWriter& end_container(char close);
  void indent();
  void write_string(std::string_view text);

  std::string out_;
  /// Per open container: true once it has a member (a comma is due before the next).
  std::vector<bool> has_member_;
  bool after_key_ = false;
};

}  // namespace delmesh::cli
