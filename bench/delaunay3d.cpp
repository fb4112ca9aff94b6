// Benchmark of 3D Delaunay tetrahedralization (toolkit/tetmesh, issue "tetrahedral
// core"): generates deterministic point sets as TetGen .node files and times the library
// call on them, reporting points/s, tets/s and bytes per tet (peak resident memory of the
// process divided by the number of tets). bench/parts/tet3d.sh runs it beside TetGen.
//
//   bench_delaunay3d generate DIR N   writes DIR/uniform.node (N points uniform in the
//                                     unit cube) and DIR/sphere.node (N points on the
//                                     unit sphere, rounded to doubles)
//   bench_delaunay3d run FILE.node    tetrahedralizes FILE and prints key=value figures
//                                     (wall and CPU seconds of the call alone)
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "bench/process_usage.h"
#include "toolkit/tetmesh/delaunay.h"
#include "toolkit/tetmesh/tet_node_io.h"

namespace {

std::uint64_t splitmix64(std::uint64_t& state) {
  std::uint64_t z = (state += 0x9E3779B97F4A7C15ULL);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  return z ^ (z >> 31);
}

double uniform01(std::uint64_t& state) {
  return static_cast<double>(splitmix64(state) >> 11) * 0x1.0p-53;
}

int generate(const std::filesystem::path& dir, std::size_t n) {
  std::filesystem::create_directories(dir);
  std::vector<delmesh::Vec3> cube, sphere;
  cube.reserve(n);
  sphere.reserve(n);
  std::uint64_t state = 20240601;
  for (std::size_t i = 0; i < n; ++i) {
    cube.emplace_back(uniform01(state), uniform01(state), uniform01(state));
  }
  while (sphere.size() < n) {
    const delmesh::Vec3 q(2 * uniform01(state) - 1, 2 * uniform01(state) - 1, 2 * uniform01(state) - 1);
    const double r = q.norm();
    if (r > 1 || r < 0.1) continue;
    sphere.push_back(q / r);
  }
  for (const auto& [name, pts] : {std::pair{"uniform.node", &cube}, std::pair{"sphere.node", &sphere}}) {
    auto written = delmesh::write_node_file(dir / name, *pts);
    if (!written) {
      std::fprintf(stderr, "%s\n", written.error().describe().c_str());
      return 1;
    }
  }
  return 0;
}

int run(const std::filesystem::path& file) {
  auto input = delmesh::read_node_file(file);
  if (!input) {
    std::fprintf(stderr, "%s\n", input.error().describe().c_str());
    return 1;
  }
  const double n = static_cast<double>(input->points.size());
  const double cpu_start = delmesh::bench::cpu_seconds();
  const auto start = std::chrono::steady_clock::now();
  // The points are handed over (moved): the mesh is built in the array the reader filled.
  auto result = delmesh::delaunay_tetrahedralize(std::move(input->points));
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const double cpu = delmesh::bench::cpu_seconds() - cpu_start;
  if (!result) {
    std::fprintf(stderr, "%s\n", result.error().describe().c_str());
    return 1;
  }
  const double peak = delmesh::bench::peak_rss_bytes();
  const double tets = result->mesh.num_finite_tets();
  std::printf("points=%.0f tets=%.0f build_s=%.3f cpu_s=%.3f points_per_cpu_s=%.0f "
              "tets_per_cpu_s=%.0f peak_rss_bytes=%.0f bytes_per_tet=%.1f\n",
              n, tets, seconds, cpu, n / cpu, tets / cpu, peak, peak / tets);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  const std::vector<std::string> args(argv + 1, argv + argc);
  if (args.size() == 3 && args[0] == "generate") return generate(args[1], std::stoul(args[2]));
  if (args.size() == 2 && args[0] == "run") return run(args[1]);
  std::fprintf(stderr, "usage: bench_delaunay3d generate DIR N | run FILE.node\n");
  return 2;
}
