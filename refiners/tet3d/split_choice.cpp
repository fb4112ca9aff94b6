// Choice among the midpoint and shell split points of a subsegment (see split_choice.h;
// notes §3.8, §4.2.1).
#include "refiners/tet3d/split_choice.h"

#include <vector>

#include "refiners/tet3d/boundary_split.h"
#include "refiners/tet3d/concentric_shells.h"
#include "toolkit/predicates/predicates.h"

namespace delmesh::tet3d {

namespace {

/// The shell points of (apex, other) whose pieces are at least a quarter of it.
void add_shell_candidates(const RefineState& state, std::uint32_t apex, std::uint32_t other, double unit,
                          std::vector<Vec3>& out) {
  const Vec3& p0 = state.mesh.point(apex);
  const Vec3& p1 = state.mesh.point(other);
  const double length = (p1 - p0).norm();
  const double nearest = shell_split_distance(unit, length);
  if (!(nearest > 0.0)) return;
  for (const double d : {nearest, 0.5 * nearest, 2.0 * nearest}) {
    if (4.0 * d < length || 4.0 * d > 3.0 * length) continue;
    out.push_back(p0 + (d / length) * (p1 - p0));
  }
}

bool outside_diametral(const RefineState& state, std::uint32_t a, const Vec3& b, std::uint32_t w) {
  return predicates::dot3d(state.mesh.coords(a), b.data(), state.mesh.coords(w)) == Sign::Positive;
}

}  // namespace

Vec3 choose_subsegment_split(RefineState& state, std::uint32_t a, std::uint32_t b, std::uint32_t by) {
  const Vec3 usual = subsegment_split_point(state, a, b);
  const std::uint64_t key = edge_key(a, b);
  const auto it = state.subsegments.find(key);
  if (it == state.subsegments.end()) return usual;
  const SegmentData& seg = state.segments[it->second];
  std::vector<Vec3>& candidates = state.scratch_split_candidates;
  candidates.assign(1, usual);
  for (const std::uint32_t apex : {a, b}) {
    const std::uint32_t other = apex == a ? b : a;
    if (apex == seg.a && seg.shell_a) add_shell_candidates(state, apex, other, seg.shell_unit_a, candidates);
    if (apex == seg.b && seg.shell_b) add_shell_candidates(state, apex, other, seg.shell_unit_b, candidates);
  }
  candidates.push_back(0.5 * (state.mesh.point(a) + state.mesh.point(b)));
  std::vector<std::uint64_t>& encroached = state.scratch_encroached;
  for (std::size_t k = 0; k < candidates.size(); ++k) {
    const Vec3& c = candidates[k];
    if (k > 0 && (c == usual || below_split_resolution(state, a, b, c))) continue;
    if (by != kNone && (!outside_diametral(state, a, c, by) || !outside_diametral(state, b, c, by))) continue;
    if (!prepare_insertion(state, c, state.mesh.any_tet_of(a))) continue;
    cavity_encroached_subsegments(state, c, key, encroached);
    if (encroached.empty()) return c;
  }
  return usual;
}

}  // namespace delmesh::tet3d
