// Where the tets outside a dihedral window are (issue 6 item 4): meshes each input with
// MeshOptions::min_dihedral_deg / max_dihedral_deg and sorts the tets left outside the
// window that touch no small input angle (refiners/tet3d/small_angles.h) by their shape
// against the boundary:
//   cap     two boundary faces meet at the tet's bad edge: the tet fills a fold of the
//           boundary alone, its bad angle is the domain's angle there (forced only when
//           that angle is itself outside the window);
//   flat4   all four vertices on the boundary, otherwise (a flat tet across nearly
//           coplanar facets; one line each on stderr);
//   inner   at least one vertex off the boundary.
// Each flat4 and inner tet is printed on stderr with its centroid and the boundary markers
// (CAD face ids of a STEP model) of the boundary faces around its vertices; an inner tet
// also with its worst angle and how many ends of that angle's edge are on the boundary
// (and whether the edge is a boundary edge).
// The domain angle at a boundary edge is the sum of the dihedral angles of the tets
// around it (360 on an edge of an internal facet); a bad tet whose bad edge is a
// boundary edge with a domain angle below the window is counted as forced (no tet there
// can avoid it; above the window the angle can be shared between tets). Also times the run (CPU) and,
// with --plain, the same run without the window.
// Usage: bench_dihedral_classify [--plain] [--window LOW HIGH] [--radius-edge B] FILE...
// prints one line per file (B: MeshOptions::max_radius_edge, default 2).
#include <algorithm>
#include <array>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "importers/import.h"
#include "refiners/tet3d/mesh_plc.h"
#include "toolkit/core/log.h"
#include "toolkit/quality/tet_quality.h"

