// Insertion order for bulk construction: Hilbert index and BRIO permutation.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <random>
#include <vector>

#include "toolkit/tetmesh/tet_bulk.h"

namespace delmesh {
namespace {

TEST(TetBulk, HilbertIndexWalksFaceAdjacentCells) {
  // The first 8^3 cells of the curve are the cube [0, 8)^3, visited one face-neighbour
  // after another.
  std::vector<std::array<int, 3>> cell(512, {-1, -1, -1});
  for (int x = 0; x < 8; ++x)
    for (int y = 0; y < 8; ++y)
      for (int z = 0; z < 8; ++z) {
        const std::uint64_t h = hilbert_index(x, y, z);
        ASSERT_LT(h, 512u) << x << " " << y << " " << z;
        ASSERT_EQ(cell[h][0], -1) << "index " << h << " used twice";
        cell[h] = {x, y, z};
      }
  for (std::size_t k = 1; k < cell.size(); ++k) {
    const int d = std::abs(cell[k][0] - cell[k - 1][0]) + std::abs(cell[k][1] - cell[k - 1][1]) +
                  std::abs(cell[k][2] - cell[k - 1][2]);
    EXPECT_EQ(d, 1) << "between indices " << k - 1 << " and " << k;
  }
  // The largest coordinates still give distinct indices below 2^63.
  const std::uint32_t top = (1u << 21) - 1;
  EXPECT_LT(hilbert_index(top, top, top), std::uint64_t{1} << 63);
  EXPECT_NE(hilbert_index(top, top, top), hilbert_index(top, top, top - 1));
}

TEST(TetBulk, BrioOrderIsADeterministicPermutationWithLocalRounds) {
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Vec3> pts;
  for (int i = 0; i < 5000; ++i) pts.emplace_back(u(rng), u(rng), u(rng));
  const auto a = brio_order(pts, 7);
  const auto b = brio_order(pts, 7);
  const auto c = brio_order(pts, 8);
  EXPECT_EQ(a, b);
  EXPECT_NE(a, c);
  auto sorted = a;
  std::sort(sorted.begin(), sorted.end());
  for (std::uint32_t i = 0; i < sorted.size(); ++i) ASSERT_EQ(sorted[i], i);
  // Within the last round (the last 7/8), consecutive points are close: the mean step is
  // far below the mean distance of two random points in the unit cube (about 0.66).
  double total = 0;
  const std::size_t begin = pts.size() / 8 + 1;
  for (std::size_t k = begin; k < a.size(); ++k) total += (pts[a[k]] - pts[a[k - 1]]).norm();
  EXPECT_LT(total / static_cast<double>(a.size() - begin), 0.1);
}

}  // namespace
}  // namespace delmesh
