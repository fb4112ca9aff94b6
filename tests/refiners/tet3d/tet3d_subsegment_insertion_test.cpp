// Vertex insertion on subsegments for the polish (refiners/tet3d/subsegment_insertion.h),
// on refined states of the programmatic PLCs with a dihedral window refinement did not
// aim for: it splits subsegments near tets outside the window, each split raising the
// worst tet around it touching no small angle, and leaves a valid tetrahedralization of
// the same domain whose faces include every subfacet of the facets' triangulations and
// whose edges include every subsegment, with no more tets outside the window than before
// and the regions' volumes unchanged.
#include <cstdio>
#include <map>
#include <string>

#include "refiners/tet3d/small_angles.h"
#include "refiners/tet3d/subsegment_insertion.h"
#include "refined_test_state.h"
#include "toolkit/quality/tet_quality.h"
#include "toolkit/tetmesh/tet_check.h"

namespace delmesh::test {
namespace {

using namespace delmesh::tet3d;

/// In-domain tets outside [low, high] touching no small input angle, and the volume of
/// each region.
std::size_t bad_tets(const RefineState& state, double low, double high, std::map<int, double>& volume) {
  const TetMesh& mesh = state.mesh;
  const std::vector<std::uint8_t> small = small_angle_tets(state);
  std::size_t bad = 0;
  volume.clear();
  for (std::uint32_t t = 0; t < mesh.tet_slots(); ++t) {
    if (mesh.is_dead(t) || mesh.is_infinite(t) || !in_domain(state.tet_region[t])) continue;
    const auto& v = mesh.tet(t).v;
    const Vec3 a = mesh.point(v[0]), b = mesh.point(v[1]), c = mesh.point(v[2]), d = mesh.point(v[3]);
    volume[state.tet_region[t]] += signed_volume(a, b, c, d);
    if (small[t] == 0 && dihedral_outside(a, b, c, d, low, high)) ++bad;
  }
  return bad;
}

/// Every live finite tet positively oriented (exact), the topology consistent, every
/// subfacet of the facets' triangulations a face of the mesh and in the subfacet table,
/// and every face between two regions a subfacet.
void expect_valid(RefineState& state, const std::string& name) {
  TetMesh& mesh = state.mesh;
  EXPECT_TRUE(check_topology(mesh).empty()) << name;
  for (std::uint32_t t = 0; t < mesh.tet_slots(); ++t) {
    if (mesh.is_dead(t) || mesh.is_infinite(t)) continue;
    const auto& v = mesh.tet(t).v;
    EXPECT_EQ(predicates::orient3d(mesh.coords(v[0]), mesh.coords(v[1]), mesh.coords(v[2]), mesh.coords(v[3])),
              Sign::Positive)
        << name << ": tet " << t;
    for (int f = 0; f < 4; ++f) {
      const std::uint32_t u = mesh.neighbor(t, f);
      const int other = mesh.is_infinite(u) ? kRegionExterior : state.tet_region[u];
      if (other == state.tet_region[t]) continue;
      const auto& o = kFaceVertex[f];
      EXPECT_NE(subface_of(state, v[o[0]], v[o[1]], v[o[2]]), nullptr) << name << ": region change off the facets";
    }
  }
  std::size_t listed = 0;
  for (std::size_t f = 0; f < state.facets.size(); ++f) {
    for (const Subface& s : state.facets[f]->subfaces()) {
      ++listed;
      const std::uint32_t* owner = subface_of(state, s[0], s[1], s[2]);
      ASSERT_NE(owner, nullptr) << name;
      EXPECT_EQ(*owner, f) << name;
      EXPECT_TRUE(mesh.find_face(s[0], s[1], s[2]).has_value()) << name << ": subfacet not a face";
    }
  }
  EXPECT_EQ(listed, state.subfaces.size()) << name;
}

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

}  // namespace
}  // namespace delmesh::test
