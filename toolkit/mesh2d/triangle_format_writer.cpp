// Writers for Triangle's .node/.ele/.poly/.edge formats (see triangle_format_writer.h).
#include "toolkit/mesh2d/triangle_format_writer.h"

#include <cmath>
#include <span>
#include <string>

#include "toolkit/io/text_writer.h"
#include "toolkit/mesh2d/triangle_mesh_arrays.h"
#include "toolkit/mesh2d/triangle_mesh_edges.h"

namespace delmesh {
namespace {

Expected<void> check_first_index(const TriangleWriteOptions& options) {
  if (options.first_index != 0 && options.first_index != 1) {
    return make_error(ErrorCode::InvalidOption, "numbering must start at 0 or 1, not " +
                                                    std::to_string(options.first_index));
  }
  return {};
}

/// The point arrays shared by Pslg and TriangleMesh.
struct PointArrays {
  std::span<const Point2> points;
  std::span<const int> markers;
  int num_attributes = 0;
  std::span<const double> attributes;
};

void write_point_block(TextWriter& out, const PointArrays& p, const TriangleWriteOptions& options) {
  const bool markers = options.markers && !p.markers.empty();
  out.put(static_cast<std::int64_t>(p.points.size())).put(" 2 ").put(static_cast<std::int64_t>(p.num_attributes)).put(' ')
      .put(static_cast<std::int64_t>(markers ? 1 : 0)).put('\n');
  const auto nattr = static_cast<std::size_t>(p.num_attributes);
  for (std::size_t i = 0; i < p.points.size(); ++i) {
    out.put(static_cast<std::int64_t>(static_cast<std::int64_t>(i) + options.first_index)).put(' ').put(p.points[i][0]).put(' ')
        .put(p.points[i][1]);
    for (std::size_t a = 0; a < nattr; ++a) out.put(' ').put(p.attributes[i * nattr + a]);
    if (markers) out.put(' ').put(static_cast<std::int64_t>(p.markers[i]));
    out.put('\n');
  }
}

void write_segment_block(TextWriter& out, std::span<const std::array<std::uint32_t, 2>> segments,
                         std::span<const int> segment_markers, const TriangleWriteOptions& options) {
  const bool markers = options.markers && !segment_markers.empty();
  out.put(static_cast<std::int64_t>(segments.size())).put(' ').put(static_cast<std::int64_t>(markers ? 1 : 0)).put('\n');
  for (std::size_t s = 0; s < segments.size(); ++s) {
    out.put(static_cast<std::int64_t>(static_cast<std::int64_t>(s) + options.first_index)).put(' ')
        .put(static_cast<std::int64_t>(static_cast<std::int64_t>(segments[s][0]) + options.first_index)).put(' ')
        .put(static_cast<std::int64_t>(static_cast<std::int64_t>(segments[s][1]) + options.first_index));
    if (markers) out.put(' ').put(static_cast<std::int64_t>(segment_markers[s]));
    out.put('\n');
  }
}

void write_hole_block(TextWriter& out, std::span<const Point2> holes, const TriangleWriteOptions& options) {
  out.put(static_cast<std::int64_t>(holes.size())).put('\n');
  for (std::size_t h = 0; h < holes.size(); ++h) {
    out.put(static_cast<std::int64_t>(static_cast<std::int64_t>(h) + options.first_index)).put(' ').put(holes[h][0]).put(' ')
        .put(holes[h][1]).put('\n');
  }
}

Expected<void> check_pslg_arrays(const Pslg& pslg) {
  const std::size_t n = pslg.points.size();
  if (!pslg.point_markers.empty() && pslg.point_markers.size() != n) {
    return make_error(ErrorCode::InvalidInput, "PSLG has " + std::to_string(pslg.point_markers.size()) +
                                                   " point markers for " + std::to_string(n) + " points");
  }
  if (pslg.num_point_attributes < 0 ||
      pslg.point_attributes.size() != n * static_cast<std::size_t>(pslg.num_point_attributes)) {
    return make_error(ErrorCode::InvalidInput, "PSLG point attribute array has the wrong length");
  }
  if (!pslg.segment_markers.empty() && pslg.segment_markers.size() != pslg.segments.size()) {
    return make_error(ErrorCode::InvalidInput, "PSLG has " + std::to_string(pslg.segment_markers.size()) +
                                                   " segment markers for " +
                                                   std::to_string(pslg.segments.size()) + " segments");
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (!std::isfinite(pslg.points[i][0]) || !std::isfinite(pslg.points[i][1])) {
      Error e = make_error(ErrorCode::InvalidInput, "PSLG point " + std::to_string(i) + " is not finite");
      e.entity_ids.push_back(static_cast<std::uint32_t>(i));
      return e;
    }
  }
  for (std::size_t s = 0; s < pslg.segments.size(); ++s) {
    if (pslg.segments[s][0] >= n || pslg.segments[s][1] >= n) {
      Error e = make_error(ErrorCode::InvalidInput,
                           "PSLG segment " + std::to_string(s) + " names a point that does not exist");
      e.entity_ids.push_back(static_cast<std::uint32_t>(s));
      return e;
    }
  }
  return {};
}

template <class Body>
Expected<void> write_file(const std::filesystem::path& path, Body&& body) {
  TextWriter out(path);
  body(out);
  return out.finish();
}

Expected<void> check_mesh(const TriangleMesh& mesh, const TriangleWriteOptions& options) {
  if (auto ok = check_first_index(options); !ok) return ok;
  return check_mesh_arrays(mesh);
}

}  // namespace

Expected<void> write_triangle_node(const std::filesystem::path& path, const TriangleMesh& mesh,
                                   const TriangleWriteOptions& options) {
  if (auto ok = check_mesh(mesh, options); !ok) return ok;
  return write_file(path, [&](TextWriter& out) {
    write_point_block(out, {mesh.points, mesh.point_markers, mesh.num_point_attributes, mesh.point_attributes},
                      options);
  });
}

Expected<void> write_triangle_ele(const std::filesystem::path& path, const TriangleMesh& mesh,
                                  const TriangleWriteOptions& options) {
  if (auto ok = check_mesh(mesh, options); !ok) return ok;
  return write_file(path, [&](TextWriter& out) {
    const bool attributes = !mesh.triangle_attributes.empty();
    out.put(static_cast<std::int64_t>(mesh.triangles.size())).put(" 3 ").put(static_cast<std::int64_t>(attributes ? 1 : 0))
        .put('\n');
    const std::int64_t base = options.first_index;
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
      const auto& tri = mesh.triangles[t];
      out.put(static_cast<std::int64_t>(static_cast<std::int64_t>(t) + base)).put(' ').put(static_cast<std::int64_t>(tri[0] + base)).put(' ')
          .put(static_cast<std::int64_t>(tri[1] + base)).put(' ').put(static_cast<std::int64_t>(tri[2] + base));
      if (attributes) out.put(' ').put(mesh.triangle_attributes[t]);
      out.put('\n');
    }
  });
}

