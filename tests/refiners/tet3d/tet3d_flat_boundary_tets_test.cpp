// Flat tets lying on two subfacets across a subsegment (flat_facet_tets.h,
// remove_flat_boundary_tets): a pyramid over a quadrilateral folded by 0.01 along its
// diagonal (x, y), whose two triangles are two facets, so (x, y) is a segment. The
// quadrilateral's other diagonal (c, d) is the shorter, so the Delaunay tetrahedralization
// holds the nearly flat tet (x, y, c, d) inside the pyramid, on both facets. The release of
// flat tets on one facet cannot flip a segment; edge removal of (c, d) replaces the three
// tets around it by two, keeping both subfacets and the volume.
#include <gtest/gtest.h>

#include <cmath>

#include "refiners/tet3d/boundary_recovery.h"
#include "refiners/tet3d/boundary_split.h"
#include "refiners/tet3d/ccdt_facet_recovery.h"
#include "refiners/tet3d/domain_marking.h"
#include "refiners/tet3d/flat_facet_tets.h"
#include "refiners/tet3d/mesh_plc.h"
#include "refiners/tet3d/plc_preparation.h"
#include "refiners/tet3d/refine_state.h"
#include "toolkit/quality/tet_quality.h"

namespace delmesh::test {
namespace {

using namespace delmesh::tet3d;

Plc folded_pyramid() {
  Plc plc;
  plc.points = {Vec3(0.0, 0.0, 0.0), Vec3(1.0, 0.0, 0.0), Vec3(0.5, 0.1, 0.0), Vec3(0.5, -0.1, 0.01),
                Vec3(0.5, 0.0, 1.0)};
  const std::uint32_t x = 0, y = 1, c = 2, d = 3, p = 4;
  for (const auto& tri : {std::array<std::uint32_t, 3>{x, y, c}, {x, d, y}, {p, c, x}, {p, y, c}, {p, d, y},
                          {p, x, d}}) {
    Plc::Facet f;
    f.polygons.push_back({tri[0], tri[1], tri[2]});
    plc.facets.push_back(f);
  }
  return plc;
}

struct DomainTets {
  std::size_t tets = 0;
  std::size_t below = 0;  ///< smallest dihedral angle below 10 degrees
  double volume = 0.0;
};

DomainTets domain_tets(const RefineState& state) {
  DomainTets r;
  for (std::uint32_t t = 0; t < state.mesh.tet_slots(); ++t) {
    if (state.mesh.is_dead(t) || state.mesh.is_infinite(t) || !in_domain(state.tet_region[t])) continue;
    const auto& v = state.mesh.tet(t).v;
    const Vec3 &a = state.mesh.point(v[0]), &b = state.mesh.point(v[1]), &c = state.mesh.point(v[2]),
               &d = state.mesh.point(v[3]);
    ++r.tets;
    r.below += dihedral_extremes_deg(a, b, c, d).first < 10.0 ? 1 : 0;
    r.volume += std::abs(signed_volume(a, b, c, d));
  }
  return r;
}

TEST(Tet3dFlatBoundaryTets, EdgeRemovalTakesTheFlatTetAcrossASegment) {
  const Plc plc = folded_pyramid();
  MeshOptions options;
  options.max_radius_edge = 1.414;
  options.segment_recovery = SegmentRecovery::StronglyDelaunay;
  RefineState state(plc, options);
  ASSERT_TRUE(prepare_plc(state).has_value());
  const std::size_t vertices = state.mesh.num_vertices();
  ASSERT_TRUE(restore_conformity(state, true).has_value());
  ASSERT_TRUE(recover_facets_ccdt(state).has_value());
  mark_domain(state);
  ASSERT_EQ(state.mesh.num_vertices(), vertices);  // no segment or facet split
  const DomainTets before = domain_tets(state);
  ASSERT_EQ(before.tets, 3u);  // around (c, d)
  ASSERT_EQ(before.below, 1u);

  EXPECT_EQ(release_flat_facet_tets(state, 10.0, 180.0), 0u);
  EXPECT_EQ(remove_flat_boundary_tets(state, 10.0, 180.0), 1u);
  const DomainTets after = domain_tets(state);
  EXPECT_EQ(after.tets, 2u);
  EXPECT_EQ(after.below, 0u);
  EXPECT_NEAR(after.volume, before.volume, 1e-12);
  for (const auto& [key, facet] : state.subfaces)
    EXPECT_TRUE(find_face_ref(state, key[0], key[1], key[2]).has_value()) << key[0] << " " << key[1] << " " << key[2];
}

}  // namespace
}  // namespace delmesh::test
