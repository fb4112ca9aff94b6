// Wavefront OBJ reader (see surface_soup.h).
#include "importers/line_reader.h"
#include "importers/surface/surface_soup.h"
#include "toolkit/core/str_cat.h"

namespace delmesh {

Expected<SurfaceSoup> parse_obj(std::string_view text, std::string_view file_name) {
  LineReader in(text, file_name);
  SurfaceSoup soup;
  std::vector<std::uint32_t> face;
  while (in.next()) {
    DELMESH_TRY(keyword, in.token("a keyword", false));
    if (*keyword == "v") {
      Vec3 p;
      for (int k = 0; k < 3; ++k) {
        DELMESH_TRY(x, in.real(std::string("coordinate ") + "xyz"[k]));
        p[k] = *x;
      }
      soup.points.push_back(p);
    } else if (*keyword == "f") {
      face.clear();
      while (in.remaining() > 0) {
        DELMESH_TRY(t, in.token("vertex", false));
        const std::string_view index_text = t->substr(0, t->find('/'));
        long long v = 0;
        const char* end = index_text.data() + index_text.size();
        auto [ptr, ec] = std::from_chars(index_text.data(), end, v);
        if (ec != std::errc() || ptr != end || v == 0) {
          return in.error(cat("bad face vertex '", *t) + "'");
        }
        const long long n = static_cast<long long>(soup.points.size());
        const long long index = v > 0 ? v - 1 : n + v;
        if (index < 0 || index >= n) {
          Error e = in.error(cat("face vertex ", v) + " refers to no vertex defined so far (" +
                             std::to_string(n) + " vertices)");
          e.code = ErrorCode::InvalidInput;
          return e;
        }
        face.push_back(static_cast<std::uint32_t>(index));
      }
      if (face.size() < 3) return in.error(cat("face with ", face.size()) + " vertices");
      soup.add_face(face.data(), face.size(), in.line());
    } else if (*keyword == "l" || *keyword == "p" || *keyword == "curv" || *keyword == "surf") {
      ++soup.ignored_elements;
    }
    // vt, vn, vp, g, o, s, usemtl, mtllib and other attribute records carry no geometry.
  }
  return soup;
}

}  // namespace delmesh
