// Radius-edge polish (see radius_edge_polish.h).
#include "refiners/tet3d/radius_edge_polish.h"

#include <algorithm>
#include <array>
#include <limits>
#include <optional>

#include "refiners/tet3d/unmet_tets.h"
#include "toolkit/predicates/predicates.h"
#include "toolkit/quality/tet_quality.h"

namespace delmesh::tet3d {

namespace {

/// The 26 directions toward the neighbours of a cube's centre, of unit length.
std::array<Vec3, 26> compass_directions() {
  std::array<Vec3, 26> directions;
  std::size_t k = 0;
  for (int x = -1; x <= 1; ++x)
    for (int y = -1; y <= 1; ++y)
      for (int z = -1; z <= 1; ++z)
        if (x != 0 || y != 0 || z != 0) directions[k++] = Vec3(x, y, z).normalized();
  return directions;
}

/// A tet of the star of the vertex being moved, as it was before the move.
struct StarTet {
  std::array<Vec3, 4> p;
  int local = 0;  ///< index of the moved vertex in p
  bool away = false;  ///< touches no small input angle
  double ratio = 0.0;
  bool met = false;  ///< meets the radius-edge bound and the volume bounds
  bool inside = false;  ///< inside the dihedral window
  double window_sine = 0.0;
};

class Polisher {
 public:
  Polisher(RefineState& state, const std::vector<std::uint8_t>& small_angle, double low_deg, double high_deg)
      : state_(state),
        mesh_(state.mesh),
        small_angle_(small_angle),
        low_(low_deg),
        high_(high_deg),
        obtuse_scale_(window_obtuse_scale(low_deg, high_deg)) {}

  bool away_and_above(std::uint32_t t) const {
    if (mesh_.is_dead(t) || mesh_.is_infinite(t) || !in_domain(state_.tet_region[t]) || small_angle_[t] != 0)
      return false;
    const auto& v = mesh_.tet(t).v;
    return !(radius_edge_ratio(mesh_.point(v[0]), mesh_.point(v[1]), mesh_.point(v[2]), mesh_.point(v[3])) <= bound());
  }

  /// Moves the interior vertices of tet t while a move lowers the star's worst ratio
  /// away from small angles; the number of moves made.
  std::size_t polish(std::uint32_t t) {
    std::size_t moves = 0;
    const std::array<std::uint32_t, 4> vertices = mesh_.tet(t).v;
    for (const std::uint32_t v : vertices) {
      if (!away_and_above(t)) break;
      if (state_.vertices[v].kind != VertexKind::Interior || !gather_star(v, state_.tet_region[t])) continue;
      const auto& q = mesh_.tet(t).v;
      const double shortest = shortest_edge(mesh_.point(q[0]), mesh_.point(q[1]), mesh_.point(q[2]), mesh_.point(q[3]));
      if (const auto p = search(mesh_.point(v), shortest / 4.0)) {
        mesh_.move_point(v, *p);
        ++moves;
      }
    }
    return moves;
  }

 private:
  double bound() const { return state_.options.max_radius_edge; }

  /// Fills star_ with v's star; false when a tet of it is infinite or lies outside `region`.
  bool gather_star(std::uint32_t v, int region) {
    mesh_.star(v, star_ids_);
    star_.clear();
    for (const std::uint32_t s : star_ids_) {
      if (mesh_.is_infinite(s) || state_.tet_region[s] != region) return false;
      StarTet st;
      const auto& w = mesh_.tet(s).v;
      for (int i = 0; i < 4; ++i) {
        st.p[i] = mesh_.point(w[i]);
        if (w[i] == v) st.local = i;
      }
      st.away = small_angle_[s] == 0;
      st.ratio = radius_edge_ratio(st.p[0], st.p[1], st.p[2], st.p[3]);
      st.met = meets_bounds(region, st.p, st.ratio);
      st.inside = !dihedral_outside(st.p[0], st.p[1], st.p[2], st.p[3], low_, high_);
      st.window_sine = min_window_dihedral_sine(st.p[0], st.p[1], st.p[2], st.p[3], obtuse_scale_);
      star_.push_back(st);
    }
    region_ = region;
    return !star_.empty();
  }

  bool meets_bounds(int region, const std::array<Vec3, 4>& p, double r) const {
    if (!(r <= bound())) return false;
    return !misses_volume_bound(state_, region, p[0], p[1], p[2], p[3]);
  }

  /// The objective at p (the largest ratio of the star's tets touching no small angle),
  /// or nothing where p breaks a rule of radius_edge_polish.h.
  std::optional<double> objective(const Vec3& p) const {
    double worst = 0.0;
    for (const StarTet& st : star_) {
      std::array<Vec3, 4> q = st.p;
      q[st.local] = p;
      if (predicates::orient3d(q[0].data(), q[1].data(), q[2].data(), q[3].data()) != Sign::Positive)
        return std::nullopt;
      const double r = radius_edge_ratio(q[0], q[1], q[2], q[3]);
      if (st.met ? !meets_bounds(region_, q, r) : !(r <= st.ratio)) return std::nullopt;
      if (st.inside ? dihedral_outside(q[0], q[1], q[2], q[3], low_, high_)
                    : !(min_window_dihedral_sine(q[0], q[1], q[2], q[3], obtuse_scale_) >= st.window_sine))
        return std::nullopt;
      if (st.away) worst = std::max(worst, r);
    }
    return worst;
  }

  /// The compass search from `origin`; the point reached where it gains at least
  /// kPolishMinGain.
  std::optional<Vec3> search(const Vec3& origin, double step) const {
    const std::optional<double> start = objective(origin);
    if (!start) return std::nullopt;  // a star that already breaks a rule (a flat tet): left as it is
    Vec3 p = origin;
    double value = *start;
    int halvings = 0;
    for (int k = 0; k < kPolishSteps && halvings <= kPolishHalvings; ++k) {
      Vec3 best = p;
      double best_value = value;
      for (const Vec3& d : directions_) {
        const Vec3 q = p + step * d;
        const std::optional<double> f = objective(q);
        if (f && *f < best_value) {
          best = q;
          best_value = *f;
        }
      }
      if (best_value < value) {
        p = best;
        value = best_value;
      } else {
        step /= 2.0;
        ++halvings;
      }
    }
    if (!(value <= *start - kPolishMinGain)) return std::nullopt;
    return p;
  }

  RefineState& state_;
  TetMesh& mesh_;
  const std::vector<std::uint8_t>& small_angle_;
  const double low_, high_, obtuse_scale_;
  const std::array<Vec3, 26> directions_ = compass_directions();
  std::vector<std::uint32_t> star_ids_;
  std::vector<StarTet> star_;
  int region_ = 0;
};

}  // namespace

RadiusEdgePolishStats polish_radius_edge(RefineState& state, const std::vector<std::uint8_t>& small_angle,
                                         double low_deg, double high_deg) {
  RadiusEdgePolishStats stats;
  Polisher polisher(state, small_angle, low_deg, high_deg);
  std::vector<std::uint32_t> tets;
  for (std::uint32_t t = 0; t < state.mesh.tet_slots(); ++t)
    if (polisher.away_and_above(t)) tets.push_back(t);
  stats.tets_before = tets.size();
  for (const std::uint32_t t : tets) stats.moves += polisher.polish(t);
  for (const std::uint32_t t : tets) stats.tets_after += polisher.away_and_above(t) ? 1 : 0;
  return stats;
}

}  // namespace delmesh::tet3d
