// Validators of a TetMesh: combinatorial and geometric consistency (check_topology) and
// the Delaunay property (check_delaunay), exact and local (notes §2.1.3: a triangulation
// whose every face is locally Delaunay is Delaunay — the "Delaunay lemma"). Used by the
// tests after every operation and by `delmesh delaunay --check`.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "toolkit/tetmesh/tet_mesh.h"

namespace delmesh {

struct MeshIssue {
  std::uint32_t tet = kNone;  ///< the tet concerned (kNone for a vertex-level issue)
  std::uint32_t vertex = kNone;
  std::string message;
};

/// Checks every live tet: vertex ids valid and distinct; every face glued to a live tet
/// whose glued face names it back and has the same three vertices in opposite
/// orientation; finite tets positively oriented (exact orient3d); no two tets with the
/// same vertex set; vertex_tet of each used vertex is a live tet holding it, and the star
/// of each vertex is connected (its link is one surface). Returns at most `max_issues`.
std::vector<MeshIssue> check_topology(const TetMesh& mesh, std::size_t max_issues = 20);

/// Checks, exactly, that every face between two finite tets is locally Delaunay (the
/// apex of one tet is not strictly inside the circumsphere of the other) and that the
/// hull is convex (no hull vertex strictly beyond a neighbouring hull face). With
/// `symbolic`, checks the perturbed property insphere_sos == Negative instead, which the
/// kernel's own output satisfies even on cospherical input. Assumes check_topology passed.
std::vector<MeshIssue> check_delaunay(const TetMesh& mesh, std::size_t max_issues = 20,
                                      bool symbolic = false);

}  // namespace delmesh
