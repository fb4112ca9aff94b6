// TetMesh validators (see tet_check.h).
#include "toolkit/tetmesh/tet_check.h"

#include <algorithm>
#include <array>

#include "toolkit/predicates/predicates.h"

namespace delmesh {

namespace {

// Is (x', y', z') a cyclic rotation of (x, z, y), i.e. the same triangle reversed?
bool reversed_face(const std::array<std::uint32_t, 3>& a, const std::array<std::uint32_t, 3>& b) {
  const std::array<std::uint32_t, 3> r{a[0], a[2], a[1]};
  for (int s = 0; s < 3; ++s) {
    if (b[0] == r[s] && b[1] == r[(s + 1) % 3] && b[2] == r[(s + 2) % 3]) return true;
  }
  return false;
}

struct IssueList {
  std::vector<MeshIssue> issues;
  std::size_t max;
  bool full() const { return issues.size() >= max; }
  void add(std::uint32_t tet, std::uint32_t vertex, std::string message) {
    if (!full()) issues.push_back({tet, vertex, std::move(message)});
  }
};

std::string tet_text(const TetMesh& mesh, std::uint32_t t) {
  const auto& v = mesh.tet(t).v;
  return "tet " + std::to_string(t) + " (" + std::to_string(v[0]) + " " + std::to_string(v[1]) +
         " " + std::to_string(v[2]) + " " + std::to_string(v[3]) + ")";
}

}  // namespace

std::vector<MeshIssue> check_topology(const TetMesh& mesh, std::size_t max_issues) {
  IssueList out{{}, max_issues};
  const std::uint32_t nv = mesh.num_vertices();
  const std::uint32_t slots = mesh.tet_slots();
  std::vector<std::uint32_t> incidence(nv, 0);
  for (std::uint32_t t = 0; t < slots && !out.full(); ++t) {
    if (mesh.is_dead(t)) continue;
    const TetRecord& r = mesh.tet(t);
    bool ids_ok = true;
    for (int i = 0; i < 4; ++i) {
      if (r.v[i] >= nv) ids_ok = false;
      for (int j = 0; j < i; ++j) ids_ok = ids_ok && r.v[i] != r.v[j];
    }
    if (!ids_ok) {
      out.add(t, kNone, tet_text(mesh, t) + ": invalid or repeated vertex ids");
      continue;
    }
    for (const std::uint32_t v : r.v) ++incidence[v];
    for (int f = 0; f < 4; ++f) {
      if (r.adj[f] == kNone) {
        out.add(t, kNone, tet_text(mesh, t) + ": face " + std::to_string(f) + " is not glued");
        continue;
      }
      const std::uint32_t u = r.adj[f] >> 2;
      const int j = static_cast<int>(r.adj[f] & 3u);
      if (u >= slots || mesh.is_dead(u)) {
        out.add(t, kNone, tet_text(mesh, t) + ": face " + std::to_string(f) + " glued to a dead tet");
        continue;
      }
      if (mesh.tet(u).adj[j] != ((t << 2) | static_cast<std::uint32_t>(f))) {
        out.add(t, kNone, tet_text(mesh, t) + ": face " + std::to_string(f) +
                              " is not glued back by " + tet_text(mesh, u));
        continue;
      }
      if (!reversed_face(mesh.face_vertices({t, static_cast<std::uint8_t>(f)}),
                         mesh.face_vertices({u, static_cast<std::uint8_t>(j)}))) {
        out.add(t, kNone, tet_text(mesh, t) + ": face " + std::to_string(f) +
                              " does not match the glued face of " + tet_text(mesh, u));
      }
    }
    if (mesh.is_finite(t) &&
        predicates::orient3d(mesh.coords(r.v[0]), mesh.coords(r.v[1]), mesh.coords(r.v[2]),
                             mesh.coords(r.v[3])) != Sign::Positive) {
      out.add(t, kNone, tet_text(mesh, t) + ": not positively oriented");
    }
  }
  if (!out.issues.empty()) return out.issues;

  // No two tets with the same vertex set.
  {
    std::vector<std::array<std::uint32_t, 4>> keys;
    keys.reserve(mesh.num_live_tets());
    for (std::uint32_t t = 0; t < slots; ++t) {
      if (mesh.is_dead(t)) continue;
      auto k = mesh.tet(t).v;
      std::sort(k.begin(), k.end());
      keys.push_back(k);
    }
    std::sort(keys.begin(), keys.end());
    for (std::size_t k = 1; k < keys.size() && !out.full(); ++k) {
      if (keys[k] == keys[k - 1]) {
        out.add(kNone, keys[k][0], "two tets share the vertex set (" + std::to_string(keys[k][0]) +
                                       " " + std::to_string(keys[k][1]) + " " +
                                       std::to_string(keys[k][2]) + " " +
                                       std::to_string(keys[k][3]) + ")");
      }
    }
  }

  // vertex_tet and connectivity of each star: a breadth-first search over the faces
  // through v from vertex_tet(v) must reach every tet holding v.
  std::vector<std::uint32_t> seen(slots, kNone);
  std::vector<std::uint32_t> queue;
  for (std::uint32_t v = 0; v < nv && !out.full(); ++v) {
    const std::uint32_t start = mesh.vertex_tet(v);
    if (incidence[v] == 0) {
      if (start != kNone && v != kInfiniteVertex) {
        out.add(kNone, v, "vertex " + std::to_string(v) + " is in no tet but has vertex_tet set");
      }
      continue;
    }
    if (start == kNone || start >= slots || mesh.is_dead(start) || mesh.local_index(start, v) < 0) {
      out.add(kNone, v, "vertex " + std::to_string(v) + ": vertex_tet does not hold it");
      continue;
    }
    queue.assign(1, start);
    seen[start] = v;
    for (std::size_t k = 0; k < queue.size(); ++k) {
      const TetRecord& r = mesh.tet(queue[k]);
      for (int f = 0; f < 4; ++f) {
        if (r.v[f] == v) continue;
        const std::uint32_t n = r.adj[f] >> 2;
        if (seen[n] == v) continue;
        seen[n] = v;
        queue.push_back(n);
      }
    }
    if (queue.size() != incidence[v]) {
      out.add(kNone, v, "vertex " + std::to_string(v) + ": its star is not connected (" +
                            std::to_string(queue.size()) + " of " +
                            std::to_string(incidence[v]) + " tets reachable)");
    }
  }
  return out.issues;
}

std::vector<MeshIssue> check_delaunay(const TetMesh& mesh, std::size_t max_issues, bool symbolic) {
  IssueList out{{}, max_issues};
  const std::uint32_t slots = mesh.tet_slots();
  for (std::uint32_t t = 0; t < slots && !out.full(); ++t) {
    if (mesh.is_dead(t)) continue;
    const TetRecord& r = mesh.tet(t);
    const int k = mesh.infinite_index(t);
    if (k < 0) {
      for (int f = 0; f < 4; ++f) {
        const std::uint32_t u = r.adj[f] >> 2;
        if (u < t || mesh.is_infinite(u)) continue;  // each interior face once
        const std::uint32_t e = mesh.tet(u).v[r.adj[f] & 3u];
        const double* pe = mesh.coords(e);
        const Sign s =
            symbolic ? predicates::insphere_sos(mesh.coords(r.v[0]), mesh.coords(r.v[1]),
                                                mesh.coords(r.v[2]), mesh.coords(r.v[3]), pe,
                                                mesh.perturbation_id(r.v[0]),
                                                mesh.perturbation_id(r.v[1]),
                                                mesh.perturbation_id(r.v[2]),
                                                mesh.perturbation_id(r.v[3]),
                                                mesh.perturbation_id(e))
                     : predicates::insphere(mesh.coords(r.v[0]), mesh.coords(r.v[1]),
                                            mesh.coords(r.v[2]), mesh.coords(r.v[3]), pe);
        if (s == Sign::Positive || (symbolic && s != Sign::Negative)) {
          out.add(t, e, tet_text(mesh, t) + ": vertex " + std::to_string(e) +
                            " of its neighbour is inside its circumsphere");
        }
      }
      continue;
    }
    // Hull convexity: the neighbouring hull faces bend away from this one.
    const auto& o = kFaceVertex[k];
    for (int f = 0; f < 4; ++f) {
      if (f == k) continue;
      const std::uint32_t x = mesh.tet(r.adj[f] >> 2).v[r.adj[f] & 3u];
      if (predicates::orient3d(mesh.coords(r.v[o[0]]), mesh.coords(r.v[o[1]]),
                               mesh.coords(r.v[o[2]]), mesh.coords(x)) == Sign::Positive) {
        out.add(t, x, tet_text(mesh, t) + ": hull vertex " + std::to_string(x) +
                          " lies beyond this hull face (hull not convex)");
      }
    }
  }
  return out.issues;
}

}  // namespace delmesh
