// Surface mesh import pipeline (see surface_importer.h for the steps).
#include "importers/surface/surface_importer.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <deque>
#include <numeric>
#include <unordered_map>

#include <Eigen/Geometry>

#include "importers/line_reader.h"
#include "importers/surface/surface_mesh.h"
#include "toolkit/core/str_cat.h"
#include "toolkit/plc/plc_geometry.h"
#include "toolkit/plc/plc_validate.h"
#include "toolkit/predicates/predicates.h"

namespace delmesh {
namespace {

using surface::PolygonSurface;

std::string point_text(const Vec3& p) {
  char buffer[96];
  std::snprintf(buffer, sizeof buffer, "(%.17g, %.17g, %.17g)", p.x(), p.y(), p.z());
  return buffer;
}

/// "face 12 (line 40): (x, y, z) (x, y, z) (x, y, z)" for a face of the input soup.
std::string face_text(const SurfaceSoup& soup, std::uint32_t f) {
  std::string out = cat("face ", f);
  if (soup.face_line[f] > 0) out += cat(" (line ", soup.face_line[f], ")");
  out += ":";
  for (std::uint32_t k = soup.face_start[f]; k < soup.face_start[f + 1]; ++k) {
    out += cat(" ", point_text(soup.points[soup.face_vertices[k]]));
  }
  return out;
}

/// Collects offending items of one defect kind: the first `max_listed` are described.
struct DefectList {
  ErrorCode code;
  std::string title;
  std::vector<std::string> listed;
  std::size_t count = 0;
  std::vector<std::uint32_t> ids;

  void add(std::size_t max_listed, const std::string& text, std::uint32_t id) {
    if (listed.size() < max_listed) {
      listed.push_back(text);
      ids.push_back(id);
    }
    ++count;
  }
};

Error defects_error(const std::string& file, std::vector<DefectList> defects) {
  std::string message = "surface refused:";
  ErrorCode code = ErrorCode::InvalidInput;
  std::vector<std::uint32_t> ids;
  bool first = true;
  for (const auto& d : defects) {
    if (d.count == 0) continue;
    if (first) {
      code = d.code;
      ids = d.ids;
      first = false;
    }
    message += cat("\n  ", d.title, " (", d.count, "):");
    for (const auto& text : d.listed) message += cat("\n    ", text);
    if (d.count > d.listed.size()) message += cat("\n    ... and ", d.count - d.listed.size(), " more");
  }
  Error error = make_error(code, message, file, 0);
  error.entity_ids = std::move(ids);
  return error;
}

/// Step 2: representative of every soup point.
std::vector<std::uint32_t> weld(const std::vector<Vec3>& P, double tolerance) {
  const std::size_t n = P.size();
  std::vector<std::uint32_t> rep(n);
  std::iota(rep.begin(), rep.end(), 0u);
  if (tolerance <= 0) {
    std::vector<std::uint32_t> order(rep);
    std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
      if (P[a] != P[b]) return std::lexicographical_compare(P[a].data(), P[a].data() + 3, P[b].data(), P[b].data() + 3);
      return a < b;
    });
    for (std::size_t i = 1; i < n; ++i) {
      if (P[order[i]] == P[order[i - 1]]) rep[order[i]] = rep[order[i - 1]];
    }
    return rep;
  }
  // Union-find over pairs closer than the tolerance, found through a hash grid of cell
  // size `tolerance`.
  auto root = [&](std::uint32_t x) {
    while (rep[x] != x) {
      rep[x] = rep[rep[x]];
      x = rep[x];
    }
    return x;
  };
  struct CellHash {
    std::size_t operator()(const std::array<long long, 3>& c) const {
      return static_cast<std::size_t>(c[0] * 73856093LL ^ c[1] * 19349663LL ^ c[2] * 83492791LL);
    }
  };
  std::unordered_map<std::array<long long, 3>, std::vector<std::uint32_t>, CellHash> grid;
  auto cell_of = [&](const Vec3& p) {
    return std::array<long long, 3>{static_cast<long long>(std::floor(p.x() / tolerance)),
                                    static_cast<long long>(std::floor(p.y() / tolerance)),
                                    static_cast<long long>(std::floor(p.z() / tolerance))};
  };
  for (std::uint32_t i = 0; i < n; ++i) grid[cell_of(P[i])].push_back(i);
  for (std::uint32_t i = 0; i < n; ++i) {
    const auto c = cell_of(P[i]);
    for (long long dx = -1; dx <= 1; ++dx)
      for (long long dy = -1; dy <= 1; ++dy)
        for (long long dz = -1; dz <= 1; ++dz) {
          const auto it = grid.find({c[0] + dx, c[1] + dy, c[2] + dz});
          if (it == grid.end()) continue;
          for (std::uint32_t j : it->second) {
            if (j <= i || (P[i] - P[j]).norm() > tolerance) continue;
            const std::uint32_t a = root(i), b = root(j);
            if (a != b) rep[std::max(a, b)] = std::min(a, b);
          }
        }
  }
  for (std::uint32_t i = 0; i < n; ++i) rep[i] = root(i);
  return rep;
}

