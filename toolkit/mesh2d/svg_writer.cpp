// SVG picture of a triangle mesh (see svg_writer.h). Mesh coordinates are mapped to
// pixels with the y axis pointing up, one uniform scale, a margin, and a caption line
// below the drawing.
#include "toolkit/mesh2d/svg_writer.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <numeric>
#include <string>
#include <vector>

#include "toolkit/io/text_writer.h"
#include "toolkit/mesh2d/triangle_angles.h"
#include "toolkit/mesh2d/triangle_mesh_arrays.h"
#include "toolkit/mesh2d/triangle_mesh_edges.h"

namespace delmesh {
namespace {

constexpr double kMargin = 10.0;
constexpr double kCaption = 24.0;
constexpr int kDecimals = 2;

struct PixelMap {
  double x0 = 0, y1 = 0, scale = 1;
  double x(const Point2& p) const { return kMargin + (p[0] - x0) * scale; }
  double y(const Point2& p) const { return kMargin + (y1 - p[1]) * scale; }
};

/// `value` in fixed notation with `decimals` digits after the point.
std::string fixed(double value, int decimals) {
  char digits[64];
  const auto result = std::to_chars(digits, digits + sizeof digits, value, std::chars_format::fixed, decimals);
  if (result.ec != std::errc()) return "0";
  return std::string(digits, static_cast<std::size_t>(result.ptr - digits));
}

void move_line(TextWriter& out, const PixelMap& map, const Point2& a, const Point2& b) {
  out.put("M").put(fixed(map.x(a), kDecimals)).put(' ').put(fixed(map.y(a), kDecimals)).put("L")
      .put(fixed(map.x(b), kDecimals)).put(' ').put(fixed(map.y(b), kDecimals));
}

}  // namespace

Expected<void> write_svg(const std::filesystem::path& path, const TriangleMesh& mesh,
                         const SvgOptions& options) {
  if (!(options.width_px > 2 * kMargin) || !std::isfinite(options.width_px)) {
    return make_error(ErrorCode::InvalidOption, "SVG width must be a finite number above " +
                                                    std::to_string(2 * kMargin) + " pixels");
  }
  if (!(options.worst_fraction >= 0.0 && options.worst_fraction <= 1.0)) {
    return make_error(ErrorCode::InvalidOption, "the fraction of highlighted triangles must lie in [0, 1]");
  }
  if (auto ok = check_mesh_arrays(mesh); !ok) return ok;

  PixelMap map;
  double x1 = 0, y0 = 0;
  if (!mesh.points.empty()) {
    map.x0 = x1 = mesh.points[0][0];
    y0 = map.y1 = mesh.points[0][1];
    for (const auto& p : mesh.points) {
      map.x0 = std::min(map.x0, p[0]);
      x1 = std::max(x1, p[0]);
      y0 = std::min(y0, p[1]);
      map.y1 = std::max(map.y1, p[1]);
    }
  }
  const double extent = std::max(x1 - map.x0, map.y1 - y0);
  const double drawing = options.width_px - 2 * kMargin;
  map.scale = extent > 0 ? drawing / extent : 1.0;
  const double width = options.width_px;
  const double height = (map.y1 - y0) * map.scale + 2 * kMargin + kCaption;

  const std::size_t nt = mesh.triangles.size();
  std::vector<double> min_angle(nt);
  for (std::size_t t = 0; t < nt; ++t) {
    const auto& tri = mesh.triangles[t];
    min_angle[t] = triangle_min_angle_deg(mesh.points[tri[0]], mesh.points[tri[1]], mesh.points[tri[2]]);
  }
  std::size_t worst = 0;
  if (nt > 0 && options.worst_fraction > 0) {
    worst = std::clamp<std::size_t>(
        static_cast<std::size_t>(std::ceil(options.worst_fraction * static_cast<double>(nt))), 1, nt);
  }
  std::vector<std::uint32_t> order(nt);
  std::iota(order.begin(), order.end(), 0u);
  if (worst > 0 && worst < nt) {
    std::nth_element(order.begin(), order.begin() + static_cast<std::ptrdiff_t>(worst - 1), order.end(),
                     [&](std::uint32_t a, std::uint32_t b) { return min_angle[a] < min_angle[b]; });
  }
  const double threshold = worst > 0 ? min_angle[order[worst - 1]] : 0.0;
  const AngleRange range = mesh_angle_range(mesh);

  TextWriter out(path);
  out.put("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"")
      .put(fixed(width, 0)).put("\" height=\"").put(fixed(height, 0)).put("\" viewBox=\"0 0 ").put(fixed(width, 0))
      .put(' ').put(fixed(height, 0)).put("\">\n");
  out.put("<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n");

  out.put("<path fill=\"#e02020\" stroke=\"none\" d=\"");
  for (std::size_t i = 0; i < worst; ++i) {
    const auto& tri = mesh.triangles[order[i]];
    out.put("M");
    for (int k = 0; k < 3; ++k) {
      const Point2& p = mesh.points[tri[static_cast<std::size_t>(k)]];
      out.put(fixed(map.x(p), kDecimals)).put(' ').put(fixed(map.y(p), kDecimals)).put(k < 2 ? "L" : "Z");
    }
  }
  out.put("\"/>\n");

  const std::vector<MeshEdge> edges = mesh_edges(mesh);
  out.put("<path fill=\"none\" stroke=\"#404040\" stroke-width=\"0.4\" d=\"");
  for (const auto& e : edges) {
    if (!e.is_segment) move_line(out, map, mesh.points[e.a], mesh.points[e.b]);
  }
  out.put("\"/>\n<path fill=\"none\" stroke=\"#1f4e9e\" stroke-width=\"1.6\" stroke-linecap=\"round\" d=\"");
  for (const auto& s : mesh.segments) move_line(out, map, mesh.points[s[0]], mesh.points[s[1]]);
  out.put("\"/>\n");

  out.put("<text x=\"").put(fixed(kMargin, 0)).put("\" y=\"").put(fixed(height - 8, 0))
      .put("\" font-family=\"sans-serif\" font-size=\"13\">")
      .put(static_cast<std::int64_t>(mesh.points.size())).put(" vertices, ")
      .put(static_cast<std::int64_t>(nt)).put(" triangles, angles ").put(fixed(range.min_deg, 2)).put("&#176; to ")
      .put(fixed(range.max_deg, 2)).put("&#176;; red: the ").put(static_cast<std::int64_t>(worst))
      .put(" smallest-angle triangles (min angle &#8804; ").put(fixed(threshold, 2)).put("&#176;)</text>\n");
  out.put("</svg>\n");
  return out.finish();
}

}  // namespace delmesh
