// Benchmark: Delaunay refinement of a .poly file (default: Triangle's A.poly from the
// corpus, drufat-a.poly) at several minimum angles with a global maximum area, through
// delmesh::triangulate (refiners/tri2d). Prints a markdown table: triangles, Steiner
// points, wall and CPU seconds, triangles per CPU second, min angle, unmet triangles, peak RSS.
// Usage: bench_refine2d [file.poly] [max_area] [angle ...]
// The small .poly parser below reads only what this benchmark needs (whitespace
// separated numbers, '#' comments); the full reader with error reporting is the
// library's.
#include <sys/resource.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "refiners/tri2d/triangulate.h"

namespace {

double cpu_seconds() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) +
         1e-6 * static_cast<double>(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
}

double peak_rss_mb() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_maxrss) / 1024.0;
}

bool read_poly(const std::string& path, delmesh::Pslg& out) {
  std::ifstream in(path);
  if (!in) return false;
  std::vector<double> nums;
  std::string line;
  std::vector<std::vector<double>> lines;
  while (std::getline(in, line)) {
    const auto hash = line.find('#');
    if (hash != std::string::npos) line.resize(hash);
    std::istringstream ss(line);
    std::vector<double> v;
    double x;
    while (ss >> x) v.push_back(x);
    if (!v.empty()) lines.push_back(v);
  }
  std::size_t k = 0;
  if (lines.empty()) return false;
  const auto n = static_cast<std::size_t>(lines[k][0]);
  const std::size_t nattr = lines[k].size() > 2 ? static_cast<std::size_t>(lines[k][2]) : 0;
  ++k;
  double first = 0;
  for (std::size_t i = 0; i < n; ++i, ++k) {
    if (i == 0) first = lines[k][0];
    out.points.push_back({lines[k][1], lines[k][2]});
  }
  (void)nattr;
  const auto base = static_cast<std::uint32_t>(first);
  const auto ns = static_cast<std::size_t>(lines[k][0]);
  ++k;
  for (std::size_t i = 0; i < ns; ++i, ++k)
    out.segments.push_back({static_cast<std::uint32_t>(lines[k][1]) - base,
                            static_cast<std::uint32_t>(lines[k][2]) - base});
  if (k < lines.size()) {
    const auto nh = static_cast<std::size_t>(lines[k][0]);
    ++k;
    for (std::size_t i = 0; i < nh && k < lines.size(); ++i, ++k)
      out.holes.push_back({lines[k][1], lines[k][2]});
  }
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  std::string path = argc > 1 ? argv[1] : "../shared/corpus/poly2d/drufat-a.poly";
  const double max_area = argc > 2 ? std::atof(argv[2]) : 5e-8;
  std::vector<double> angles;
  for (int i = 3; i < argc; ++i) angles.push_back(std::atof(argv[i]));
  if (angles.empty()) angles = {30.0};
  delmesh::Pslg pslg;
  if (!read_poly(path, pslg)) {
    std::fprintf(stderr, "cannot read %s\n", path.c_str());
    return 1;
  }
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