std::uint64_t edge_key(std::uint32_t a, std::uint32_t b) {
  return (static_cast<std::uint64_t>(std::min(a, b)) << 32) | std::max(a, b);
}

struct EdgeUse {
  std::uint64_t key;
  std::uint32_t face;
  std::uint32_t k;  ///< position of the edge's first vertex in the face
};

std::vector<EdgeUse> edge_uses(const PolygonSurface& s, const std::vector<bool>* skip = nullptr) {
  std::vector<EdgeUse> uses;
  uses.reserve(s.verts.size());
  for (std::uint32_t f = 0; f < s.size(); ++f) {
    if (skip && (*skip)[f]) continue;
    const std::size_t n = s.degree(f);
    for (std::uint32_t k = 0; k < n; ++k) {
      uses.push_back({edge_key(s.face(f)[k], s.face(f)[(k + 1) % n]), f, k});
    }
  }
  std::sort(uses.begin(), uses.end(), [](const EdgeUse& x, const EdgeUse& y) {
    return x.key < y.key || (x.key == y.key && x.face < y.face);
  });
  return uses;
}

bool face_is_collinear(const PolygonSurface& s, std::size_t f) {
  const std::uint32_t* v = s.face(f);
  for (std::size_t k = 2; k < s.degree(f); ++k) {
    if (!collinear(s.points[v[0]], s.points[v[1]], s.points[v[k]])) return false;
  }
  return true;
}

}  // namespace

