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
  for (std::size_t i = 0; i < n; ++i) order[i] = static_cast<std::uint32_t>(i);
  if (n < 2) return order;

  // Random permutation (Fisher-Yates with a fixed seed: deterministic output).
  std::uint64_t state = seed;
  for (std::size_t i = n - 1; i > 0; --i) {
    const std::size_t j = static_cast<std::size_t>(splitmix(state) % (i + 1));
    std::swap(order[i], order[j]);
  }

  double lo[2] = {points[0][0], points[0][1]};
  double hi[2] = {lo[0], lo[1]};
  for (const Point2& p : points) {
    for (int k = 0; k < 2; ++k) {
      lo[k] = std::min(lo[k], p[k]);
      hi[k] = std::max(hi[k], p[k]);
    }
  }
  constexpr int kOrder = 16;
  const double cells = static_cast<double>(1u << kOrder);
  const double span = std::max(hi[0] - lo[0], hi[1] - lo[1]);
  const double scale = span > 0 ? (cells - 1) / span : 0.0;

  std::vector<std::pair<std::uint32_t, std::uint32_t>> keyed(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Point2& p = points[order[i]];
    const auto qx = static_cast<std::uint32_t>((p[0] - lo[0]) * scale);
    const auto qy = static_cast<std::uint32_t>((p[1] - lo[1]) * scale);
    keyed[i] = {hilbert_index(std::min(qx, (1u << kOrder) - 1), std::min(qy, (1u << kOrder) - 1),
                              kOrder),
                order[i]};
  }
  // Rounds: [0, n/8^k) ... the last round is the last 7/8 of the points.
  std::size_t end = n;
  while (end > 0) {
    const std::size_t begin = end > 64 ? end / 8 : 0;
    std::sort(keyed.begin() + static_cast<std::ptrdiff_t>(begin),
              keyed.begin() + static_cast<std::ptrdiff_t>(end));
    end = begin;
  }
  for (std::size_t i = 0; i < n; ++i) order[i] = keyed[i].second;
  return order;
}

}  // namespace delmesh::mesh2d
