// Import benchmark: for each file given, times import_file() and validate_plc() and
// prints one markdown table row (file, counts, seconds, peak resident memory so far).
// Usage: bench_import FILE...   |   bench_import --has-cad (exit 0 iff STEP is readable)
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <string_view>

#include "bench/process_usage.h"
#include "importers/import.h"
#include "toolkit/plc/plc_validate.h"

namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

int main(int argc, char** argv) {
  if (argc == 2 && std::string_view(argv[1]) == "--has-cad") return delmesh::cad_import_available() ? 0 : 1;
  std::printf("| file | vertices | facets | import s | validate s | issues | peak RSS MB |\n");
  std::printf("|---|---:|---:|---:|---:|---:|---:|\n");
  int status = 0;
  for (int i = 1; i < argc; ++i) {
    const std::filesystem::path path = argv[i];
    const auto t0 = std::chrono::steady_clock::now();
    const auto plc = delmesh::import_file(path, delmesh::ImportOptions{});
    const double import_s = seconds_since(t0);
    if (!plc) {
      std::printf("| %s | refused (%s) | | %.3f | | | %.0f |\n", path.filename().c_str(),
                  delmesh::to_string(plc.error().code), import_s, delmesh::bench::peak_rss_mb());
      continue;
    }
    const auto t1 = std::chrono::steady_clock::now();
    const auto issues = delmesh::validate_plc(*plc);
    const double validate_s = seconds_since(t1);
    if (!issues.empty()) status = 1;
    std::printf("| %s | %zu | %zu | %.3f | %.3f | %zu | %.0f |\n", path.filename().c_str(), plc->points.size(),
                plc->facets.size(), import_s, validate_s, issues.size(), delmesh::bench::peak_rss_mb());
  }
  return status;
}
