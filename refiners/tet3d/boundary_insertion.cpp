// What the polish's vertex insertions on the boundary share (see boundary_insertion.h).
#include "refiners/tet3d/boundary_insertion.h"

#include <algorithm>
#include <limits>

#include "refiners/tet3d/boundary_split.h"
#include "refiners/tet3d/small_angles.h"
#include "toolkit/predicates/predicates.h"
#include "toolkit/quality/tet_quality.h"

namespace delmesh::tet3d {

bool replay_facet_flips(const TetMesh& mesh, const FacetTriangulation& facet, const Vec3& p,
                        std::vector<FacetFlip> edges, std::vector<FaceKey>& removed, std::vector<FacetFlip>& flips) {
  flips.clear();
  const Axis axis = facet.axis();
  while (!edges.empty()) {
    const auto [x, y] = edges.back();
    edges.pop_back();
    if (facet.is_segment(x, y)) continue;
    const std::uint32_t z = facet.third_vertex(y, x);
    if (z == ~0u) continue;
    // The facet's coordinates are the tetrahedralization's (sliver_improvement.h).
    if (predicates::incircle_in_plane(mesh.coords(x), mesh.coords(y), p.data(), mesh.coords(z), axis,
                                      facet.normal().data()) != Sign::Positive)
      continue;
    if (predicates::orient2d_projected(mesh.coords(z), p.data(), mesh.coords(x), axis) != Sign::Positive ||
        predicates::orient2d_projected(p.data(), mesh.coords(z), mesh.coords(y), axis) != Sign::Positive)
      return false;
    removed.push_back(sorted_face_key(x, y, z));
    flips.push_back({x, y});
    edges.push_back({x, z});
    edges.push_back({z, y});
  }
  return true;
}

BoundaryInserter::BoundaryInserter(RefineState& state)
    : state_(state),
      mesh_(state.mesh),
      low_(state.options.min_dihedral_deg),
      high_(state.options.max_dihedral_deg),
      scale_(window_obtuse_scale(low_, high_)),
      small_(small_angle_vertices(state)) {}

std::size_t BoundaryInserter::run(std::size_t only) {
  bad_tets_.clear();
  for (std::uint32_t t = 0; t < mesh_.tet_slots(); ++t)
    if (mesh_.is_finite(t) && !mesh_.is_dead(t) && domain(t) && !touches_small(mesh_.tet(t).v) &&
        outside(mesh_.tet(t).v))
      bad_tets_.push_back(mesh_.tet(t).v);
  std::size_t made = 0;
  for (std::size_t k = 0; k < bad_tets_.size(); ++k) {
    if (only != kEveryTet && k != only) continue;
    const auto v = bad_tets_[k];
    const auto ref = find_face_ref(state_, v[0], v[1], v[2]);
    if (!ref) continue;
    std::uint32_t t = ref->tet;
    if (!has_vertex(t, v[3])) t = mesh_.neighbor(ref->tet, ref->face);
    if (mesh_.is_dead(t) || !mesh_.is_finite(t) || !has_vertex(t, v[3]) || !domain(t) || !outside(mesh_.tet(t).v))
      continue;
    if (try_tet(t)) ++made;
  }
  return made;
}

bool BoundaryInserter::domain(std::uint32_t t) const {
  return t < state_.tet_region.size() && in_domain(state_.tet_region[t]);
}

bool BoundaryInserter::has_vertex(std::uint32_t t, std::uint32_t x) const {
  const auto& v = mesh_.tet(t).v;
  return std::find(v.begin(), v.end(), x) != v.end();
}

bool BoundaryInserter::small(std::uint32_t x) const { return x < small_.size() && small_[x] != 0; }

bool BoundaryInserter::touches_small(const std::array<std::uint32_t, 4>& v) const {
  return std::any_of(v.begin(), v.end(), [&](std::uint32_t x) { return small(x); });
}

bool BoundaryInserter::outside(const std::array<std::uint32_t, 4>& v) const {
  return dihedral_outside(mesh_.point(v[0]), mesh_.point(v[1]), mesh_.point(v[2]), mesh_.point(v[3]), low_, high_);
}

bool BoundaryInserter::judge(const Vec3& p, double min_gain, double& margin, bool& acceptable) const {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  const Cavity& cavity = state_.cavity;
  const double bound = state_.options.max_radius_edge;
  double old_free = kInf, old_held = kInf, new_free = kInf, new_held = kInf;
  std::array<std::size_t, 2> old_bad{}, new_bad{};
  std::size_t old_breakers = 0, new_breakers = 0;
  for (const std::uint32_t u : cavity.tets) {
    if (!mesh_.is_finite(u) || !domain(u)) continue;
    const auto& w = mesh_.tet(u).v;
    const std::array<Vec3, 4> q{mesh_.point(w[0]), mesh_.point(w[1]), mesh_.point(w[2]), mesh_.point(w[3])};
    const bool held = touches_small(w);
    double& worst = held ? old_held : old_free;
    worst = std::min(worst, min_window_dihedral_sine(q[0], q[1], q[2], q[3], scale_));
    old_bad[held ? 1 : 0] += dihedral_outside(q[0], q[1], q[2], q[3], low_, high_) ? 1 : 0;
    old_breakers += radius_edge_ratio(q[0], q[1], q[2], q[3]) > bound ? 1 : 0;
  }
  for (const CavityFace& cf : cavity.boundary) {
    // The new tet: the cavity tet on this face with its opposite vertex replaced by p.
    const std::uint32_t inner_ref = mesh_.tet(cf.outside >> 2).adj[cf.outside & 3u];
    const std::uint32_t inner = inner_ref >> 2;
    std::array<std::uint32_t, 4> w = mesh_.tet(inner).v;
    const std::uint32_t replaced = inner_ref & 3u;
    bool infinite = false;
    for (std::uint32_t i = 0; i < 4; ++i) infinite = infinite || (i != replaced && w[i] == kInfiniteVertex);
    if (infinite) continue;  // a new hull face: by the cavity's exact visibility test
    std::array<Vec3, 4> q{mesh_.point(w[0]), mesh_.point(w[1]), mesh_.point(w[2]), mesh_.point(w[3])};
    q[replaced] = p;
    w[replaced] = kInfiniteVertex;  // the new vertex touches no small angle
    if (predicates::orient3d(q[0].data(), q[1].data(), q[2].data(), q[3].data()) != Sign::Positive) return false;
    if (!domain(inner)) continue;
    const bool held = touches_small(w);
    double& worst = held ? new_held : new_free;
    worst = std::min(worst, min_window_dihedral_sine(q[0], q[1], q[2], q[3], scale_));
    new_bad[held ? 1 : 0] += dihedral_outside(q[0], q[1], q[2], q[3], low_, high_) ? 1 : 0;
    new_breakers += radius_edge_ratio(q[0], q[1], q[2], q[3]) > bound ? 1 : 0;
  }
  const bool holds = old_held < old_free;
  margin = (holds ? new_free : std::min(new_free, new_held)) - old_free - min_gain;
  acceptable = new_bad[0] <= old_bad[0] && new_bad[1] <= old_bad[1] && new_breakers <= old_breakers &&
               (!holds || new_held >= old_held);
  return true;
}

}  // namespace delmesh::tet3d
