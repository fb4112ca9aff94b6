// Benchmark: Delaunay triangulation of uniform random points in the unit square
// (BRIO/Hilbert order, Bowyer-Watson insertion, toolkit/mesh2d/triangulation.h).
// Usage: bench_delaunay2d [n ...]   (default 1000000). Prints a markdown table with the
// wall and CPU time (the machine may be shared: CPU time is the steadier figure),
// triangles per second and peak resident memory of the process.
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <vector>

#include "bench/process_usage.h"
#include "toolkit/mesh2d/triangulation.h"

using delmesh::bench::cpu_seconds;
using delmesh::bench::peak_rss_mb;

int main(int argc, char** argv) {
  std::vector<std::size_t> sizes;
  for (int i = 1; i < argc; ++i) sizes.push_back(std::strtoull(argv[i], nullptr, 10));
  if (sizes.empty()) sizes.push_back(1000000);
  std::printf("| points | triangles | seconds (wall) | seconds (CPU) | triangles/s (CPU) | peak RSS (MB) | bytes/triangle |\n");
  std::printf("|---:|---:|---:|---:|---:|---:|---:|\n");
  for (std::size_t n : sizes) {
    std::mt19937_64 rng(12345);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    std::vector<delmesh::Point2> pts(n);
    for (auto& p : pts) p = {u(rng), u(rng)};
    const double rss_before = peak_rss_mb();
    const double cpu0 = cpu_seconds();
    const auto t0 = std::chrono::steady_clock::now();
    delmesh::mesh2d::Triangulation tri;
    const auto ok = tri.build_delaunay(std::move(pts));
    const auto t1 = std::chrono::steady_clock::now();
    const double cpu = cpu_seconds() - cpu0;
    if (!ok) {
      std::fprintf(stderr, "%s\n", ok.error().describe().c_str());
      return 1;
    }
    const double sec = std::chrono::duration<double>(t1 - t0).count();
    const std::size_t ntri = tri.count_real();
    const double rss = peak_rss_mb();
    std::printf("| %zu | %zu | %.3f | %.3f | %.3g | %.1f | %.1f |\n", n, ntri, sec, cpu,
                static_cast<double>(ntri) / cpu, rss,
                (rss - rss_before) * 1024.0 * 1024.0 / static_cast<double>(ntri));
  }
  return 0;
}
