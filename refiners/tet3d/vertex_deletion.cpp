// Vertex deletion by edge contraction (see vertex_deletion.h; notes §2.2.4).
#include "refiners/tet3d/vertex_deletion.h"

#include "toolkit/core/error.h"
#include "toolkit/predicates/predicates.h"

namespace delmesh::tet3d {

bool plan_contraction(const TetMesh& mesh, std::span<const std::uint32_t> star, std::uint32_t v,
                      std::uint32_t u, Contraction& plan) {
  plan.v = v;
  plan.u = u;
  plan.star.assign(star.begin(), star.end());
  plan.tets.clear();
  plan.outside.clear();
  bool touches_u = false;
  for (const std::uint32_t t : star) {
    if (mesh.is_infinite(t)) return false;
    const TetRecord& r = mesh.tet(t);
    const int k = mesh.local_index(t, v);
    if (k < 0) return false;
    plan.outside.push_back(r.adj[k]);
    if (mesh.local_index(t, u) >= 0) {
      touches_u = true;
      continue;
    }
    std::array<std::uint32_t, 4> q = r.v;
    q[k] = u;
    if (predicates::orient3d(mesh.coords(q[0]), mesh.coords(q[1]), mesh.coords(q[2]), mesh.coords(q[3])) !=
        Sign::Positive)
      return false;
    plan.tets.push_back(q);
  }
  return touches_u && !plan.tets.empty();
}

void commit_contraction(TetMesh& mesh, const Contraction& plan, std::vector<std::uint32_t>& created) {
  for (const std::uint32_t t : plan.star) mesh.kill_tet(t);
  created.clear();
  for (const auto& q : plan.tets) created.push_back(mesh.create_tet(q[0], q[1], q[2], q[3]));
  const bool glued = mesh.glue_by_vertices(created, plan.outside);
  DELMESH_CHECK(glued, "vertex deletion: the contracted star's tets do not close up with the mesh");
  mesh.set_vertex_tet(plan.v, kNone);
  for (const std::uint32_t c : created)
    for (const std::uint32_t x : mesh.tet(c).v) mesh.set_vertex_tet(x, c);
}

}  // namespace delmesh::tet3d
