// Errors as values.
//
// Every user-facing failure in delmesh (a malformed line in a file, a facet that is not
// planar, a segment naming a missing vertex) is reported as an `Error` returned inside an
// `Expected<T>`, never as an exit() or a thrown integer. An Error names what is wrong and,
// where it applies, the file and line and the ids of the offending entities, so that a
// command-line user and an FEM preprocessor linking the library get the same precise text.
//
// Internal invariant violations (bugs, not bad input) throw `InternalError` through
// DELMESH_CHECK, which stays on in release builds.
#pragma once

#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <variant>
#include <vector>

namespace delmesh {

enum class ErrorCode : std::uint8_t {
  IoError,           ///< a file could not be opened, read or written
  ParseError,        ///< malformed text or binary content
  InvalidInput,      ///< well-formed but unusable input (NaN coordinate, bad index, ...)
  DuplicateVertex,   ///< two input vertices at the same position
  DegenerateInput,   ///< all points collinear / coplanar, zero-length segment, ...
  NonPlanarFacet,    ///< a facet whose vertices are not exactly coplanar
  SelfIntersection,  ///< input features that cross other than at shared entities
  OpenBoundary,      ///< a boundary that must be closed is not
  NonManifold,       ///< an edge shared by a number of faces that makes no solid
  InvalidOption,     ///< an option value out of range
  Unsupported,       ///< a valid request delmesh does not implement
};

/// Human-readable name of an error code ("ParseError", ...).
const char* to_string(ErrorCode code);

struct SourceLocation {
  std::string file;
  std::size_t line = 0;  ///< 1-based; 0 when the location is the whole file
};

struct Error {
  ErrorCode code = ErrorCode::InvalidInput;
  std::string message;
  std::optional<SourceLocation> location;
  std::vector<std::uint32_t> entity_ids;  ///< ids of the offending vertices/segments/facets

  /// "file:line: message" (or just the message), the form printed by the CLI.
  std::string describe() const;
};

/// Shorthand constructors.
Error make_error(ErrorCode code, std::string message);
Error make_error(ErrorCode code, std::string message, std::string file, std::size_t line);

/// The value of an operation that can fail on bad input: either a T or an Error.
template <class T>
class [[nodiscard]] Expected {
 public:
  Expected(T value) : data_(std::move(value)) {}          // NOLINT(implicit)
  Expected(Error error) : data_(std::move(error)) {}      // NOLINT(implicit)

  bool has_value() const { return data_.index() == 0; }
  explicit operator bool() const { return has_value(); }

  T& value() & { return std::get<0>(data_); }
  const T& value() const& { return std::get<0>(data_); }
  T&& value() && { return std::get<0>(std::move(data_)); }
  T& operator*() & { return value(); }
  const T& operator*() const& { return value(); }
  T* operator->() { return &value(); }
  const T* operator->() const { return &value(); }

  const Error& error() const { return std::get<1>(data_); }

 private:
  std::variant<T, Error> data_;
};

/// Expected<void>: success or an Error.
template <>
class [[nodiscard]] Expected<void> {
 public:
  Expected() = default;
  Expected(Error error) : error_(std::move(error)) {}  // NOLINT(implicit)
  bool has_value() const { return !error_.has_value(); }
  explicit operator bool() const { return has_value(); }
  const Error& error() const { return *error_; }

 private:
  std::optional<Error> error_;
};

/// Thrown by DELMESH_CHECK when an internal invariant fails: a delmesh bug, never bad input.
class InternalError : public std::logic_error {
 public:
  using std::logic_error::logic_error;
};

[[noreturn]] void throw_internal_error(const char* condition, const char* file, int line,
                                       const std::string& context);

}  // namespace delmesh

/// Always-on invariant check. Throws delmesh::InternalError with the condition and location.
#define DELMESH_CHECK(cond, context)                                             \
  do {                                                                           \
    if (!(cond)) ::delmesh::throw_internal_error(#cond, __FILE__, __LINE__, (context)); \
  } while (false)
