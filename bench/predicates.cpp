// Micro benchmark of the exact predicates (toolkit/predicates): CPU nanoseconds per call of
// orient3d and insphere on three kinds of input, which exercise different stages:
//   random       points uniform in the unit cube (decided by the floating-point filter),
//   sphere       points on the unit sphere rounded to doubles, five at random: every
//                insphere is degenerate up to rounding (the double-double stage),
//   sphere_far   the same sphere centred at (1e6, 1e6, 1e6): inexact differences,
//   plane        random points, the fourth of each tuple rounded onto the plane of the
//                first three: near-coplanar orient3d (insphere as for random),
//   cospherical  integer points on x^2 + y^2 + z^2 = 9: exactly zero (small-integer
//                path of stage A).
// orient3d uses the first four points of each tuple (on the whole sphere most of these
// are decided by the floating-point filter).
//
//   bench_predicates [CALLS]     prints one line per predicate and input kind
#include <time.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "toolkit/predicates/predicates.h"

namespace {

using delmesh::predicates::insphere;
using delmesh::predicates::orient3d;

struct Point {
  double x[3];
};

std::uint64_t splitmix64(std::uint64_t& state) {
  std::uint64_t z = (state += 0x9E3779B97F4A7C15ULL);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  return z ^ (z >> 31);
}

double uniform01(std::uint64_t& state) { return static_cast<double>(splitmix64(state) >> 11) * 0x1.0p-53; }

std::vector<Point> random_points(std::size_t n, std::uint64_t& state) {
  std::vector<Point> pts(n);
  for (auto& p : pts)
    for (double& c : p.x) c = uniform01(state);
  return pts;
}

std::vector<Point> sphere_points(std::size_t n, double center, std::uint64_t& state) {
  std::vector<Point> pts;
  while (pts.size() < n) {
    double q[3] = {2 * uniform01(state) - 1, 2 * uniform01(state) - 1, 2 * uniform01(state) - 1};
    const double r = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2]);
    if (r > 1 || r < 0.1) continue;
    pts.push_back({{center + q[0] / r, center + q[1] / r, center + q[2] / r}});
  }
  return pts;
}

/// Tuples whose fourth point is rounded onto the plane of the first three (near-coplanar
/// orient3d); the fifth is random.
std::vector<Point> plane_points(std::size_t n, std::uint64_t& state) {
  std::vector<Point> pts = random_points(n, state);
  for (std::size_t i = 0; i + 5 <= n; i += 5) {
    const double u = uniform01(state), v = uniform01(state);
    for (int k = 0; k < 3; ++k)
      pts[i + 3].x[k] =
          pts[i].x[k] + u * (pts[i + 1].x[k] - pts[i].x[k]) + v * (pts[i + 2].x[k] - pts[i].x[k]);
  }
  return pts;
}

std::vector<Point> cospherical_points(std::size_t n, std::uint64_t& state) {
  static const double kOnSphere[][3] = {{3, 0, 0},  {0, 3, 0},   {0, 0, 3},   {-3, 0, 0}, {0, -3, 0},
                                        {0, 0, -3}, {1, 2, 2},   {-2, 1, -2}, {2, -2, 1}, {2, 1, -2},
                                        {-1, -2, 2}, {2, 2, -1}, {-2, -2, -1}, {1, -2, -2}};
  constexpr std::size_t kCount = sizeof(kOnSphere) / sizeof(kOnSphere[0]);
  std::vector<Point> pts(n);
  for (auto& p : pts) {
    const auto& s = kOnSphere[splitmix64(state) % kCount];
    p = {{s[0], s[1], s[2]}};
  }
  return pts;
}

// CPU time of this process (the machine running the benchmarks is shared).
double cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

void measure(const std::string& name, const std::vector<Point>& pts, long calls) {
  const std::size_t tuples = pts.size() / 5;
  long checksum = 0;
  double start = cpu_seconds();
  for (long i = 0; i < calls; ++i) {
    const Point* t = &pts[5 * (static_cast<std::size_t>(i) % tuples)];
    checksum += to_int(orient3d(t[0].x, t[1].x, t[2].x, t[3].x));
  }
  const double orient_ns = 1e9 * (cpu_seconds() - start) / static_cast<double>(calls);
  start = cpu_seconds();
  for (long i = 0; i < calls; ++i) {
    const Point* t = &pts[5 * (static_cast<std::size_t>(i) % tuples)];
    checksum += to_int(insphere(t[0].x, t[1].x, t[2].x, t[3].x, t[4].x));
  }
  const double insphere_ns = 1e9 * (cpu_seconds() - start) / static_cast<double>(calls);
  std::printf("input=%s orient3d_ns=%.1f insphere_ns=%.1f checksum=%ld\n", name.c_str(), orient_ns,
              insphere_ns, checksum);
}

}  // namespace

int main(int argc, char** argv) {
  const long calls = argc > 1 ? std::atol(argv[1]) : 200000;
  if (calls <= 0) {
    std::fprintf(stderr, "usage: bench_predicates [CALLS > 0]\n");
    return 1;
  }
  std::uint64_t state = 20240601;
  constexpr std::size_t kPoints = 5 * 4096;
  measure("random", random_points(kPoints, state), calls);
  measure("sphere", sphere_points(kPoints, 0.0, state), calls);
  measure("sphere_far", sphere_points(kPoints, 1e6, state), calls);
  measure("plane", plane_points(kPoints, state), calls);
  measure("cospherical", cospherical_points(kPoints, state), calls);
  return 0;
}
