// Writes N uniformly random points in the unit square as a Triangle .node file, the input
// of the 2D Delaunay benchmark (bench/parts/tri2d_io.sh). The points depend only on N and
// the seed: 53-bit fractions of a 64-bit Mersenne Twister, so every platform writes the
// same file.
//
// usage: bench_tri2d_random_points N OUT.node [SEED]
#include <charconv>
#include <cstdint>
#include <iostream>
#include <random>
#include <string_view>

#include "toolkit/mesh2d/pslg.h"
#include "toolkit/mesh2d/triangle_format_writer.h"

namespace {

bool parse(std::string_view text, std::uint64_t& value) {
  const auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  return ec == std::errc() && ptr == text.data() + text.size();
}

}  // namespace

int main(int argc, char** argv) {
  std::uint64_t count = 0;
  std::uint64_t seed = 1;
  if (argc < 3 || argc > 4 || !parse(argv[1], count) || count > 100000000 ||
      (argc == 4 && !parse(argv[3], seed))) {
    std::cerr << "usage: bench_tri2d_random_points N OUT.node [SEED]   (N <= 1e8)\n";
    return 2;
  }
  std::mt19937_64 rng(seed);
  auto unit = [&rng]() { return static_cast<double>(rng() >> 11) * 0x1p-53; };
  delmesh::Pslg points;
  points.points.reserve(count);
  for (std::uint64_t i = 0; i < count; ++i) {
    const double x = unit();
    const double y = unit();
    points.points.push_back({x, y});
  }
  if (auto written = delmesh::write_pslg_node(argv[2], points); !written) {
    std::cerr << "bench_tri2d_random_points: " << written.error().describe() << '\n';
    return 1;
  }
  return 0;
}
