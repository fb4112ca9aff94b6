// ASCII OFF reader (see surface_soup.h).
#include "importers/line_reader.h"
#include "importers/surface/surface_soup.h"
#include "toolkit/core/str_cat.h"

namespace delmesh {

Expected<SurfaceSoup> parse_off(std::string_view text, std::string_view file_name) {
  LineReader in(text, file_name);
  SurfaceSoup soup;
  DELMESH_TRY(first, in.require_line("the OFF header"));
  DELMESH_TRY(magic, in.token("the OFF header", false));
  const std::string_view m = *magic;
  if (m.size() < 3 || m.substr(m.size() - 3) != "OFF") {
    return in.error(cat("expected an OFF header, found '", m) + "'");
  }
  if (m != "OFF" && m != "COFF" && m != "NOFF" && m != "CNOFF") {
    return make_error(ErrorCode::Unsupported, cat("OFF variant '", m) + "' is not supported",
                      std::string(file_name), in.line());
  }
  if (in.remaining() > 0) {
    DELMESH_TRY(next, in.token("the OFF header", false));
    if (*next == "BINARY") {
      return make_error(ErrorCode::Unsupported, "binary OFF is not supported", std::string(file_name), in.line());
    }
    return in.error(cat("unexpected '", *next) + "' after the OFF header");
  }
  DELMESH_TRY(counts, in.require_line("vertex and face counts"));
  DELMESH_TRY(nv, in.count("number of vertices"));
  DELMESH_TRY(nf, in.count("number of faces"));
  for (std::size_t i = 0; i < *nv; ++i) {
    DELMESH_TRY(line, in.require_line(cat("vertex ", i)));
    Vec3 p;
    for (int k = 0; k < 3; ++k) {
      DELMESH_TRY(x, in.real(std::string("coordinate ") + "xyz"[k]));
      p[k] = *x;
    }
    soup.points.push_back(p);
  }
  std::vector<std::uint32_t> face;
  for (std::size_t f = 0; f < *nf; ++f) {
    DELMESH_TRY(line, in.require_line(cat("face ", f)));
    DELMESH_TRY(n, in.count(cat("number of vertices of face ", f)));
    if (*n > in.remaining()) {
      return in.error(cat("face ", f) + cat(" announces ", *n) +
                      cat(" vertices but its line has ", in.remaining()) + " numbers");
    }
    face.clear();
    for (std::size_t k = 0; k < *n; ++k) {
      DELMESH_TRY(v, in.integer("vertex index"));
      if (*v < 0 || static_cast<std::size_t>(*v) >= soup.points.size()) {
        Error e = in.error(cat("face ", f) + cat(" names vertex ", *v) +
                           cat(", but vertices are numbered 0..", static_cast<long long>(soup.points.size()) - 1));
        e.code = ErrorCode::InvalidInput;
        return e;
      }
      face.push_back(static_cast<std::uint32_t>(*v));
    }
    soup.add_face(face.data(), face.size(), in.line());
  }
  return soup;
}

}  // namespace delmesh
