// The polish at the end of the improvement pass (refiners/tet3d/sliver_improvement.h,
// step 5): on refined states of the programmatic PLCs with windows the passes cannot
// meet everywhere, it never raises the count of tets outside the window, stays within
// its budget (improvement_schedule.h), keeps the mesh valid, and removes bad tets the
// passes left.
#include <cstdio>

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

}  // namespace
}  // namespace delmesh::test
