// Meshes a unit square with a square hole through the installed delmesh library and
// prints the result: the smallest program an FEM preprocessor would write.
#include <cstdio>

#include "refiners/tri2d/triangulate.h"

int main() {
  delmesh::Pslg domain;
  domain.points = {{0, 0}, {1, 0}, {1, 1}, {0, 1}, {0.4, 0.4}, {0.6, 0.4}, {0.6, 0.6}, {0.4, 0.6}};
  domain.segments = {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {4, 5}, {5, 6}, {6, 7}, {7, 4}};
  domain.holes = {{0.5, 0.5}};
  delmesh::TriangulateOptions options;
  options.quality = true;
  options.min_angle_deg = 30.0;
  options.max_area = 0.001;
  auto result = delmesh::triangulate(domain, options);
  if (!result) {
    std::fprintf(stderr, "delmesh: %s\n", result.error().describe().c_str());
    return 1;
  }
  std::printf("%zu vertices, %zu triangles, min angle %.2f deg\n", result->mesh.points.size(),
              result->mesh.triangles.size(), result->stats.min_angle_deg);
  return result->mesh.triangles.empty() || result->stats.min_angle_deg < 30.0 ? 1 : 0;
}
