// The polish at the end of the improvement pass (refiners/tet3d/sliver_improvement.h,
// step 5): on refined states of the programmatic PLCs with windows the passes cannot
// meet everywhere, it never raises the count of tets outside the window, stays within
// its budget (improvement_schedule.h), keeps the mesh valid, and removes bad tets the
// passes left. Started from some tets (ImprovementTarget::start_tets), it leaves the tets
// outside the window far from them as they were.
#include <algorithm>
#include <array>
#include <cstdio>
#include <vector>

#include "refiners/tet3d/improvement_schedule.h"
#include "refiners/tet3d/sliver_improvement.h"
#include "refined_test_state.h"
#include "toolkit/tetmesh/tet_check.h"

namespace delmesh::test {
namespace {

using namespace delmesh::tet3d;

std::size_t outside_window(const RefineState& state, double low, double high) {
  std::size_t count = 0;
  for (std::uint32_t t = 0; t < state.mesh.tet_slots(); ++t) {
    if (state.mesh.is_dead(t) || state.mesh.is_infinite(t) || !in_domain(state.tet_region[t])) continue;
    const auto& v = state.mesh.tet(t).v;
    count += dihedral_outside(state.mesh.point(v[0]), state.mesh.point(v[1]), state.mesh.point(v[2]),
                              state.mesh.point(v[3]), low, high);
  }
  return count;
}

TEST(Tet3dPolish, NeverAddsBadTetsAndRemovesSomeThePassesLeft) {
  // Windows of 30 / 130 degrees (and the sharp wedge's small angles) leave tets outside
  // after the passes.
  std::size_t removed = 0, polished = 0;
  for (const TestPlc& input : all_test_plcs()) {
    MeshOptions options;
    if (!input.small_angles) options.max_volume = input.volume / 1000.0;
    options.min_dihedral_deg = 30.0;
    options.max_dihedral_deg = 130.0;
    RefineState state(input.plc, options);
    refine_for_improvement(state, input);
    const ImprovementStats stats = improve_slivers(state);
    std::printf("%-14s %zu -> %zu after the passes -> %zu after the polish (%zu tries)\n", input.name.c_str(),
                stats.bad_before, stats.bad_after_passes, stats.bad_after, stats.polish_tries);
    EXPECT_LE(stats.bad_after, stats.bad_after_passes) << input.name;
    EXPECT_LE(stats.polish_tries, kPolishTriesPerBadTet * stats.bad_after_passes) << input.name;
    EXPECT_EQ(stats.bad_after, outside_window(state, 30.0, 130.0)) << input.name;
    EXPECT_TRUE(check_topology(state.mesh).empty()) << input.name;
    for (const auto& [key, facet] : state.subfaces)
      EXPECT_TRUE(state.mesh.find_face(key[0], key[1], key[2]).has_value()) << input.name;
    removed += stats.bad_after_passes - stats.bad_after;
    polished += stats.polish_tries > 0;
  }
  EXPECT_GT(polished, 0u);
  EXPECT_GT(removed, 0u);
}


/// The vertices at most `rings` edges from `centres`.
std::vector<std::uint8_t> within_rings(TetMesh& mesh, const std::vector<std::uint32_t>& centres, int rings) {
  std::vector<std::uint8_t> near(mesh.num_vertices(), 0);
  std::vector<std::uint32_t> frontier = centres, next, neighbours;
  for (const std::uint32_t x : centres) near[x] = 1;
  for (int ring = 0; ring < rings; ++ring) {
    next.clear();
    for (const std::uint32_t x : frontier) {
      if (x == kInfiniteVertex) continue;
      mesh.vertex_neighbors(x, neighbours);
      for (const std::uint32_t y : neighbours)
        if (!near[y]) {
          near[y] = 1;
          next.push_back(y);
        }
    }
    frontier.swap(next);
  }
  return near;
}

TEST(Tet3dPolish, StartedFromSomeTetsLeavesTheFarOnesAsTheyWere) {
  // The polish alone (no tries for the passes' steps, as the improvement rounds run it)
  // started from the stars of one bad tet's vertices: the bad tets with no vertex within
  // four edges of that tet keep their vertices and points, which the polish from every
  // bad tet moves.
  std::size_t far_in_all = 0;
  for (const TestPlc& input : {unit_cube(), l_prism(), two_boxes()}) {
    MeshOptions options;
    options.max_volume = input.volume / 1000.0;
    options.min_dihedral_deg = 30.0;
    options.max_dihedral_deg = 130.0;
    RefineState state(input.plc, options);
    ASSERT_NO_FATAL_FAILURE(refine_for_improvement(state, input));
    std::vector<std::uint32_t> bad;
    for (std::uint32_t t = 0; t < state.mesh.tet_slots(); ++t)
      if (!state.mesh.is_dead(t) && !state.mesh.is_infinite(t) && in_domain(state.tet_region[t])) {
        const auto& v = state.mesh.tet(t).v;
        if (dihedral_outside(state.mesh.point(v[0]), state.mesh.point(v[1]), state.mesh.point(v[2]),
                             state.mesh.point(v[3]), 30.0, 130.0))
          bad.push_back(t);
      }
    ASSERT_GT(bad.size(), 10u) << input.name;
    const std::array<std::uint32_t, 4> centre = state.mesh.tet(bad.front()).v;
    const std::vector<std::uint32_t> centres(centre.begin(), centre.end());
    const std::vector<std::uint8_t> near = within_rings(state.mesh, centres, 4);
    struct FarTet {
      std::uint32_t slot;
      std::array<std::uint32_t, 4> v;
      std::array<Vec3, 4> p;
    };
    std::vector<FarTet> far;
    for (const std::uint32_t t : bad) {
      const auto& v = state.mesh.tet(t).v;
      if (std::none_of(v.begin(), v.end(), [&](std::uint32_t x) { return near[x] != 0; }))
        far.push_back({t, v, {state.mesh.point(v[0]), state.mesh.point(v[1]), state.mesh.point(v[2]),
                              state.mesh.point(v[3])}});
    }
    std::vector<std::uint32_t> start;
    std::vector<std::uint32_t> star;
    for (const std::uint32_t x : centres) {
      state.mesh.star(x, star);
      start.insert(start.end(), star.begin(), star.end());
    }
    ImprovementTarget polish;
    polish.min_dihedral_deg = 30.0;
    polish.max_dihedral_deg = 130.0;
    polish.tries_per_bad_tet = 0;
    polish.start_tets = &start;
    const std::size_t before = outside_window(state, 30.0, 130.0);
    const ImprovementStats stats = improve_slivers(state, polish);
    std::size_t kept = 0;
    for (const FarTet& f : far)
      kept += !state.mesh.is_dead(f.slot) && state.mesh.tet(f.slot).v == f.v &&
              std::equal(f.v.begin(), f.v.end(), f.p.begin(),
                         [&](std::uint32_t x, const Vec3& p) { return state.mesh.point(x) == p; });
    std::printf("%-10s %zu bad tets, %zu far from the start, %zu kept; %zu moves\n", input.name.c_str(),
                bad.size(), far.size(), kept, stats.vertex_moves);
    EXPECT_EQ(kept, far.size()) << input.name;
    EXPECT_LE(outside_window(state, 30.0, 130.0), before) << input.name;
    EXPECT_TRUE(check_topology(state.mesh).empty()) << input.name;
    for (const auto& [key, facet] : state.subfaces)
      EXPECT_TRUE(state.mesh.find_face(key[0], key[1], key[2]).has_value()) << input.name;
    far_in_all += far.size();
  }
  EXPECT_GT(far_in_all, 100u);
}

}  // namespace
}  // namespace delmesh::test
