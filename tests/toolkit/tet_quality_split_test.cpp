// tet_quality_split (toolkit/quality): the three reports of one pass must equal the three
// separate tet_quality_report calls field for field, bit for bit.
#include <gtest/gtest.h>

#include <random>

#include "toolkit/quality/tet_quality.h"

namespace delmesh {
namespace {

void expect_same(const TetQualityReport& x, const TetQualityReport& y) {
  EXPECT_EQ(x.tets, y.tets);
  EXPECT_EQ(x.total_volume, y.total_volume);
  EXPECT_EQ(x.min_volume, y.min_volume);
  EXPECT_EQ(x.min_dihedral_deg, y.min_dihedral_deg);
  EXPECT_EQ(x.max_dihedral_deg, y.max_dihedral_deg);
  EXPECT_EQ(x.max_radius_edge, y.max_radius_edge);
  EXPECT_EQ(x.mean_radius_edge, y.mean_radius_edge);
  EXPECT_EQ(x.radius_edge_counts, y.radius_edge_counts);
  EXPECT_EQ(x.min_dihedral_counts, y.min_dihedral_counts);
  EXPECT_EQ(x.max_dihedral_counts, y.max_dihedral_counts);
  EXPECT_EQ(x.outside_dihedral_window, y.outside_dihedral_window);
  EXPECT_EQ(x.above_radius_edge, y.above_radius_edge);
}

/// Random tets of every shape (slivers, needles and inverted ones included).
TetraMesh random_tets(std::size_t count) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  TetraMesh mesh;
  for (std::size_t i = 0; i < count; ++i) {
    const auto base = static_cast<std::uint32_t>(mesh.points.size());
    for (int k = 0; k < 4; ++k) mesh.points.emplace_back(u(rng), u(rng), i % 5 == 0 ? 1e-3 * u(rng) : u(rng));
    mesh.tets.push_back({base, base + 1, base + 2, base + 3});
  }
  return mesh;
}

TEST(TetQualitySplit, EqualsTheThreeSeparateReports) {
  const TetraMesh mesh = random_tets(3000);
  // A selection shorter than the mesh: missing entries count as unselected.
  std::vector<std::uint8_t> selection(mesh.tets.size() - 100, 0);
  for (std::size_t i = 0; i < selection.size(); i += 3) selection[i] = 1;
  const TetQualitySplit split = tet_quality_split(mesh, selection, 1.414, 20.0, 150.0);
  expect_same(split.all, tet_quality_report(mesh, 1.414, 20.0, 150.0));
  expect_same(split.selected, tet_quality_report(mesh, selection, true, 1.414, 20.0, 150.0));
  expect_same(split.unselected, tet_quality_report(mesh, selection, false, 1.414, 20.0, 150.0));
  EXPECT_EQ(split.selected.tets, 967u);
  EXPECT_EQ(split.selected.tets + split.unselected.tets, mesh.tets.size());
  EXPECT_GT(split.all.outside_dihedral_window, 0u);
  EXPECT_GT(split.all.above_radius_edge, 0u);
}

TEST(TetQualitySplit, EmptySelectionPartIsZeroed) {
  const TetraMesh mesh = random_tets(10);
  const TetQualitySplit split = tet_quality_split(mesh, {}, 2.0);
  EXPECT_EQ(split.selected.tets, 0u);
  EXPECT_EQ(split.selected.min_volume, 0.0);
  EXPECT_EQ(split.selected.min_dihedral_deg, 0.0);
  expect_same(split.unselected, split.all);
}

}  // namespace
}  // namespace delmesh