namespace {

using delmesh::Vec3;

constexpr int kEdges[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};

std::uint64_t edge_key(std::uint32_t a, std::uint32_t b) {
  if (a > b) std::swap(a, b);
  return (static_cast<std::uint64_t>(a) << 32) | b;
}

/// Prints the improvement pass's summary line (Info level) to stderr.
class StderrInfo : public delmesh::LogSink {
 public:
  void write(delmesh::LogLevel level, std::string_view message) override {
    if (level == delmesh::LogLevel::Info && message.find("slivers") != std::string_view::npos)
      std::fprintf(stderr, "  %.*s\n", static_cast<int>(message.size()), message.data());
  }
};

double cpu_seconds() { return static_cast<double>(std::clock()) / CLOCKS_PER_SEC; }

/// The face of tet v opposite its vertex f, vertex ids sorted.
std::array<std::uint32_t, 3> sorted_face(const std::array<std::uint32_t, 4>& v, int f) {
  std::array<std::uint32_t, 3> face{};
  int k = 0;
  for (int i = 0; i < 4; ++i)
    if (i != f) face[k++] = v[i];
  std::sort(face.begin(), face.end());
  return face;
}

void classify(const char* path, double low, double high, double radius_edge, bool plain) {
  auto plc = delmesh::import_file(path, delmesh::ImportOptions{});
  if (!plc) {
    std::printf("%s: import failed: %s\n", path, plc.error().describe().c_str());
    return;
  }
  double plain_seconds = -1.0;
  std::size_t plain_unmet = 0;
  if (plain) {
    const double start = cpu_seconds();
    delmesh::MeshOptions options;
    options.max_radius_edge = radius_edge;
    auto result = delmesh::mesh_plc(*plc, options);
    plain_seconds = result ? cpu_seconds() - start : -1.0;
    if (result) plain_unmet = result->stats.unmet_tets;
  }
  delmesh::MeshOptions options;
  options.max_radius_edge = radius_edge;
  options.min_dihedral_deg = low;
  options.max_dihedral_deg = high;
  StderrInfo sink;
  options.log = &sink;
  const double start = cpu_seconds();
  auto result = delmesh::mesh_plc(*plc, options);
  const double seconds = cpu_seconds() - start;
  if (!result) {
    std::printf("%s: mesh failed: %s\n", path, result.error().describe().c_str());
    return;
  }
  const delmesh::TetraMesh& mesh = result->mesh;
  std::vector<char> on_boundary(mesh.points.size(), 0);
  std::map<std::uint64_t, int> boundary_edge_faces;
  std::map<std::array<std::uint32_t, 3>, int> boundary_face;
  // The boundary markers (CAD face ids for STEP input) around each boundary vertex.
  std::vector<std::vector<int>> vertex_markers(mesh.points.size());
  for (std::size_t k = 0; k < mesh.boundary_faces.size(); ++k) {
    const int marker = k < mesh.boundary_markers.size() ? mesh.boundary_markers[k] : 0;
    for (const std::uint32_t v : mesh.boundary_faces[k]) {
      auto& list = vertex_markers[v];
      if (std::find(list.begin(), list.end(), marker) == list.end()) list.push_back(marker);
    }
  }
  const auto markers_of = [&](const std::array<std::uint32_t, 4>& v) {
    std::vector<int> all;
    for (const std::uint32_t x : v) all.insert(all.end(), vertex_markers[x].begin(), vertex_markers[x].end());
    std::sort(all.begin(), all.end());
    all.erase(std::unique(all.begin(), all.end()), all.end());
    std::string text;
    for (const int m : all) text += (text.empty() ? "" : ",") + std::to_string(m);
    return text;
  };
  for (const auto& f : mesh.boundary_faces) {
    for (const std::uint32_t v : f) on_boundary[v] = 1;
    for (int i = 0; i < 3; ++i) ++boundary_edge_faces[edge_key(f[i], f[(i + 1) % 3])];
    auto key = f;
    std::sort(key.begin(), key.end());
    boundary_face[key] = 1;
  }
  // Domain angle at each boundary edge: the sum of the tets' dihedral angles there.
  std::map<std::uint64_t, double> domain_angle;
  for (const auto& v : mesh.tets) {
    const auto angles = delmesh::dihedral_angles_deg(mesh.points[v[0]], mesh.points[v[1]], mesh.points[v[2]],
                                                     mesh.points[v[3]]);
    for (int e = 0; e < 6; ++e) {
      const std::uint64_t key = edge_key(v[kEdges[e][0]], v[kEdges[e][1]]);
      if (boundary_edge_faces.count(key)) domain_angle[key] += angles[e];
    }
  }
  std::array<std::size_t, 4> inner_by_boundary{};
  std::array<std::size_t, 3> inner_by_faces{};  // inner tets with 0, 1, 2+ boundary faces
  std::size_t inner_small_only = 0, inner_skinny = 0;
  std::size_t bad = 0, at_small = 0, forced = 0, cap = 0, flat4 = 0, inner = 0, large = 0;
  double cap_min_fold = 360.0, cap_max_fold = 0.0;
  for (std::size_t t = 0; t < mesh.tets.size(); ++t) {
    const auto& v = mesh.tets[t];
    const auto angles = delmesh::dihedral_angles_deg(mesh.points[v[0]], mesh.points[v[1]], mesh.points[v[2]],
                                                     mesh.points[v[3]]);
    int worst = -1;
    for (int e = 0; e < 6; ++e)
      if (!(angles[e] >= low && angles[e] <= high)) worst = e;
    if (worst < 0) continue;
    ++bad;
    if (result->tet_at_small_angle[t]) {
      ++at_small;
      continue;
    }
    large += angles[worst] > high;
    const std::uint64_t key = edge_key(v[kEdges[worst][0]], v[kEdges[worst][1]]);
    const auto it = domain_angle.find(key);
    if (it != domain_angle.end() && it->second < low) {
      ++forced;
      const Vec3 &pa = mesh.points[v[kEdges[worst][0]]], &pb = mesh.points[v[kEdges[worst][1]]];
      std::fprintf(stderr, "  forced: angle %.2f, domain angle %.2f at edge (%g %g %g)-(%g %g %g)\n", angles[worst],
                   it->second, pa[0], pa[1], pa[2], pb[0], pb[1], pb[2]);
      continue;
    }
    int faces_at_edge = 0;
    for (int f = 0; f < 4; ++f) {
      const std::array<std::uint32_t, 3> face = sorted_face(v, f);
      const bool holds_edge = f != kEdges[worst][0] && f != kEdges[worst][1];
      if (holds_edge && boundary_face.count(face)) ++faces_at_edge;
    }
    const int boundary_vertices = on_boundary[v[0]] + on_boundary[v[1]] + on_boundary[v[2]] + on_boundary[v[3]];
    if (faces_at_edge >= 2) {
      ++cap;
      cap_min_fold = std::min(cap_min_fold, it->second);
      cap_max_fold = std::max(cap_max_fold, it->second);
    } else if (boundary_vertices == 4) {
      ++flat4;
      int faces = 0;
      for (int f = 0; f < 4; ++f) {
        faces += boundary_face.count(sorted_face(v, f)) ? 1 : 0;
      }
      const Vec3 centroid = (mesh.points[v[0]] + mesh.points[v[1]] + mesh.points[v[2]] + mesh.points[v[3]]) / 4.0;
      std::fprintf(stderr,
                   "  flat4: worst %.2f, boundary faces %d, worst edge on the boundary %d (domain angle %.2f) at "
                   "(%g %g %g), markers %s\n",
                   angles[worst], faces, it != domain_angle.end() ? 1 : 0, it != domain_angle.end() ? it->second : 0.0,
                   centroid[0], centroid[1], centroid[2], markers_of(v).c_str());
    } else {
      ++inner;
      ++inner_by_boundary[static_cast<std::size_t>(boundary_vertices)];
      int faces = 0;
      for (int f = 0; f < 4; ++f) faces += boundary_face.count(sorted_face(v, f)) ? 1 : 0;
      ++inner_by_faces[static_cast<std::size_t>(std::min(faces, 2))];
      const auto [lo, hi] = std::minmax_element(angles.begin(), angles.end());
      const Vec3 centroid = (mesh.points[v[0]] + mesh.points[v[1]] + mesh.points[v[2]] + mesh.points[v[3]]) / 4.0;
      const int worst_ends = on_boundary[v[kEdges[worst][0]]] + on_boundary[v[kEdges[worst][1]]];
      std::fprintf(stderr,
                   "  inner: boundary vertices %d, faces %d, angles %.2f..%.2f, worst %.2f at an edge with %d ends on "
                   "the boundary%s, radius-edge %.2f at (%g %g %g), markers %s\n",
                   boundary_vertices, faces, *lo, *hi, angles[worst], worst_ends,
                   it != domain_angle.end() ? " (a boundary edge)" : "",
                   delmesh::radius_edge_ratio(mesh.points[v[0]], mesh.points[v[1]], mesh.points[v[2]],
                                              mesh.points[v[3]]),
                   centroid[0], centroid[1], centroid[2], markers_of(v).c_str());
      inner_small_only += !(angles[worst] > high) && *std::max_element(angles.begin(), angles.end()) <= high;
      inner_skinny += delmesh::radius_edge_ratio(mesh.points[v[0]], mesh.points[v[1]], mesh.points[v[2]],
                                                 mesh.points[v[3]]) > options.max_radius_edge;
    }
  }
  const double share = 100.0 * static_cast<double>(bad) / static_cast<double>(mesh.tets.size());
  std::printf("%s: tets=%zu outside=%zu (%.4f%%) at_small=%zu unforced: forced_by_domain=%zu cap=%zu", path,
              mesh.tets.size(), bad, share, at_small, forced, cap);
  if (cap) std::printf(" (folds %.1f..%.1f)", cap_min_fold, cap_max_fold);
  std::printf(
      " flat4=%zu inner=%zu (boundary vertices 0/1/2/3: %zu/%zu/%zu/%zu, boundary faces 0/1/2+: %zu/%zu/%zu, only "
      "small angles %zu, skinny %zu)",
      flat4, inner, inner_by_boundary[0], inner_by_boundary[1], inner_by_boundary[2], inner_by_boundary[3],
      inner_by_faces[0], inner_by_faces[1], inner_by_faces[2], inner_small_only, inner_skinny);
  std::printf(" above %g: %zu, cpu=%.2fs (", high, large, seconds);
  for (const auto& stage : result->stats.stages) std::printf(" %s %.2fs", stage.name.c_str(), stage.seconds);
  std::printf(" )");
  if (plain) std::printf(" plain_cpu=%.2fs plain_unmet=%zu", plain_seconds, plain_unmet);
  std::printf("\n");
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  bool plain = false;
  double low = 20.0, high = 150.0, radius_edge = delmesh::MeshOptions{}.max_radius_edge;
  int i = 1;
  for (; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--plain") {
      plain = true;
    } else if (arg == "--window" && i + 2 < argc) {
      low = std::strtod(argv[i + 1], nullptr);
      high = std::strtod(argv[i + 2], nullptr);
      i += 2;
    } else if (arg == "--radius-edge" && i + 1 < argc) {
      radius_edge = std::strtod(argv[++i], nullptr);
    } else {
      break;
    }
  }
  if (i >= argc) {
    std::fprintf(stderr,
                 "usage: bench_dihedral_classify [--plain] [--window LOW HIGH] [--radius-edge B] FILE...\n");
    return 2;
  }
  for (; i < argc; ++i) classify(argv[i], low, high, radius_edge, plain);
  return 0;
}
