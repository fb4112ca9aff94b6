// Meshes through the installed delmesh library what an FEM preprocessor would: a unit
// square with a square hole (2D quality triangles), a unit cube with one marker per side
// built in memory (3D quality tets, checked with check_mesh), and the same cube read from
// a TetGen .smesh file, printing the results.
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "refiners/tri2d/triangulate.h"
#include "tools/api/delmesh.h"

namespace {

int mesh_square_with_hole() {
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
  std::printf("2D: %zu vertices, %zu triangles, min angle %.2f deg\n", result->mesh.points.size(),
              result->mesh.triangles.size(), result->stats.min_angle_deg);
  return result->mesh.triangles.empty() || result->stats.min_angle_deg < 30.0 ? 1 : 0;
}

int mesh_cube() {
  delmesh::Plc cube;
  for (int i = 0; i < 8; ++i) cube.points.emplace_back(i & 1, (i >> 1) & 1, (i >> 2) & 1);
  const delmesh::Plc::Polygon sides[6] = {{0, 2, 6, 4}, {1, 3, 7, 5}, {0, 1, 5, 4},
                                          {2, 3, 7, 6}, {0, 1, 3, 2}, {4, 5, 7, 6}};
  for (int s = 0; s < 6; ++s) {
    delmesh::Plc::Facet facet;
    facet.polygons = {sides[s]};
    facet.marker = s + 1;
    cube.facets.push_back(facet);
  }
  delmesh::MeshOptions options;
  options.max_radius_edge = 1.414;
  options.max_volume = 0.01;
  auto result = delmesh::mesh(cube, options);
  if (!result) {
    std::fprintf(stderr, "delmesh: %s\n", result.error().describe().c_str());
    return 1;
  }
  const auto issues = delmesh::check_mesh(*result, cube);
  for (const auto& issue : issues) std::fprintf(stderr, "check: %s\n", issue.message.c_str());
  std::printf("3D: %zu vertices, %zu tets, %zu boundary faces, status %s, %zu check issues\n",
              result->mesh.points.size(), result->mesh.tets.size(), result->mesh.boundary_faces.size(),
              delmesh::to_string(result->status), issues.size());
  return result->mesh.tets.size() < 100 || !issues.empty() ? 1 : 0;
}

int mesh_cube_file() {
  const auto path = std::filesystem::temp_directory_path() / "delmesh_consumer_cube.smesh";
  {
    std::ofstream file(path);
    file << "8 3 0 0\n";
    for (int i = 0; i < 8; ++i) {
      file << i + 1 << ' ' << (i & 1) << ' ' << ((i >> 1) & 1) << ' ' << ((i >> 2) & 1) << '\n';
    }
    file << "6 1\n4 1 3 7 5 1\n4 2 4 8 6 2\n4 1 2 6 5 3\n4 3 4 8 7 4\n4 1 2 4 3 5\n4 5 6 8 7 6\n0\n0\n";
  }
  delmesh::MeshOptions options;
  options.max_radius_edge = 1.414;
  auto result = delmesh::mesh(path, options);
  std::filesystem::remove(path);
  if (!result) {
    std::fprintf(stderr, "delmesh: %s\n", result.error().describe().c_str());
    return 1;
  }
  std::printf("3D from .smesh: %zu tets, status %s\n", result->mesh.tets.size(), delmesh::to_string(result->status));
  return result->mesh.tets.empty() ? 1 : 0;
}

}  // namespace

int main() {
  const int plane = mesh_square_with_hole();
  const int solid = mesh_cube();
  const int file = mesh_cube_file();
  return plane != 0 || solid != 0 || file != 0 ? 1 : 0;
}
