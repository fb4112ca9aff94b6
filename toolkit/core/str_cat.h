// cat(a, b, ...): builds a message string from pieces (text, characters, numbers) by
// appending into one buffer. Used for error and log messages instead of chains of
// `"text" + std::to_string(n)`, which GCC 12 misreports under -Wrestrict (GCC bug 105329)
// and which allocate once per operator.
#pragma once

#include <charconv>
#include <concepts>
#include <string>
#include <string_view>

namespace delmesh {

namespace detail {
inline void cat_part(std::string& out, std::string_view text) { out.append(text); }
inline void cat_part(std::string& out, const char* text) { out.append(text); }
inline void cat_part(std::string& out, const std::string& text) { out.append(text); }
inline void cat_part(std::string& out, char c) { out.push_back(c); }
template <std::integral I>
  requires(!std::same_as<I, char> && !std::same_as<I, bool>)
void cat_part(std::string& out, I value) {
  char buffer[24];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  out.append(buffer, result.ptr);
}
template <std::floating_point F>
void cat_part(std::string& out, F value) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, static_cast<double>(value));
  out.append(buffer, result.ptr);
}
}  // namespace detail

/// Concatenation of the pieces; numbers in their shortest round-trip form.
template <class... Parts>
std::string cat(const Parts&... parts) {
  std::string out;
  (detail::cat_part(out, parts), ...);
  return out;
}

}  // namespace delmesh
