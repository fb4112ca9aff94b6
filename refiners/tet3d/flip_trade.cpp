// Flip trades judged by the trade rules of the polish (flip_trade.h; notes §2.2.4).
#include "refiners/tet3d/flip_trade.h"

#include <algorithm>
#include <array>
#include <limits>

#include "toolkit/predicates/predicates.h"
#include "toolkit/quality/tet_quality.h"
#include "toolkit/tetmesh/ring_triangulation.h"
#include "toolkit/tetmesh/tet_flips.h"

namespace delmesh::tet3d {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
/// The score of a new tet touching a small angle that keeps the trade's floors: above
/// every window dihedral sine, so only the tets touching none rank a triangulation.
constexpr double kKeptFloor = 2.0;

using Quad = std::array<std::uint32_t, 4>;

bool positive(const TetMesh& mesh, const Quad& q) {
  return predicates::orient3d(mesh.coords(q[0]), mesh.coords(q[1]), mesh.coords(q[2]), mesh.coords(q[3])) ==
         Sign::Positive;
}

/// What the old tets of a flip allow its new tets (flip_trade.h's rules).
class TradeJudge {
 public:
  TradeJudge(const RefineState& state, const FlipTradeRules& rules) : state_(state), rules_(rules) {}

  /// Takes in the old tets; false where they may not be traded (not one region of the
  /// domain, no tet touching none outside the window, or a flat tet touching a small angle).
  bool read(const std::vector<std::uint32_t>& tets) {
    const TetMesh& mesh = state_.mesh;
    region_ = kRegionUnknown;
    double least_small = kInf, smallest = rules_.trade_min_deg, largest = rules_.trade_max_deg;
    bool bad_free = false;
    free_worst_ = kInf;
    free_breakers_ = 0;
    free_outside_ = 0;
    small_breakers_ = 0;
    small_points_.clear();
    for (const std::uint32_t t : tets) {
      if (t >= mesh.tet_slots() || mesh.is_dead(t) || mesh.is_infinite(t) || t >= state_.tet_region.size())
        return false;
      const int region = state_.tet_region[t];
      if (!in_domain(region) || (region_ != kRegionUnknown && region != region_)) return false;
      region_ = region;
      const auto& v = mesh.tet(t).v;
      const std::array<Vec3, 4> p{mesh.point(v[0]), mesh.point(v[1]), mesh.point(v[2]), mesh.point(v[3])};
      const double sine = min_window_dihedral_sine(p[0], p[1], p[2], p[3], rules_.obtuse_scale);
      bool touches = false;
      for (int k = 0; k < 4; ++k)
        if (small(v[k])) {
          touches = true;
          small_points_.push_back(p[k]);
        }
      if (touches) {
        least_small = std::min(least_small, sine);
        small_breakers_ += sine > 0.0 && rules_.breaks_bounds(region, p[0], p[1], p[2], p[3]) ? 1 : 0;
        const auto [lo, hi] = dihedral_extremes_deg(p[0], p[1], p[2], p[3]);
        smallest = std::min(smallest, lo);
        largest = std::max(largest, hi);
      } else {
        const bool outside = dihedral_outside(p[0], p[1], p[2], p[3], rules_.low_deg, rules_.high_deg);
        bad_free = bad_free || outside;
        free_outside_ += outside ? 1 : 0;
        const bool breaker = sine > 0.0 && rules_.breaks_bounds(region, p[0], p[1], p[2], p[3]);
        free_breakers_ += breaker ? 1 : 0;
        free_worst_ = std::min(free_worst_, breaker ? -1.0 + sine : sine);
      }
    }
    if (!bad_free || !(least_small > 0.0)) return false;
    floor_ = rules_.trade_fraction * least_small;
    smallest_ = smallest;
    largest_ = largest;
    return true;
  }

  int region() const { return region_; }
  /// The score a triangulation's worst new tet must exceed.
  double threshold() const { return free_worst_ + rules_.min_gain; }

  /// The score of a new tet: its window dihedral sine if it touches no small angle and
  /// lies inside the window, kKeptFloor if it touches one and keeps the rules, -infinity
  /// otherwise (a new tet that breaks a bound is counted by breakers_kept, except one
  /// touching a small angle where no old tet touching one broke a bound: -infinity).
  double score(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) const {
    const double sine = min_window_dihedral_sine(a, b, c, d, rules_.obtuse_scale);
    if (!(sine > 0.0)) return -kInf;
    bool touches = false;
    for (const Vec3& x : small_points_) touches = touches || x == a || x == b || x == c || x == d;
    if (touches) {
      if (sine < floor_) return -kInf;
      const auto [lo, hi] = dihedral_extremes_deg(a, b, c, d);
      if (lo < smallest_ || hi > largest_) return -kInf;
      return small_breakers_ == 0 && rules_.breaks_bounds(region_, a, b, c, d) ? -kInf : kKeptFloor;
    }
    return sine;
  }

