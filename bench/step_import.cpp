// Benchmark driver for the CAD importer: imports each file given on the command line
// with import_step and prints one markdown table row per file: wall and CPU time, peak
// resident memory of this process, the PLC's counts and angle statistics: the smallest angle of
// the triangular facets (the sliver measure of the tessellation), how many are below
// 10 degrees, and the smallest corner of the polygonal facets (a CAD feature). Run one file per process for a per-file peak RSS.

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <numbers>
#include <set>

#include <Eigen/Geometry>

#include "bench/process_usage.h"
#include "importers/step/step_importer.h"

namespace {

double corner_angle_deg(const delmesh::Vec3& prev, const delmesh::Vec3& at, const delmesh::Vec3& next) {
  const delmesh::Vec3 u = prev - at;
  const delmesh::Vec3 v = next - at;
  return std::atan2(u.cross(v).norm(), u.dot(v)) * 180.0 / std::numbers::pi;
}

struct AngleStats {
  double triangle_min = 180.0;       ///< smallest angle of a triangular facet
  std::size_t triangles = 0;
  std::size_t triangles_below_10 = 0;
  double polygon_corner_min = 180.0;  ///< smallest corner of a polygonal facet (CAD feature)
};

AngleStats angle_stats(const delmesh::Plc& plc) {
  AngleStats stats;
  for (const delmesh::Plc::Facet& facet : plc.facets) {
    const bool triangle = facet.polygons.size() == 1 && facet.polygons.front().size() == 3;
    double facet_min = 180.0;
    for (const delmesh::Plc::Polygon& loop : facet.polygons) {
      const std::size_t n = loop.size();
      if (n < 3) continue;
      for (std::size_t i = 0; i < n; ++i) {
        facet_min = std::min(facet_min, corner_angle_deg(plc.points[loop[(i + n - 1) % n]], plc.points[loop[i]],
                                                         plc.points[loop[(i + 1) % n]]));
      }
    }
    if (triangle) {
      ++stats.triangles;
      if (facet_min < 10.0) ++stats.triangles_below_10;
      stats.triangle_min = std::min(stats.triangle_min, facet_min);
    } else {
      stats.polygon_corner_min = std::min(stats.polygon_corner_min, facet_min);
    }
  }
  return stats;
}

class StderrSink : public delmesh::LogSink {
 public:
  void write(delmesh::LogLevel, std::string_view message) override {
    std::fprintf(stderr, "%.*s\n", static_cast<int>(message.size()), message.data());
  }
};

}  // namespace

// Usage: bench_step_import [-v] [--no-glue] [--min-angle DEG] FILE...   (-v: the importer's log on stderr;
// --min-angle: the curved faces' angle bound, 26 as `delmesh mesh --radius-edge 1.414` asks)
int main(int argc, char** argv) {
  int status = 0;
  StderrSink sink;
  double cpu_before = 0.0;
  delmesh::StepImportOptions options;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "-v") == 0) {
      options.log = &sink;
      continue;
    }
    if (std::strcmp(argv[i], "--no-glue") == 0) {
      options.glue_assembly = false;
      continue;
    }
    if (std::strcmp(argv[i], "--min-angle") == 0 && i + 1 < argc) {
      options.surface_min_angle_deg = std::atof(argv[++i]);
      continue;
    }
    const auto start = std::chrono::steady_clock::now();
    const delmesh::Expected<delmesh::Plc> plc = delmesh::import_step(argv[i], options);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const double rss_mb = delmesh::bench::peak_rss_mb();
    const double cpu = delmesh::bench::cpu_seconds() - cpu_before;
    cpu_before += cpu;
    const char* name = std::max(argv[i], std::strrchr(argv[i], '/') ? std::strrchr(argv[i], '/') + 1 : argv[i]);
    if (!plc) {
      std::printf("| %s | %.2f | %.2f | %.0f | refused: %s | | | | | | | |\n", name, seconds, cpu, rss_mb,
                  plc.error().describe().c_str());
      status = 1;
      continue;
    }
    std::set<int> markers;
    std::size_t polygons = 0;
    for (const delmesh::Plc::Facet& facet : plc->facets) {
      markers.insert(facet.marker);
      if (facet.polygons.size() > 1 || facet.polygons.front().size() > 3) ++polygons;
    }
    const AngleStats angles = angle_stats(*plc);
    std::printf("| %s | %.2f | %.2f | %.0f | %zu | %zu | %zu | %zu | %zu | %.2f | %zu (%.1f%%) | %.2f |\n", name,
                seconds, cpu, rss_mb, plc->points.size(), plc->facets.size(), polygons, markers.size(), plc->regions.size(),
                angles.triangle_min, angles.triangles_below_10,
                angles.triangles ? 100.0 * static_cast<double>(angles.triangles_below_10) / static_cast<double>(angles.triangles) : 0.0,
                angles.polygon_corner_min);
  }
  return status;
}