Expected<void> write_triangle_poly(const std::filesystem::path& path, const TriangleMesh& mesh,
                                   const TriangleWriteOptions& options) {
  if (auto ok = check_mesh(mesh, options); !ok) return ok;
  return write_file(path, [&](TextWriter& out) {
    const bool markers = options.markers && !mesh.point_markers.empty();
    out.put("0 2 ").put(static_cast<std::int64_t>(mesh.num_point_attributes)).put(' ').put(static_cast<std::int64_t>(markers ? 1 : 0)).put('\n');
    write_segment_block(out, mesh.segments, mesh.segment_markers, options);
    write_hole_block(out, mesh.holes, options);
  });
}

Expected<void> write_triangle_edge(const std::filesystem::path& path, const TriangleMesh& mesh,
                                   const TriangleWriteOptions& options) {
  if (auto ok = check_mesh(mesh, options); !ok) return ok;
  const std::vector<MeshEdge> edges = mesh_edges(mesh);
  return write_file(path, [&](TextWriter& out) {
    out.put(static_cast<std::int64_t>(edges.size())).put(' ').put(static_cast<std::int64_t>(options.markers ? 1 : 0)).put('\n');
    const std::int64_t base = options.first_index;
    for (std::size_t i = 0; i < edges.size(); ++i) {
      out.put(static_cast<std::int64_t>(static_cast<std::int64_t>(i) + base)).put(' ').put(static_cast<std::int64_t>(edges[i].a + base)).put(' ')
          .put(static_cast<std::int64_t>(edges[i].b + base));
      if (options.markers) out.put(' ').put(static_cast<std::int64_t>(edges[i].marker));
      out.put('\n');
    }
  });
}

Expected<void> write_pslg_node(const std::filesystem::path& path, const Pslg& pslg,
                               const TriangleWriteOptions& options) {
  if (auto ok = check_first_index(options); !ok) return ok;
  if (auto ok = check_pslg_arrays(pslg); !ok) return ok;
  return write_file(path, [&](TextWriter& out) {
    write_point_block(out, {pslg.points, pslg.point_markers, pslg.num_point_attributes, pslg.point_attributes},
                      options);
  });
}

Expected<void> write_pslg_poly(const std::filesystem::path& path, const Pslg& pslg,
                               const TriangleWriteOptions& options) {
  if (auto ok = check_first_index(options); !ok) return ok;
  if (auto ok = check_pslg_arrays(pslg); !ok) return ok;
  return write_file(path, [&](TextWriter& out) {
    write_point_block(out, {pslg.points, pslg.point_markers, pslg.num_point_attributes, pslg.point_attributes},
                      options);
    write_segment_block(out, pslg.segments, pslg.segment_markers, options);
    write_hole_block(out, pslg.holes, options);
    if (!pslg.regions.empty()) {
      out.put(static_cast<std::int64_t>(pslg.regions.size())).put('\n');
      for (std::size_t r = 0; r < pslg.regions.size(); ++r) {
        const auto& region = pslg.regions[r];
        out.put(static_cast<std::int64_t>(static_cast<std::int64_t>(r) + options.first_index)).put(' ').put(region.point[0]).put(' ')
            .put(region.point[1]).put(' ').put(region.attribute).put(' ').put(region.max_area).put('\n');
      }
    }
  });
}

}  // namespace delmesh
