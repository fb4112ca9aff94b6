// Benchmark: Delaunay refinement of a .poly file (default: Triangle's A.poly from the
// corpus, drufat-a.poly) at several minimum angles with a global maximum area, through
// delmesh::triangulate (refiners/tri2d). Prints a markdown table: triangles, Steiner
// points, wall and CPU seconds, triangles per CPU second, min angle, unmet triangles, peak RSS.
// Usage: bench_refine2d [file.poly] [max_area] [angle ...]
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "bench/process_usage.h"
#include "refiners/tri2d/triangulate.h"
#include "toolkit/mesh2d/triangle_format_reader.h"

using delmesh::bench::cpu_seconds;
using delmesh::bench::peak_rss_mb;

int main(int argc, char** argv) {
  std::string path = argc > 1 ? argv[1] : "../shared/corpus/poly2d/drufat-a.poly";
  const double max_area = argc > 2 ? std::atof(argv[2]) : 5e-8;
  std::vector<double> angles;
  for (int i = 3; i < argc; ++i) angles.push_back(std::atof(argv[i]));
  if (angles.empty()) angles = {30.0};
  auto input = delmesh::read_triangle_poly(path);
  if (!input) {
    std::fprintf(stderr, "%s\n", input.error().describe().c_str());
    return 1;
  }
  const delmesh::Pslg& pslg = input->pslg;
  std::printf("| input | min angle | max area | triangles | Steiner points | seconds (wall) | seconds (CPU) | triangles/s (CPU) | achieved min angle | unmet | peak RSS (MB) | bytes/triangle |\n");
  std::printf("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
  for (double angle : angles) {
    delmesh::TriangulateOptions opt;
    opt.quality = angle > 0;
    opt.min_angle_deg = angle;
    opt.max_area = max_area;
    const double rss0 = peak_rss_mb();
    const double cpu0 = cpu_seconds();
    const auto t0 = std::chrono::steady_clock::now();
    auto r = delmesh::triangulate(pslg, opt);
    const auto t1 = std::chrono::steady_clock::now();
    const double cpu = cpu_seconds() - cpu0;
    if (!r) {
      std::fprintf(stderr, "%s\n", r.error().describe().c_str());
      return 1;
    }
    const double sec = std::chrono::duration<double>(t1 - t0).count();
    const std::size_t nt = r->mesh.triangles.size();
    const double rss = peak_rss_mb();
    const auto slash = path.find_last_of('/');
    std::printf("| %s | %.1f | %g | %zu | %zu | %.3f | %.3f | %.3g | %.2f | %zu | %.1f | %.1f |\n",
                path.substr(slash == std::string::npos ? 0 : slash + 1).c_str(), angle, max_area,
                nt, r->stats.steiner_points, sec, cpu, static_cast<double>(nt) / cpu,
                r->stats.min_angle_deg, r->stats.unmet_triangles, rss,
                (rss - rss0) * 1048576.0 / static_cast<double>(nt));
  }
  return 0;
}
