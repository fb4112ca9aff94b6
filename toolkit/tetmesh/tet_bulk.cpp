// BRIO with Hilbert-sorted rounds (see tet_bulk.h).
#include "toolkit/tetmesh/tet_bulk.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace delmesh {

namespace {

constexpr int kBits = 21;
constexpr std::size_t kSmallestRound = 64;

std::uint64_t splitmix64(std::uint64_t& state) {
  std::uint64_t z = (state += 0x9E3779B97F4A7C15ULL);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  return z ^ (z >> 31);
}

// Maps the bounding cube of the points onto the integer grid [0, 2^21).
struct Quantizer {
  double lo[3] = {0, 0, 0};
  double scale = 0;

  explicit Quantizer(std::span<const Vec3> points) {
    if (points.empty()) return;
    double hi[3];
    for (int k = 0; k < 3; ++k) lo[k] = hi[k] = points[0][k];
    for (const Vec3& p : points) {
      for (int k = 0; k < 3; ++k) {
        lo[k] = std::min(lo[k], p[k]);
        hi[k] = std::max(hi[k], p[k]);
      }
    }
    const double extent = std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]});
    if (extent > 0 && std::isfinite(extent)) scale = (double((1u << kBits) - 1)) / extent;
  }

  std::uint64_t key(const Vec3& p) const {
    std::uint32_t c[3];
    for (int k = 0; k < 3; ++k) {
      const double q = (p[k] - lo[k]) * scale;
      c[k] = q <= 0 ? 0u : std::min<std::uint32_t>(static_cast<std::uint32_t>(q), (1u << kBits) - 1);
    }
    return hilbert_index(c[0], c[1], c[2]);
  }
};

void sort_by_key(std::span<const Vec3> points, const Quantizer& quantizer,
                 std::span<std::uint32_t> indices,
                 std::vector<std::pair<std::uint64_t, std::uint32_t>>& scratch) {
  scratch.resize(indices.size());
  for (std::size_t k = 0; k < indices.size(); ++k) {
    scratch[k] = {quantizer.key(points[indices[k]]), indices[k]};
  }
  std::sort(scratch.begin(), scratch.end());
  for (std::size_t k = 0; k < indices.size(); ++k) indices[k] = scratch[k].second;
}

// Moves bit b of x (b < 21) to bit 3b.
std::uint64_t spread_bits(std::uint32_t x) {
  std::uint64_t v = x & 0x1FFFFFu;
  v = (v | (v << 32)) & 0x1F00000000FFFFULL;
  v = (v | (v << 16)) & 0x1F0000FF0000FFULL;
  v = (v | (v << 8)) & 0x100F00F00F00F00FULL;
  v = (v | (v << 4)) & 0x10C30C30C30C30C3ULL;
  v = (v | (v << 2)) & 0x1249249249249249ULL;
  return v;
}

}  // namespace

std::uint64_t hilbert_index(std::uint32_t x, std::uint32_t y, std::uint32_t z) {
  // Skilling, "Programming the Hilbert curve" (2004): axes to transposed index.
  std::uint32_t X[3] = {x, y, z};
  const std::uint32_t M = 1u << (kBits - 1);
  for (std::uint32_t Q = M; Q > 1; Q >>= 1) {
    const std::uint32_t P = Q - 1;
    for (int i = 0; i < 3; ++i) {
      if (X[i] & Q) {
        X[0] ^= P;
      } else {
        const std::uint32_t t = (X[0] ^ X[i]) & P;
        X[0] ^= t;
        X[i] ^= t;
      }
    }
  }
  for (int i = 1; i < 3; ++i) X[i] ^= X[i - 1];
  std::uint32_t t = 0;
  for (std::uint32_t Q = M; Q > 1; Q >>= 1) {
    if (X[2] & Q) t ^= Q - 1;
  }
  for (int i = 0; i < 3; ++i) X[i] ^= t;
  // Interleave the transposed bits: bit b of X[0], X[1], X[2] become key bits
  // 3b + 2, 3b + 1, 3b.
  return (spread_bits(X[0]) << 2) | (spread_bits(X[1]) << 1) | spread_bits(X[2]);
}

void hilbert_sort(std::span<const Vec3> points, std::span<std::uint32_t> indices) {
  const Quantizer quantizer(points);
  std::vector<std::pair<std::uint64_t, std::uint32_t>> scratch;
  sort_by_key(points, quantizer, indices, scratch);
}

std::vector<std::uint32_t> brio_order(std::span<const Vec3> points, std::uint64_t seed) {
  const std::size_t n = points.size();
  std::vector<std::uint32_t> order(n);
  for (std::size_t k = 0; k < n; ++k) order[k] = static_cast<std::uint32_t>(k);
  // Fisher–Yates with a fixed generator: the same order on every platform.
  std::uint64_t state = seed;
  for (std::size_t k = n; k > 1; --k) {
    const std::size_t j = static_cast<std::size_t>(splitmix64(state) % k);
    std::swap(order[k - 1], order[j]);
  }
  const Quantizer quantizer(points);
  std::vector<std::pair<std::uint64_t, std::uint32_t>> scratch;
  std::size_t end = n;
  while (end > 0) {
    const std::size_t begin = end > kSmallestRound ? end / 8 : 0;
    sort_by_key(points, quantizer, std::span(order).subspan(begin, end - begin), scratch);
    end = begin;
  }
  return order;
}

}  // namespace delmesh
