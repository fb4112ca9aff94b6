// Error formatting and the internal-error path (see error.h).
#include "toolkit/core/error.h"

namespace delmesh {

const char* to_string(ErrorCode code) {
  switch (code) {
    case ErrorCode::IoError: return "IoError";
    case ErrorCode::ParseError: return "ParseError";
    case ErrorCode::InvalidInput: return "InvalidInput";
    case ErrorCode::DuplicateVertex: return "DuplicateVertex";
    case ErrorCode::DegenerateInput: return "DegenerateInput";
    case ErrorCode::NonPlanarFacet: return "NonPlanarFacet";
    case ErrorCode::SelfIntersection: return "SelfIntersection";
    case ErrorCode::OpenBoundary: return "OpenBoundary";
    case ErrorCode::NonManifold: return "NonManifold";
    case ErrorCode::InvalidOption: return "InvalidOption";
    case ErrorCode::Unsupported: return "Unsupported";
  }
  return "Unknown";
}

std::string Error::describe() const {
  std::string out;
  if (location) {
    out += location->file;
    if (location->line > 0) {
      out.push_back(':');
      out.append(std::to_string(location->line));
    }
    out.append(": ");
  }
  out += message;
  return out;
}

Error make_error(ErrorCode code, std::string message) {
  Error e;
  e.code = code;
  e.message = std::move(message);
  return e;
}

Error make_error(ErrorCode code, std::string message, std::string file, std::size_t line) {
  Error e = make_error(code, std::move(message));
  e.location = SourceLocation{std::move(file), line};
  return e;
}

void throw_internal_error(const char* condition, const char* file, int line,
                          const std::string& context) {
  throw InternalError(std::string("delmesh internal error: ") + condition + " failed at " +
                      file + ":" + std::to_string(line) + (context.empty() ? "" : ": " + context));
}

}  // namespace delmesh
