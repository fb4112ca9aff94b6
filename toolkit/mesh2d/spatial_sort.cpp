// BRIO rounds sorted along a Hilbert curve (see spatial_sort.h).
#include "toolkit/mesh2d/spatial_sort.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace delmesh::mesh2d {

std::uint32_t hilbert_index(std::uint32_t x, std::uint32_t y, int order) {
  const std::uint32_t n = 1u << order;
  std::uint64_t d = 0;
  for (std::uint32_t s = n / 2; s > 0; s /= 2) {
    const std::uint32_t rx = (x & s) ? 1u : 0u;
    const std::uint32_t ry = (y & s) ? 1u : 0u;
    d += static_cast<std::uint64_t>(s) * s * ((3u * rx) ^ ry);
    if (ry == 0) {
      if (rx == 1) {
        x = n - 1 - x;
        y = n - 1 - y;
      }
      std::swap(x, y);
    }
  }
  return static_cast<std::uint32_t>(d);
}

namespace {

std::uint64_t splitmix(std::uint64_t& state) {
  std::uint64_t z = (state += 0x9E3779B97F4A7C15ull);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

}  // namespace

std::vector<std::uint32_t> brio_hilbert_order(const std::vector<Point2>& points,
                                              std::uint64_t seed) {
  const std::size_t n = points.size();
  std::vector<std::uint32_t> order(n);
  if (n == 0) return order;

  double lo[2] = {points[0][0], points[0][1]};
  double hi[2] = {lo[0], lo[1]};
  for (const Point2& p : points) {
    for (int k = 0; k < 2; ++k) {
      lo[k] = std::min(lo[k], p[k]);
      hi[k] = std::max(hi[k], p[k]);
    }
  }
  constexpr int kOrder = 16;
  constexpr std::uint32_t kMax = (1u << kOrder) - 1;
  const double span = std::max(hi[0] - lo[0], hi[1] - lo[1]);
  const double scale = span > 0 ? kMax / span : 0.0;

  // Each point joins round `level` with probability 7/8 * (1/8)^level (a hash of its
  // index with the seed: deterministic); rare levels are inserted first. The sort key is
  // (round, Hilbert index).
  constexpr std::uint64_t kLevels = 10;
  std::vector<std::pair<std::uint64_t, std::uint32_t>> keyed(n);
  for (std::size_t i = 0; i < n; ++i) {
    std::uint64_t state = seed ^ (static_cast<std::uint64_t>(i) * 0xD1B54A32D192ED03ull);
    const std::uint64_t h = splitmix(state);
    const std::uint64_t level = std::min<std::uint64_t>(
        static_cast<std::uint64_t>(__builtin_ctzll(h | (1ull << 63))) / 3, kLevels);
    const Point2& p = points[i];
    const auto qx = static_cast<std::uint32_t>((p[0] - lo[0]) * scale);
    const auto qy = static_cast<std::uint32_t>((p[1] - lo[1]) * scale);
    const std::uint64_t hk = hilbert_index(std::min(qx, kMax), std::min(qy, kMax), kOrder);
    keyed[i] = {((kLevels - level) << 32) | hk, static_cast<std::uint32_t>(i)};
  }
  std::sort(keyed.begin(), keyed.end());
  for (std::size_t i = 0; i < n; ++i) order[i] = keyed[i].second;
  return order;
}

}  // namespace delmesh::mesh2d
