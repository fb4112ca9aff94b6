// Insertion order for randomized incremental Delaunay construction: biased randomized
// insertion order (BRIO, Amenta, Choi and Rote 2003) with each round sorted along a
// Hilbert curve, so that consecutive points are close and the walking point location
// takes O(1) steps on average (notes §2.1.5-2.1.6).
#pragma once

#include <cstdint>
#include <vector>

#include "toolkit/mesh2d/pslg.h"

namespace delmesh::mesh2d {

/// Hilbert index of cell (x, y) on a 2^order x 2^order grid (order <= 16).
std::uint32_t hilbert_index(std::uint32_t x, std::uint32_t y, int order);

/// A permutation of 0..points.size()-1: rounds of geometrically growing size (each
/// round about 8 times the previous one, points drawn at random with a fixed seed so
/// the result is deterministic), each round in Hilbert order.
std::vector<std::uint32_t> brio_hilbert_order(const std::vector<Point2>& points,
                                              std::uint64_t seed = 0x9E3779B97F4A7C15ull);

}  // namespace delmesh::mesh2d
