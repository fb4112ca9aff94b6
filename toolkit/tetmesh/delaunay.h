// The library call for 3D Delaunay tetrahedralization of a point set (notes §2.1.3,
// §2.1.5): bulk incremental Bowyer–Watson insertion in BRIO/Hilbert order into a
// TetMesh (toolkit/tetmesh), with exact predicates and symbolic perturbation, so the
// result is a valid Delaunay tetrahedralization for every input, cospherical or not.
//
// Contract
//   - Points are used bit for bit. Every coordinate must be finite with magnitude at most
//     1e140 (the range in which the predicates are exact), else InvalidInput naming the
//     point.
//   - Duplicates are MERGED, not refused: of several points at exactly the same position
//     the one with the lowest input index is kept; the others appear in no tet and are
//     listed in `duplicate_of`; `num_duplicates` counts them.
//   - Fewer than four distinct points, or all points collinear or coplanar: an Error with
//     code DegenerateInput and a message saying which ("all 12 points are coplanar").
//   - Output tets are positively oriented (orient3d Positive, predicates.h convention).
//     Among cospherical points the tetrahedralization chosen is the one the symbolic
//     perturbation of insphere_sos defines (it depends on the point indices only), so the
//     output is deterministic: same input, same output.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "toolkit/core/error.h"
#include "toolkit/core/log.h"
#include "toolkit/geometry/vec3.h"
#include "toolkit/tetmesh/tet_mesh.h"

namespace delmesh {

struct DelaunayOptions {
  /// Insert in BRIO + Hilbert order (fast); false inserts in input order (slow on large
  /// inputs, useful to test the kernel).
  bool spatial_sort = true;
  /// Seed of the BRIO shuffle.
  std::uint64_t seed = 0x5EEDu;
  /// Progress and statistics; nullptr: silent.
  LogSink* log = nullptr;
};

struct DelaunayResult {
  /// Vertex i + 1 of the mesh is input point i (vertex 0 is the infinite vertex). The
  /// mesh holds finite and infinite tets; dead slots are compacted away.
  TetMesh mesh;
  /// Empty when there are no duplicates; otherwise one entry per input point: kNone, or
  /// the index of the input point at the same position that was kept.
  std::vector<std::uint32_t> duplicate_of;
  std::size_t num_duplicates = 0;
};

/// Delaunay tetrahedralization of `points` as a TetMesh (for further kernel work). The
/// mesh stores a copy of the points.
Expected<DelaunayResult> delaunay_tetrahedralize(std::span<const Vec3> points,
                                                 const DelaunayOptions& options = {});

/// The same, taking the caller's array instead of copying it (pass it with std::move;
/// it is left empty, on error too): the mesh is built in it, which saves one copy of the
/// points at the peak of memory use. The points stay available as
/// result.mesh.point(i + 1).
Expected<DelaunayResult> delaunay_tetrahedralize(std::vector<Vec3>&& points,
                                                 const DelaunayOptions& options = {});

/// Plain output: tets as four 0-based indices into the input array, positively oriented.
struct TetList {
  std::vector<std::array<std::uint32_t, 4>> tets;
  std::vector<std::uint32_t> duplicate_of;  ///< as in DelaunayResult
  std::size_t num_duplicates = 0;
};

/// Delaunay tetrahedralization of `points` as a plain list of tets.
Expected<TetList> delaunay_tet_list(std::span<const Vec3> points,
                                    const DelaunayOptions& options = {});

/// The finite tets of a mesh built by delaunay_tetrahedralize, as 0-based input indices.
std::vector<std::array<std::uint32_t, 4>> finite_tets_as_input_indices(const TetMesh& mesh);

}  // namespace delmesh
