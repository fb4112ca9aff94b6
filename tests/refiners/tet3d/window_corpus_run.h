// A corpus input meshed with a dihedral window, as the polish's tests on real inputs
// measure it: the tets outside the window that touch no small input angle
// (MeshResult::tet_at_small_angle, refiners/tet3d/small_angles.h) and the mesh's extreme
// dihedral angles.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cstddef>
#include <filesystem>
#include <string>

#include "importers/import.h"
#include "refiners/tet3d/mesh_plc.h"
#include "tests/support/corpus_inputs.h"
#include "toolkit/quality/tet_quality.h"

namespace delmesh::test {

struct WindowRun {
  std::size_t tets = 0;
  std::size_t away = 0;  ///< tets outside the window touching no small input angle
  double smallest = 180.0, largest = 0.0;  ///< the mesh's extreme dihedral angles, degrees
};

/// Meshes the corpus input `relative` (default radius-edge) with the window [low, high]
/// and measures it into `run`; fails the test where the input is missing or not meshed.
inline void mesh_with_window(const std::string& relative, double low, double high, WindowRun& run) {
  const auto path = corpus_input_path(relative);
  ASSERT_TRUE(std::filesystem::exists(path)) << path;
  auto plc = import_file(path, ImportOptions{});
  ASSERT_TRUE(plc.has_value()) << path;
  MeshOptions options;
  options.min_dihedral_deg = low;
  options.max_dihedral_deg = high;
  auto result = mesh_plc(*plc, options);
  ASSERT_TRUE(result.has_value()) << path;
  const auto& mesh = result->mesh;
  ASSERT_EQ(result->tet_at_small_angle.size(), mesh.tets.size());
  run = WindowRun{};
  run.tets = mesh.tets.size();
  for (std::size_t t = 0; t < mesh.tets.size(); ++t) {
    const auto& v = mesh.tets[t];
    bool outside = false;
    for (const double angle : dihedral_angles_deg(mesh.points[v[0]], mesh.points[v[1]], mesh.points[v[2]],
                                                  mesh.points[v[3]])) {
      outside = outside || !(angle >= low && angle <= high);
      run.smallest = std::min(run.smallest, angle);
      run.largest = std::max(run.largest, angle);
    }
    run.away += outside && result->tet_at_small_angle[t] == 0 ? 1 : 0;
  }
}

}  // namespace delmesh::test
