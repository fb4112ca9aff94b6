// Quality figures of a tetrahedral mesh written by any of the meshers compared in
// bench/parts/mesh3d.sh, measured the same way for all of them (toolkit/quality/
// tet_quality.h): tet count, smallest and largest dihedral angle, largest
// circumradius-to-shortest-edge ratio, and the share of tets above a radius-edge bound.
// Reads TetGen .node/.ele (either numbering base) and Medit .mesh (what `gmsh -3 -o
// X.mesh` writes); only the tets are used.
// With a dihedral window LOW HIGH (degrees) also the share of tets with a dihedral angle
// outside it (bench/parts/slivers.sh).
// Usage: bench_mesh_quality MESH.ele|MESH.mesh [BOUND [LOW HIGH]]   prints key=value pairs.
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "toolkit/mesh3d/tetra_mesh.h"
#include "toolkit/quality/tet_quality.h"

namespace {

/// Next data token of a TetGen file, skipping '#' comments.
class Tokens {
 public:
  explicit Tokens(const std::string& path) : in_(path) {}
  bool ok() const { return static_cast<bool>(in_); }
  bool next(std::string& token) {
    while (!(line_ >> token)) {
      std::string text;
      if (!std::getline(in_, text)) return false;
      text = text.substr(0, text.find('#'));
      line_.clear();
      line_.str(text);
    }
    return true;
  }
  double number() {
    std::string t;
    if (!next(t)) return 0;
    return std::strtod(t.c_str(), nullptr);
  }
  /// Skips the rest of the current line.
  void end_line() { line_.str(""), line_.clear(); }

 private:
  std::ifstream in_;
  std::istringstream line_;
};

bool read_tetgen(const std::string& ele_path, delmesh::TetraMesh& mesh) {
  const std::string base = ele_path.substr(0, ele_path.size() - 4);
  Tokens node(base + ".node");
  Tokens ele(ele_path);
  if (!node.ok() || !ele.ok()) return false;
  const auto n = static_cast<std::size_t>(node.number());
  node.end_line();
  long first = -1;
  mesh.points.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const long id = static_cast<long>(node.number());
    if (first < 0) first = id;
    const double x = node.number(), y = node.number(), z = node.number();
    node.end_line();
    mesh.points[static_cast<std::size_t>(id - first)] = delmesh::Vec3(x, y, z);
  }
  const auto m = static_cast<std::size_t>(ele.number());
  const long corners = static_cast<long>(ele.number());
  ele.end_line();
  if (corners != 4) return false;
  for (std::size_t i = 0; i < m; ++i) {
    ele.number();
    std::array<std::uint32_t, 4> t{};
    for (auto& v : t) v = static_cast<std::uint32_t>(static_cast<long>(ele.number()) - first);
    ele.end_line();
    mesh.tets.push_back(t);
  }
  return true;
}

bool read_medit(const std::string& path, delmesh::TetraMesh& mesh) {
  Tokens in(path);
  if (!in.ok()) return false;
  std::string token;
  while (in.next(token)) {
    if (token == "Vertices") {
      const auto n = static_cast<std::size_t>(in.number());
      for (std::size_t i = 0; i < n; ++i) {
        const double x = in.number(), y = in.number(), z = in.number();
        in.number();
        mesh.points.emplace_back(x, y, z);
      }
    } else if (token == "Tetrahedra") {
      const auto n = static_cast<std::size_t>(in.number());
      for (std::size_t i = 0; i < n; ++i) {
        std::array<std::uint32_t, 4> t{};
        for (auto& v : t) v = static_cast<std::uint32_t>(in.number()) - 1;
        in.number();
        mesh.tets.push_back(t);
      }
    }
  }
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: bench_mesh_quality MESH.ele|MESH.mesh [BOUND [LOW HIGH]]\n");
    return 2;
  }
  const std::string path = argv[1];
  const double bound = argc > 2 ? std::strtod(argv[2], nullptr) : 1.415;
  const bool window = argc > 4;
  const double low = window ? std::strtod(argv[3], nullptr) : 0.0;
  const double high = window ? std::strtod(argv[4], nullptr) : 180.0;
  delmesh::TetraMesh mesh;
  const bool ok = path.ends_with(".ele") ? read_tetgen(path, mesh) : read_medit(path, mesh);
  if (!ok || mesh.tets.empty()) {
    std::fprintf(stderr, "bench_mesh_quality: cannot read tets from %s\n", path.c_str());
    return 1;
  }
  for (const auto& t : mesh.tets) {
    for (const std::uint32_t v : t) {
      if (v >= mesh.points.size()) {
        std::fprintf(stderr, "bench_mesh_quality: vertex id out of range in %s\n", path.c_str());
        return 1;
      }
    }
  }
  const delmesh::TetQualityReport q = delmesh::tet_quality_report(mesh, bound, low, high);
  const auto share = [&](std::size_t n) { return 100.0 * static_cast<double>(n) / static_cast<double>(mesh.tets.size()); };
  std::printf("tets=%zu min_dihedral=%.2f max_dihedral=%.2f max_radius_edge=%.3f above=%zu above_pct=%.2f",
              mesh.tets.size(), q.min_dihedral_deg, q.max_dihedral_deg, q.max_radius_edge, q.above_radius_edge,
              share(q.above_radius_edge));
  if (window) std::printf(" outside=%zu outside_pct=%.3f", q.outside_dihedral_window, share(q.outside_dihedral_window));
  std::printf("\n");
  return 0;
}
