// Vertex insertion on subsegments for the polish (refiners/tet3d/subsegment_insertion.h),
// on refined states of the programmatic PLCs with a dihedral window refinement did not
// aim for: it splits subsegments near tets outside the window, each split raising the
// worst tet around it touching no small angle, and leaves a valid tetrahedralization of
// the same domain whose faces include every subfacet of the facets' triangulations and
// whose edges include every subsegment, with no more tets outside the window than before
// and the regions' volumes unchanged. Asked for the splits at one of those tets alone (as
// the splits judged after the polish try them, deferred_split.h), it makes at most one.
#include <algorithm>
#include <array>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "refiners/tet3d/state_snapshot.h"
#include "refiners/tet3d/subsegment_insertion.h"
#include "insertion_test_checks.h"
#include "refined_test_state.h"

namespace delmesh::test {
namespace {

using namespace delmesh::tet3d;

TEST(Tet3dSubsegmentInsertion, SplitsSubsegmentsWithGainAndKeepsAValidMesh) {
  std::size_t inserted_in_all = 0;
  for (TestPlc input : {unit_cube(), l_prism(), two_boxes()}) {
    MeshOptions options;
    options.max_volume = input.volume / 2000.0;
    options.min_dihedral_deg = 35.0;
    options.max_dihedral_deg = 135.0;
    RefineState state(input.plc, options);
    ASSERT_NO_FATAL_FAILURE(refine_for_improvement(state, input));
    std::map<int, double> before_volume, after_volume;
    const std::size_t before = bad_tets(state, 35.0, 135.0, before_volume);
    const std::uint32_t vertices = state.mesh.num_vertices();
    const std::size_t subsegments = state.subsegments.size(), subfaces = state.subfaces.size();
    const std::size_t segment_queue = state.subsegment_queue.size(), face_queue = state.subface_queue.size();
    const auto splits = state.stage_segment_splits.for_rejected_points;
    const std::size_t inserted = insert_on_subsegments(state);
    const std::size_t after = bad_tets(state, 35.0, 135.0, after_volume);
    std::printf("%-10s %zu vertices on subsegments, %zu -> %zu tets outside [35, 135]\n", input.name.c_str(),
                inserted, before, after);
    inserted_in_all += inserted;
    EXPECT_EQ(state.mesh.num_vertices(), vertices + inserted) << input.name;
    for (std::uint32_t v = vertices; v < state.mesh.num_vertices(); ++v)
      EXPECT_EQ(state.vertices[v].kind, VertexKind::OnSegment) << input.name;
    // Each split makes one subsegment two, and each facet's subfacet on it two.
    EXPECT_EQ(state.subsegments.size(), subsegments + inserted) << input.name;
    EXPECT_GE(state.subfaces.size(), subfaces + inserted) << input.name;
    for (const auto& [key, segment] : state.subsegments) {
      const auto a = static_cast<std::uint32_t>(key >> 32), b = static_cast<std::uint32_t>(key & 0xffffffffu);
      std::vector<std::uint32_t> around;
      EXPECT_TRUE(state.mesh.tets_around_edge(a, b, around)) << input.name << ": subsegment not an edge";
    }
    EXPECT_LE(after, before) << input.name;
    for (const auto& [region, volume] : before_volume)
      EXPECT_NEAR(after_volume[region], volume, 1e-12 * volume) << input.name << ": region " << region;
    EXPECT_EQ(state.subsegment_queue.size(), segment_queue) << input.name;
    EXPECT_EQ(state.subface_queue.size(), face_queue) << input.name;
    EXPECT_EQ(state.stage_segment_splits.for_rejected_points, splits) << input.name;
    expect_valid(state, input.name);
  }
  EXPECT_GT(inserted_in_all, 0u);
}

TEST(Tet3dSubsegmentInsertion, SplitsAtOneTetAlone) {
  std::size_t alone_in_all = 0;
  for (const TestPlc& input : {unit_cube(), l_prism(), two_boxes()}) {
    MeshOptions options;
    options.max_volume = input.volume / 2000.0;
    options.min_dihedral_deg = 35.0;
    options.max_dihedral_deg = 135.0;
    RefineState state(input.plc, options);
    ASSERT_NO_FATAL_FAILURE(refine_for_improvement(state, input));
    const StateSnapshot snapshot(state);
    std::vector<std::array<std::uint32_t, 4>> tets;
    const std::size_t together = insert_on_subsegments(state, SubsegmentJudgement::AfterPolish, &tets);
    const std::size_t bad = tets.size();
    std::size_t alone = 0;
    // The first tets only (the PLCs have about 700 outside [35, 135]).
    for (std::size_t k = 0; k < std::min<std::size_t>(bad, 40); ++k) {
      snapshot.restore(state);
      const std::uint32_t vertices = state.mesh.num_vertices();
      const std::size_t made = insert_on_subsegments(state, SubsegmentJudgement::AfterPolish, nullptr, k);
      EXPECT_LE(made, 1u) << input.name << ": tet " << k;
      EXPECT_EQ(state.mesh.num_vertices(), vertices + made) << input.name;
      if (made > 0) expect_valid(state, input.name);
      alone += made;
    }
    std::printf("%-10s %zu tets, %zu splits together, %zu at one tet alone\n", input.name.c_str(), bad, together, alone);
    if (together > 0) {
      EXPECT_GT(alone, 0u) << input.name;
    }
    alone_in_all += alone;
  }
  EXPECT_GT(alone_in_all, 1u);
}

}  // namespace
}  // namespace delmesh::test
