// Small helpers shared by the tetrahedral-kernel tests (tests/toolkit/tetmesh_*): seeded
// random point clouds, a readable list of validator issues for assertion messages, and
// whether a vertex is interior (its star has no infinite tet).
#pragma once

#include <cstddef>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "toolkit/geometry/vec3.h"
#include "toolkit/tetmesh/tet_check.h"
#include "toolkit/tetmesh/tet_mesh.h"

namespace delmesh::test {

/// The validator's issues, one message per line (for EXPECT/ASSERT messages).
inline std::string describe(const std::vector<MeshIssue>& issues) {
  std::string s;
  for (const auto& i : issues) s += i.message + "\n";
  return s;
}

/// n points uniform in [-1, 1]^3, the same for the same seed.
inline std::vector<Vec3> random_points(std::size_t n, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<Vec3> pts;
  for (std::size_t i = 0; i < n; ++i) pts.emplace_back(u(rng), u(rng), u(rng));
  return pts;
}

/// n points with integer coordinates in [0, max]^3, the same for the same seed (volumes and
/// orientations of their tets are exact in double precision for small max).
inline std::vector<Vec3> random_integer_points(std::size_t n, unsigned seed, int max) {
  std::mt19937_64 rng(seed);
  std::uniform_int_distribution<int> u(0, max);
  std::vector<Vec3> pts;
  for (std::size_t i = 0; i < n; ++i) pts.emplace_back(u(rng), u(rng), u(rng));
  return pts;
}

/// Fills `star` with the tets around v; true if there are some and none is infinite.
inline bool interior(TetMesh& mesh, std::uint32_t v, std::vector<std::uint32_t>& star) {
  mesh.star(v, star);
  if (star.empty()) return false;
  for (const std::uint32_t t : star)
    if (mesh.is_infinite(t)) return false;
  return true;
}

}  // namespace delmesh::test
