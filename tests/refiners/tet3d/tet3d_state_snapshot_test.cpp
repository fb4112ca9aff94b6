// The copy of a refinement state that undoes a trial of the polish
// (refiners/tet3d/state_snapshot.h): after subsegment splits and a polish run on the
// programmatic PLCs with a dihedral window refinement did not aim for, restore gives back
// the state a second, identical refinement has (every point, tet, region, subsegment and
// subfacet), and the same polish run then makes the same mesh from both, so a run that
// undoes a trial goes on exactly as if it had not been made.
#include <cstdio>
#include <string>

#include "refiners/tet3d/state_snapshot.h"
#include "refiners/tet3d/subsegment_insertion.h"
#include "insertion_test_checks.h"
#include "refined_test_state.h"

namespace delmesh::test {
namespace {

using namespace delmesh::tet3d;

/// Every point, tet slot, region, subsegment and subfacet of `a` and `b` the same.
void expect_same_state(const RefineState& a, const RefineState& b, const std::string& name) {
  ASSERT_EQ(a.mesh.num_vertices(), b.mesh.num_vertices()) << name;
  ASSERT_EQ(a.mesh.tet_slots(), b.mesh.tet_slots()) << name;
  std::size_t points = 0, tets = 0;
  for (std::uint32_t v = 1; v < a.mesh.num_vertices(); ++v) points += a.mesh.point(v) == b.mesh.point(v);
  for (std::uint32_t t = 0; t < a.mesh.tet_slots(); ++t)
    tets += a.mesh.is_dead(t) == b.mesh.is_dead(t) &&
            (a.mesh.is_dead(t) || (a.mesh.tet(t).v == b.mesh.tet(t).v && a.tet_region[t] == b.tet_region[t]));
  EXPECT_EQ(points, a.mesh.num_vertices() - 1u) << name;
  EXPECT_EQ(tets, a.mesh.tet_slots()) << name;
  EXPECT_EQ(a.subsegments.size(), b.subsegments.size()) << name;
  for (const auto& [key, segment] : a.subsegments) {
    const std::uint32_t* other = b.subsegments.lookup(key);
    EXPECT_TRUE(other && *other == segment) << name << ": subsegment";
  }
  EXPECT_EQ(a.subfaces.size(), b.subfaces.size()) << name;
  for (const auto& [key, facet] : a.subfaces) {
    const std::uint32_t* other = b.subfaces.lookup(key);
    EXPECT_TRUE(other && *other == facet) << name << ": subfacet";
  }
}

TEST(Tet3dStateSnapshot, RestoreUndoesSplitsAndPolish) {
  std::size_t split_in_all = 0;
  for (const TestPlc& input : {unit_cube(), l_prism(), two_boxes()}) {
    MeshOptions options;
    options.max_volume = input.volume / 2000.0;
    options.min_dihedral_deg = 35.0;
    options.max_dihedral_deg = 135.0;
    ImprovementTarget polish;
    polish.min_dihedral_deg = options.min_dihedral_deg;
    polish.max_dihedral_deg = options.max_dihedral_deg;
    polish.tries_per_bad_tet = 0;
    RefineState tried(input.plc, options), untouched(input.plc, options);
    ASSERT_NO_FATAL_FAILURE(refine_for_improvement(tried, input));
    ASSERT_NO_FATAL_FAILURE(refine_for_improvement(untouched, input));
    ASSERT_NO_FATAL_FAILURE(expect_same_state(tried, untouched, input.name));

    const StateSnapshot snapshot(tried);
    const std::uint32_t vertices = tried.mesh.num_vertices();
    const std::size_t split = insert_on_subsegments(tried, SubsegmentJudgement::AfterPolish);
    improve_slivers(tried, polish);
    std::printf("%-10s %zu subsegments split, %u -> %u vertices, restored\n", input.name.c_str(), split, vertices,
                tried.mesh.num_vertices());
    split_in_all += split;
    snapshot.restore(tried);
    ASSERT_NO_FATAL_FAILURE(expect_same_state(tried, untouched, input.name));
    expect_valid(tried, input.name);

    // The facet triangulations and caches came back too: the same run makes the same mesh.
    insert_on_subsegments(tried);
    insert_on_subsegments(untouched);
    improve_slivers(tried, polish);
    improve_slivers(untouched, polish);
    ASSERT_NO_FATAL_FAILURE(expect_same_state(tried, untouched, input.name));
    expect_valid(tried, input.name);
  }
  EXPECT_GT(split_in_all, 0u);
}

}  // namespace
}  // namespace delmesh::test
