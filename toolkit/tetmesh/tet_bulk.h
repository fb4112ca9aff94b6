// Insertion order for bulk Delaunay construction: biased randomized insertion order
// (BRIO; Amenta, Choi and Rote, "Incremental constructions con BRIO", 2003) with each
// round sorted along a Hilbert curve (the spatial sort of CGAL and geogram; notes §2.1.5
// and §2.1.6 on why a random order bounds the expected work and why locality speeds up
// point location).
//
// The points are shuffled (deterministically, from a seed), then split into rounds of
// geometrically growing size: the last round holds the last 7/8 of the shuffled points,
// the one before 7/8 of the rest, and so on. Each round is sorted by its points' index
// on a 3D Hilbert curve (21 bits per axis over the bounding cube of all points). Rounds
// keep the randomization that bounds the expected conflict sizes; the curve makes
// consecutive insertions close in space, so the location walk from the last new tet
// takes a few steps and the touched memory stays in cache.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "toolkit/geometry/vec3.h"

namespace delmesh {

/// 63-bit Hilbert index of the integer point (x, y, z), each coordinate < 2^21.
std::uint64_t hilbert_index(std::uint32_t x, std::uint32_t y, std::uint32_t z);

/// Sorts `indices` (into `points`) by the Hilbert index of the points within the bounding
/// cube of all `points`.
void hilbert_sort(std::span<const Vec3> points, std::span<std::uint32_t> indices);

/// The BRIO order of points 0 .. points.size()-1 (a permutation), deterministic for a
/// given seed.
std::vector<std::uint32_t> brio_order(std::span<const Vec3> points, std::uint64_t seed);

}  // namespace delmesh
