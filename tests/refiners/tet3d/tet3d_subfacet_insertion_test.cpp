// Vertex insertion on subfacets for the polish (refiners/tet3d/subfacet_insertion.h), on
// refined states of the programmatic PLCs with a dihedral window refinement did not aim
// for: it inserts vertices on subfacets, each insertion raising the worst tet around it
// touching no small angle, and leaves a valid tetrahedralization of the same domain whose
// faces include every subfacet of the facets' triangulations, with no more tets outside
// the window than before and the regions' volumes unchanged.
#include <cstdio>
#include <map>
#include <string>

#include "refiners/tet3d/subfacet_insertion.h"
#include "insertion_test_checks.h"
#include "refined_test_state.h"

namespace delmesh::test {
namespace {

using namespace delmesh::tet3d;

TEST(Tet3dSubfacetInsertion, InsertsOnSubfacetsWithGainAndKeepsAValidMesh) {
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
    const std::size_t subfaces = state.subfaces.size();
    const std::size_t segment_queue = state.subsegment_queue.size(), face_queue = state.subface_queue.size();
    const std::size_t inserted = insert_on_subfacets(state);
    const std::size_t after = bad_tets(state, 35.0, 135.0, after_volume);
    std::printf("%-10s %zu vertices on subfacets, %zu -> %zu tets outside [35, 135]\n", input.name.c_str(), inserted,
                before, after);
    inserted_in_all += inserted;
    EXPECT_EQ(state.mesh.num_vertices(), vertices + inserted) << input.name;
    for (std::uint32_t v = vertices; v < state.mesh.num_vertices(); ++v)
      EXPECT_EQ(state.vertices[v].kind, VertexKind::OnFacet) << input.name;
    // A split subfacet becomes three or more: the table grows by two per insertion at least.
    EXPECT_GE(state.subfaces.size(), subfaces + 2 * inserted) << input.name;
    EXPECT_LE(after, before) << input.name;
    for (const auto& [region, volume] : before_volume)
      EXPECT_NEAR(after_volume[region], volume, 1e-12 * volume) << input.name << ": region " << region;
    EXPECT_EQ(state.subsegment_queue.size(), segment_queue) << input.name;
    EXPECT_EQ(state.subface_queue.size(), face_queue) << input.name;
    expect_valid(state, input.name);
  }
  EXPECT_GT(inserted_in_all, 0u);
}

}  // namespace
}  // namespace delmesh::test
