// best_ring_triangulation (toolkit/tetmesh/ring_triangulation.h): the max-min
// triangulation of a polygon found by dynamic programming equals the best of all its
// triangulations, enumerated by brute force, on random triangle scores with invalid
// triangles; the returned triangles form a triangulation with that worst score; a
// must_exceed at or above the optimum gives no triangulation.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <limits>
#include <map>
#include <random>
#include <vector>

#include "toolkit/tetmesh/ring_triangulation.h"

namespace delmesh {
namespace {

constexpr double kInvalid = -std::numeric_limits<double>::infinity();

/// Random scores of every triangle (i, k, j), i < k < j, of an m-gon; about one in six invalid.
std::map<std::array<int, 3>, double> random_scores(int m, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::map<std::array<int, 3>, double> score;
  for (int i = 0; i < m; ++i) {
    for (int k = i + 1; k < m; ++k) {
      for (int j = k + 1; j < m; ++j) {
        const double x = u(rng);
        score[{i, k, j}] = x < 1.0 / 6.0 ? kInvalid : x;
      }
    }
  }
  return score;
}

/// The best worst score over all triangulations of the polygon i..j (brute force:
/// every apex k of the edge (i, j)); +infinity for an edge.
double brute_best(int i, int j, const std::map<std::array<int, 3>, double>& score) {
  if (j - i < 2) return std::numeric_limits<double>::infinity();
  double best = kInvalid;
  for (int k = i + 1; k < j; ++k) {
    best = std::max(best, std::min({score.at({i, k, j}), brute_best(i, k, score), brute_best(k, j, score)}));
  }
  return best;
}

TEST(RingTriangulation, MatchesBruteForceOnRandomScores) {
  std::mt19937_64 rng(7);
  int solved = 0;
  for (int trial = 0; trial < 200; ++trial) {
    const int m = 3 + trial % 7;
    const auto score = random_scores(m, rng);
    const double expected = brute_best(0, m - 1, score);
    std::vector<std::array<int, 3>> triangles;
    const double found = best_ring_triangulation(
        m, kInvalid, [&](int i, int k, int j) { return score.at({i, k, j}); }, triangles);
    ASSERT_EQ(found, expected) << "m = " << m << ", trial " << trial;
    if (found == kInvalid) {
      EXPECT_TRUE(triangles.empty());
      continue;
    }
    ++solved;
    // m - 2 distinct triangles whose worst score is the result and whose edges pair up:
    // each polygon edge in one triangle, each diagonal in two.
    ASSERT_EQ(triangles.size(), static_cast<std::size_t>(m - 2));
    double worst = std::numeric_limits<double>::infinity();
    std::map<std::pair<int, int>, int> edge_use;
    for (const auto& [i, k, j] : triangles) {
      ASSERT_TRUE(i < k && k < j);
      worst = std::min(worst, score.at({i, k, j}));
      ++edge_use[{i, k}];
      ++edge_use[{k, j}];
      ++edge_use[{i, j}];
    }
    EXPECT_EQ(worst, found);
    for (const auto& [edge, uses] : edge_use) {
      const bool boundary = edge.second - edge.first == 1 || (edge.first == 0 && edge.second == m - 1);
      EXPECT_EQ(uses, boundary ? 1 : 2) << "edge " << edge.first << "-" << edge.second;
    }
    // Asking for more than the optimum gives nothing.
    std::vector<std::array<int, 3>> none;
    EXPECT_EQ(best_ring_triangulation(
                  m, found, [&](int i, int k, int j) { return score.at({i, k, j}); }, none),
              kInvalid);
    EXPECT_TRUE(none.empty());
  }
  EXPECT_GT(solved, 100);
}

TEST(RingTriangulation, ShortRingsHaveNoTriangle) {
  std::vector<std::array<int, 3>> triangles;
  const double found = best_ring_triangulation(2, 0.0, [](int, int, int) { return kInvalid; }, triangles);
  EXPECT_EQ(found, std::numeric_limits<double>::infinity());
  EXPECT_TRUE(triangles.empty());
}

}  // namespace
}  // namespace delmesh
