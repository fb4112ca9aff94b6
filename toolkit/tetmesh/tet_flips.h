// Topological flips of a TetMesh (notes §2.1.3, Figures 2.19 and 2.20; §2.2.4 on
// topological transformations): the 2-3 and 3-2 flips, the 4-4 flip, and edge removal
// (Shewchuk, "Two discrete optimization algorithms for the topological improvement of
// tetrahedral meshes", 2002), which replaces the m tets around an edge by 2(m-2) tets
// built on a triangulation of the edge's ring chosen by dynamic programming (Klincsek
// 1980) to maximize the worst new tet.
//
// Every flip checks its geometric validity exactly before changing anything: each new
// tet must be positively oriented (orient3d), which holds exactly when the new tets fill
// the same region as the old ones (for the 2-3 flip: the edge between the two apexes
// crosses the interior of the shared face; for the 3-2 flip: the edge crosses the
// triangle of its ring). A flip that fails its check returns false and leaves the mesh
// untouched. Flips act on finite tets only (the hull is never changed); they keep the
// mesh valid but not necessarily Delaunay — that is the caller's business (facet
// recovery, sliver removal).
#pragma once

#include <cstdint>
#include <functional>
#include <limits>
#include <vector>

#include "toolkit/geometry/vec3.h"
#include "toolkit/tetmesh/tet_mesh.h"

namespace delmesh {

/// 2-3 flip of `face` (shared by face.tet and its neighbour): the two tets become three
/// around the edge joining their apexes. `created` (optional) receives the new tets.
bool flip23(TetMesh& mesh, FaceRef face, std::vector<std::uint32_t>* created = nullptr);

/// 3-2 flip: edge (a, b), in exactly three tets, is replaced by the triangle of its ring;
/// the three tets become two.
bool flip32(TetMesh& mesh, std::uint32_t a, std::uint32_t b,
            std::vector<std::uint32_t>* created = nullptr);

/// 4-4 flip: edge (a, b), in exactly four tets whose ring is (c0, c1, c2, c3), is
/// replaced by the edge (c, e), where {c, e} is {c0, c2} or {c1, c3}. Valid when a, b, c,
/// e are coplanar with c, e on opposite sides of ab (Figure 2.20), and more generally
/// whenever the four new tets are positively oriented.
bool flip44(TetMesh& mesh, std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t e,
            std::vector<std::uint32_t>* created = nullptr);

/// Quality of a tet (a, b, c, d) for ranking flips; larger is better.
using TetQualityFn = std::function<double(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d)>;

/// Edge removal: replaces the m tets around edge (a, b) by the 2(m-2) tets joining a and
/// b to a triangulation of the ring, choosing among the valid triangulations the one
/// that maximizes the minimum quality of the new tets (`quality`, by default
/// tet_shape_quality). Flips only if that minimum exceeds `must_exceed` (pass the worst
/// quality of the current ring to improve it; the default accepts any valid
/// triangulation). m may be 3 (then it is a 3-2 flip) up to 64.
bool remove_edge(TetMesh& mesh, std::uint32_t a, std::uint32_t b,
                 double must_exceed = -std::numeric_limits<double>::infinity(),
                 std::vector<std::uint32_t>* created = nullptr, const TetQualityFn& quality = {});

/// Shape quality used to rank edge-removal candidates: 6*sqrt(2)*volume / l_rms^3, where
/// l_rms is the root mean square edge length; 1 for the regular tet, near 0 for slivers,
/// negative for inverted tets. A floating-point measure for ranking only; validity is
/// always decided by the exact predicates.
double tet_shape_quality(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d);

}  // namespace delmesh