Expected<Plc> surface_to_plc(const SurfaceSoup& soup, std::string_view file_name,
                             const SurfaceImportOptions& options, SurfaceImportReport* report_out) {
  const std::string file(file_name);
  SurfaceImportReport report;
  report.input_vertices = soup.points.size();
  report.input_faces = soup.face_count();
  for (const Vec3& p : soup.points) {
    if (!p.allFinite()) {
      return make_error(ErrorCode::InvalidInput, cat("non-finite vertex coordinate ", point_text(p)), file, 0);
    }
  }
  if (soup.face_count() == 0) return make_error(ErrorCode::InvalidInput, "the surface has no face", file, 0);

  // Step 2: weld, then renumber the surviving points in input order.
  const auto rep = weld(soup.points, options.weld_tolerance);
  PolygonSurface s;
  std::vector<std::uint32_t> new_id(soup.points.size(), ~0u);
  for (std::uint32_t i = 0; i < soup.points.size(); ++i) {
    if (rep[i] == i) {
      new_id[i] = static_cast<std::uint32_t>(s.points.size());
      s.points.push_back(soup.points[i]);
    }
  }
  report.welded_vertices = s.points.size();

  // Step 3: collapsed and duplicate faces.
  std::vector<std::uint32_t> face;
  std::unordered_map<std::string, std::uint32_t> seen;
  for (std::uint32_t f = 0; f < soup.face_count(); ++f) {
    face.clear();
    for (std::uint32_t k = soup.face_start[f]; k < soup.face_start[f + 1]; ++k) {
      const std::uint32_t v = new_id[rep[soup.face_vertices[k]]];
      if (face.empty() || face.back() != v) face.push_back(v);
    }
    while (face.size() > 1 && face.front() == face.back()) face.pop_back();
    std::vector<std::uint32_t> sorted = face;
    std::sort(sorted.begin(), sorted.end());
    const bool repeated = std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end();
    if (face.size() < 3 || (repeated && std::unique(sorted.begin(), sorted.end()) - sorted.begin() < 3)) {
      ++report.collapsed_dropped;
      continue;
    }
    if (repeated) {
      return make_error(ErrorCode::DegenerateInput,
                        cat("surface refused: ", face_text(soup, f), " visits a vertex twice"), file,
                        soup.face_line[f]);
    }
    std::string key(reinterpret_cast<const char*>(sorted.data()), sorted.size() * sizeof(std::uint32_t));
    if (!seen.emplace(std::move(key), f).second) {
      ++report.duplicates_dropped;
      continue;
    }
    s.add(face.data(), face.size(), f);
  }
  if (report.collapsed_dropped > 0) {
    log(options.log, LogLevel::Warning,
        cat(file, ": dropped ", report.collapsed_dropped, " collapsed face(s) with a repeated vertex"));
  }
  if (report.duplicates_dropped > 0) {
    log(options.log, LogLevel::Warning, cat(file, ": dropped ", report.duplicates_dropped, " duplicate face(s)"));
  }

  // Zero-area faces: removable when every edge they touch keeps exactly two faces.
  std::vector<bool> zero_area(s.size(), false);
  std::size_t zero_count = 0;
  for (std::uint32_t f = 0; f < s.size(); ++f) {
    if (face_is_collinear(s, f)) {
      zero_area[f] = true;
      ++zero_count;
    }
  }
  DefectList zero_defects{ErrorCode::DegenerateInput,
                          "zero-area faces whose removal would open the surface", {}, 0, {}};
  if (zero_count > 0) {
    const auto uses = edge_uses(s, &zero_area);
    auto count_of = [&](std::uint64_t key) {
      const auto lo = std::lower_bound(uses.begin(), uses.end(), key,
                                       [](const EdgeUse& u, std::uint64_t k) { return u.key < k; });
      std::size_t c = 0;
      for (auto it = lo; it != uses.end() && it->key == key; ++it) ++c;
      return c;
    };
    for (std::uint32_t f = 0; f < s.size(); ++f) {
      if (!zero_area[f]) continue;
      bool removable = true;
      for (std::size_t k = 0; k < s.degree(f) && removable; ++k) {
        const std::size_t c = count_of(edge_key(s.face(f)[k], s.face(f)[(k + 1) % s.degree(f)]));
        removable = c == 2 || (c == 0 && !options.require_closed);
      }
      if (!removable) zero_defects.add(options.max_listed, face_text(soup, s.source[f]), s.source[f]);
    }
    if (zero_defects.count == 0) {
      PolygonSurface kept;
      kept.points = s.points;
      for (std::uint32_t f = 0; f < s.size(); ++f) {
        if (!zero_area[f]) kept.add(s.face(f), s.degree(f), s.source[f]);
      }
      s = std::move(kept);
      report.zero_area_dropped = zero_count;
      log(options.log, LogLevel::Warning, cat(file, ": dropped ", zero_count, " zero-area face(s)"));
    }
  }

  // Step 4: topology.
  const auto uses = edge_uses(s);
  DefectList open{ErrorCode::OpenBoundary, "open: boundary edges on a single face", {}, 0, {}};
  DefectList non_manifold{ErrorCode::NonManifold, "non-manifold: edges on three or more faces", {}, 0, {}};
  for (std::size_t i = 0; i < uses.size();) {
    std::size_t j = i;
    while (j < uses.size() && uses[j].key == uses[i].key) ++j;
    const auto a = static_cast<std::uint32_t>(uses[i].key >> 32), b = static_cast<std::uint32_t>(uses[i].key);
    auto edge = [&] { return cat("edge ", point_text(s.points[a]), " - ", point_text(s.points[b])); };
    if (j - i == 1 && options.require_closed) {
      open.add(options.max_listed, cat(edge(), " of ", face_text(soup, s.source[uses[i].face])), s.source[uses[i].face]);
    } else if (j - i > 2) {
      std::string faces = cat(edge(), " on ", j - i, " faces:");
      for (std::size_t k = i; k < j && k < i + 4; ++k) faces += cat(" ", s.source[uses[k].face]);
      non_manifold.add(options.max_listed, faces, s.source[uses[i].face]);
    }
    i = j;
  }
  if (open.count + non_manifold.count + zero_defects.count > 0) {
    return defects_error(file, {non_manifold, open, zero_defects});
  }

  // Step 5: orientation. Faces are made consistent through manifold edges (two uses).
  const std::size_t nf = s.size();
  std::vector<std::vector<std::pair<std::uint32_t, bool>>> adjacency(nf);  // (neighbour, same direction)
  for (std::size_t i = 0; i + 1 < uses.size(); ++i) {
    if (uses[i].key != uses[i + 1].key) continue;
    if ((i + 2 < uses.size() && uses[i + 2].key == uses[i].key) || (i > 0 && uses[i - 1].key == uses[i].key)) continue;
    const auto& x = uses[i];
    const auto& y = uses[i + 1];
    const bool same = s.face(x.face)[x.k] == s.face(y.face)[y.k];
    adjacency[x.face].push_back({y.face, same});
    adjacency[y.face].push_back({x.face, same});
  }
  s.shell.assign(nf, ~0u);
  std::vector<bool> flip(nf, false);
  std::uint32_t shells = 0;
  DefectList non_orientable{ErrorCode::NonManifold, "non-orientable shells (first face of each)", {}, 0, {}};
  for (std::uint32_t seed = 0; seed < nf; ++seed) {
    if (s.shell[seed] != ~0u) continue;
    const std::uint32_t id = shells++;
    std::deque<std::uint32_t> queue{seed};
    s.shell[seed] = id;
    bool orientable = true;
    while (!queue.empty()) {
      const std::uint32_t f = queue.front();
      queue.pop_front();
      for (const auto& [g, same] : adjacency[f]) {
        const bool want = flip[f] != same;  // same direction: g must be flipped relative to f
        if (s.shell[g] == ~0u) {
          s.shell[g] = id;
          flip[g] = want;
          queue.push_back(g);
        } else if (flip[g] != want) {
          orientable = false;
        }
      }
    }
    if (!orientable) non_orientable.add(options.max_listed, face_text(soup, s.source[seed]), s.source[seed]);
  }
  if (non_orientable.count > 0) return defects_error(file, {non_orientable});
  for (std::uint32_t f = 0; f < nf; ++f) {
    if (flip[f]) std::reverse(s.face(f), s.face(f) + s.degree(f));
  }
  // Outward: positive signed volume per shell (fan triangles, relative to a shell vertex).
  std::vector<double> volume(shells, 0.0);
  std::vector<Vec3> origin(shells, Vec3::Zero());
  std::vector<bool> has_origin(shells, false);
  for (std::uint32_t f = 0; f < nf; ++f) {
    const std::uint32_t sh = s.shell[f];
    const std::uint32_t* v = s.face(f);
    if (!has_origin[sh]) {
      origin[sh] = s.points[v[0]];
      has_origin[sh] = true;
    }
    for (std::size_t k = 1; k + 1 < s.degree(f); ++k) {
      const Vec3 a = s.points[v[0]] - origin[sh], b = s.points[v[k]] - origin[sh], c = s.points[v[k + 1]] - origin[sh];
      volume[sh] += a.dot(b.cross(c)) / 6.0;
    }
  }
  DefectList flat{ErrorCode::DegenerateInput, "shells enclosing no volume (first face of each)", {}, 0, {}};
  for (std::uint32_t f = 0; f < nf; ++f) {
    const std::uint32_t sh = s.shell[f];
    if (volume[sh] == 0.0 && has_origin[sh]) {
      if (options.require_closed) flat.add(options.max_listed, face_text(soup, s.source[f]), s.source[f]);
      has_origin[sh] = false;
    }
    if (volume[sh] < 0) {
      std::reverse(s.face(f), s.face(f) + s.degree(f));
      flip[f] = !flip[f];
    }
    if (flip[f]) ++report.faces_reoriented;
  }
  if (flat.count > 0) return defects_error(file, {flat});
  if (report.faces_reoriented > 0) {
    log(options.log, LogLevel::Warning,
        cat(file, ": reoriented ", report.faces_reoriented, " face(s) for consistent outward normals"));
  }
  report.shells = shells;

  // Step 6: facets, merged where coplanar, then the exact intersection check of the
  // facets (after the merge: large coplanar fans would otherwise be tested pair by pair).
  Plc plc;
  plc.points = s.points;
  std::vector<std::uint32_t> facet_face;
  report.merged_facets = surface::merge_coplanar_faces(s, options.merge_coplanar, plc, &facet_face);
  auto facet_text = [&](std::uint32_t facet) {
    std::string text = face_text(soup, s.source[facet_face[facet]]);
    const auto& polygons = plc.facets[facet].polygons;
    if (polygons.size() > 1 || polygons[0].size() > s.degree(facet_face[facet])) {
      text += cat(" (part of a merged planar facet of ", polygons[0].size(), "+ vertices)");
    }
    return text;
  };
  if (options.check_intersections) {
    PlcValidationOptions vo;
    vo.require_closed = false;
    vo.check_points_inside = false;
    vo.max_issues = options.max_listed * 4;
    const auto issues = validate_plc(plc, vo);
    if (!issues.empty()) {
      DefectList crossing{ErrorCode::SelfIntersection, "self-intersecting: face pairs that cross", {}, 0, {}};
      DefectList other{ErrorCode::DegenerateInput, "invalid faces", {}, 0, {}};
      for (const auto& issue : issues) {
        if (issue.kind == PlcIssueKind::Intersection && issue.facets.size() == 2) {
          crossing.add(options.max_listed,
                       cat(facet_text(issue.facets[0]), "\n      x ", facet_text(issue.facets[1])),
                       s.source[facet_face[issue.facets[0]]]);
        } else if (issue.kind == PlcIssueKind::Truncated) {
          other.add(options.max_listed, issue.message, 0);
        } else if (issue.facets.empty()) {
          other.add(options.max_listed, cat(to_string(issue.kind), ": ", issue.message), 0);
        } else {
          other.add(options.max_listed, cat(to_string(issue.kind), ": ", facet_text(issue.facets[0])),
                    s.source[facet_face[issue.facets[0]]]);
        }
      }
      return defects_error(file, {crossing, other});
    }
  }

  // Step 7: shells, nesting, region and hole points (exact tests on the faces).
  if (shells > 0 && options.require_closed) {
    std::vector<std::uint32_t> sample_vertex(shells, ~0u);
    for (std::uint32_t f = 0; f < nf; ++f) {
      if (sample_vertex[s.shell[f]] == ~0u) sample_vertex[s.shell[f]] = s.face(f)[0];
    }
    // contains[a][b]: shell a inside shell b.
    std::vector<std::vector<bool>> inside(shells, std::vector<bool>(shells, false));
    if (shells > 1) {
      for (std::uint32_t a = 0; a < shells; ++a) {
        for (std::uint32_t b = 0; b < shells; ++b) {
          if (a == b) continue;
          const auto c = surface::point_in_shell(s, b, s.points[sample_vertex[a]]);
          if (c == surface::Containment::Unknown) {
            return make_error(ErrorCode::SelfIntersection,
                              cat("surface refused: cannot decide whether shell ", a + 1, " (vertex ",
                                  point_text(s.points[sample_vertex[a]]), ") is inside shell ", b + 1,
                                  ": the shells touch"),
                              file, 0);
          }
          inside[a][b] = c == surface::Containment::Inside;
        }
      }
    }
    std::vector<std::uint32_t> depth(shells, 0), parent(shells, ~0u);
    for (std::uint32_t a = 0; a < shells; ++a) {
      for (std::uint32_t b = 0; b < shells; ++b) {
        if (!inside[a][b]) continue;
        ++depth[a];
      }
    }
    for (std::uint32_t a = 0; a < shells; ++a) {
      for (std::uint32_t b = 0; b < shells; ++b) {
        if (inside[a][b] && depth[b] + 1 == depth[a]) parent[a] = b;
      }
    }
    int next_region = 1;
    for (std::uint32_t sh = 0; sh < shells; ++sh) {
      std::vector<std::uint32_t> children;
      for (std::uint32_t c = 0; c < shells; ++c) {
        if (parent[c] == sh) children.push_back(c);
      }
      const bool cavity = depth[sh] % 2 == 1;
      if (cavity) ++report.cavities;
      const auto point = surface::interior_point(s, sh, children);
      if (!point) {
        log(options.log, LogLevel::Warning,
            cat(file, ": found no interior point for shell ", sh + 1, "; it gets no region point"));
        continue;
      }
      if (cavity && options.nested_shells == NestedShells::Holes) {
        plc.holes.push_back(*point);
      } else {
        Plc::Region region;
        region.point = *point;
        region.id = next_region++;
        plc.regions.push_back(region);
      }
    }
  }

  // Step 8: drop vertices no facet uses.
  std::vector<std::uint32_t> remap(plc.points.size(), ~0u);
  for (const auto& facet : plc.facets)
    for (const auto& polygon : facet.polygons)
      for (std::uint32_t v : polygon) remap[v] = 0;
  std::vector<Vec3> points;
  for (std::uint32_t v = 0; v < plc.points.size(); ++v) {
    if (remap[v] == ~0u) continue;
    remap[v] = static_cast<std::uint32_t>(points.size());
    points.push_back(plc.points[v]);
  }
  plc.points = std::move(points);
  for (auto& facet : plc.facets)
    for (auto& polygon : facet.polygons)
      for (auto& v : polygon) v = remap[v];
  if (report_out) *report_out = report;
  return plc;
}

Expected<Plc> import_surface(const std::filesystem::path& path, const SurfaceImportOptions& options,
                             SurfaceImportReport* report) {
  DELMESH_TRY(bytes, read_text(path));
  std::string ext = path.extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  const std::string name = path.string();
  Expected<SurfaceSoup> soup = make_error(ErrorCode::Unsupported, cat("'", name, "' is not an .stl, .off, .obj or .ply file"));
  if (ext == ".stl") soup = parse_stl(*bytes, name);
  if (ext == ".off") soup = parse_off(*bytes, name);
  if (ext == ".obj") soup = parse_obj(*bytes, name);
  if (ext == ".ply") soup = parse_ply(*bytes, name);
  if (!soup) return soup.error();
  if (soup->ignored_elements > 0) {
    log(options.log, LogLevel::Warning,
        cat(name, ": ignored ", soup->ignored_elements, " non-face element(s) (lines, points, edges)"));
  }
  return surface_to_plc(*soup, name, options, report);
}

}  // namespace delmesh