  /// Do the new tets `quads` (of scores above the threshold) break a bound no more often
  /// than the old tets did, those touching no small angle and those touching one each
  /// counted apart, and lie outside the window away from small angles no more often?
  bool breakers_kept(const TetMesh& mesh, const std::vector<Quad>& quads) const {
    int breakers = 0, outside = 0, small_breakers = 0;
    for (const Quad& q : quads) {
      const Vec3 &a = mesh.point(q[0]), &b = mesh.point(q[1]), &c = mesh.point(q[2]), &d = mesh.point(q[3]);
      bool touches = false;
      for (const Vec3& x : small_points_) touches = touches || x == a || x == b || x == c || x == d;
      if (touches) {
        small_breakers += rules_.breaks_bounds(region_, a, b, c, d) ? 1 : 0;
        continue;
      }
      breakers += rules_.breaks_bounds(region_, a, b, c, d) ? 1 : 0;
      outside += dihedral_outside(a, b, c, d, rules_.low_deg, rules_.high_deg) ? 1 : 0;
    }
    return breakers <= free_breakers_ && outside <= free_outside_ && small_breakers <= small_breakers_;
  }

 private:
  bool small(std::uint32_t v) const {
    return rules_.at_small_angle != nullptr && v < rules_.at_small_angle->size() && (*rules_.at_small_angle)[v] != 0;
  }

  const RefineState& state_;
  const FlipTradeRules& rules_;
  int region_ = kRegionUnknown;
  int free_breakers_ = 0;  ///< old tets touching none that break a bound
  int free_outside_ = 0;   ///< old tets touching none outside the window
  int small_breakers_ = 0;  ///< old tets touching a small angle that break a bound
  double free_worst_ = kInf, floor_ = 0.0, smallest_ = 0.0, largest_ = 180.0;
  /// The points of the old tets' vertices touching a small angle (the objective sees
  /// points, and no two vertices of a valid mesh share one).
  std::vector<Vec3> small_points_;
};

}  // namespace

bool trade_remove_edge(RefineState& state, const FlipTradeRules& rules, std::uint32_t a, std::uint32_t b,
                       std::vector<std::uint32_t>& created, int& region) {
  TetMesh& mesh = state.mesh;
  if (state.subsegments.count(edge_key(a, b))) return false;
  std::vector<std::uint32_t> tets, ring;
  if (!mesh.tets_around_edge(a, b, tets, &ring) || ring.size() < 3 || ring.size() > rules.max_ring) return false;
  for (const std::uint32_t x : ring)
    if (x == kInfiniteVertex || state.subfaces.count(face_key(a, b, x))) return false;
  TradeJudge judge(state, rules);
  if (!judge.read(tets)) return false;
  // The triangulation remove_edge will choose (the same dynamic programming over the same
  // scores and exact orientations, toolkit/tetmesh), planned first for the count of
  // bound breakers.
  const double threshold = judge.threshold();
  const auto triangle_score = [&](int i, int j, int k) {
    const std::array<Quad, 2> q{Quad{ring[i], ring[j], ring[k], b}, Quad{ring[j], ring[i], ring[k], a}};
    double worst = kInf;
    for (const Quad& x : q) {
      worst = std::min(worst, judge.score(mesh.point(x[0]), mesh.point(x[1]), mesh.point(x[2]), mesh.point(x[3])));
      if (!(worst > threshold)) return worst;
    }
    if (!positive(mesh, q[0]) || !positive(mesh, q[1])) return -kInf;
    return worst;
  };
  std::vector<std::array<int, 3>> triangles;
  if (best_ring_triangulation(static_cast<int>(ring.size()), threshold, triangle_score, triangles) == -kInf)
    return false;
  std::vector<Quad> quads;
  for (const auto& [i, k, j] : triangles) {
    quads.push_back({ring[i], ring[k], ring[j], b});
    quads.push_back({ring[k], ring[i], ring[j], a});
  }
  if (!judge.breakers_kept(mesh, quads)) return false;
  const TetQualityFn objective = [&judge](const Vec3& p, const Vec3& q, const Vec3& r, const Vec3& s) {
    return judge.score(p, q, r, s);
  };
  created.clear();
  if (!remove_edge(mesh, a, b, judge.threshold(), &created, objective)) return false;
  region = judge.region();
  return true;
}

bool trade_flip23(RefineState& state, const FlipTradeRules& rules, std::uint32_t t, int f,
                  std::vector<std::uint32_t>& created, int& region) {
  TetMesh& mesh = state.mesh;
  const std::array<std::uint32_t, 4> v = mesh.tet(t).v;
  const auto& o = kFaceVertex[f];
  if (state.subfaces.count(face_key(v[o[0]], v[o[1]], v[o[2]]))) return false;
  const std::uint32_t u = mesh.neighbor(t, f);
  TradeJudge judge(state, rules);
  if (!judge.read({t, u})) return false;
  const std::uint32_t apex = mesh.opposite_vertex({t, static_cast<std::uint8_t>(f)});
  double worst = kInf;
  std::vector<Quad> quads;
  for (const std::uint8_t k : o) {
    Quad q = v;
    q[k] = apex;
    worst = std::min(worst, judge.score(mesh.point(q[0]), mesh.point(q[1]), mesh.point(q[2]), mesh.point(q[3])));
    quads.push_back(q);
  }
  if (!(worst > judge.threshold()) || !judge.breakers_kept(mesh, quads)) return false;
  created.clear();
  if (!flip23(mesh, {t, static_cast<std::uint8_t>(f)}, &created)) return false;
  region = judge.region();
  return true;
}

}  // namespace delmesh::tet3d
