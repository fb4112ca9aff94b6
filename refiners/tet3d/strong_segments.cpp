// Strongly Delaunay edges (see strong_segments.h; notes §2.1.4).
#include "refiners/tet3d/strong_segments.h"

#include "toolkit/predicates/predicates.h"

namespace delmesh::tet3d {

bool strongly_delaunay_edge(TetMesh& mesh, std::uint32_t a, std::uint32_t b, std::vector<std::uint32_t>& tets,
                            std::vector<std::uint32_t>& ring) {
  if (!mesh.tets_around_edge(a, b, tets, &ring)) return false;
  const std::size_t m = ring.size();
  if (m < 3) return false;
  const double* pa = mesh.coords(a);
  const double* pb = mesh.coords(b);
  std::size_t changes = 0;
  // Tets k and k+1 share the face (a, b, ring[k+1]); their other vertices are ring[k]
  // and ring[k+2].
  for (std::size_t k = 0; k < m && changes < 3; ++k) {
    const std::uint32_t u = ring[k], s = ring[(k + 1) % m], w = ring[(k + 2) % m];
    bool same_sphere = false;
    if (s == kInfiniteVertex) {
      same_sphere = predicates::orient3d(pa, pb, mesh.coords(u), mesh.coords(w)) == Sign::Zero;
    } else if (u != kInfiniteVertex && w != kInfiniteVertex) {
      same_sphere =
          predicates::insphere(pa, pb, mesh.coords(u), mesh.coords(s), mesh.coords(w)) == Sign::Zero;
    }
    if (!same_sphere) ++changes;
  }
  return changes >= 3;
}

}  // namespace delmesh::tet3d
