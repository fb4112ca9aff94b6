// Checks shared by the tests of the polish's insertions on the boundary
// (tet3d_subfacet_insertion_test.cpp, tet3d_subsegment_insertion_test.cpp): the tets left
// outside a dihedral window away from small input angles with the regions' volumes, and
// the validity of the state after the insertions.
#pragma once

#include <gtest/gtest.h>

#include <map>
#include <string>
#include <vector>

#include "refiners/tet3d/refine_state.h"
#include "refiners/tet3d/small_angles.h"
#include "toolkit/predicates/predicates.h"
#include "toolkit/quality/tet_quality.h"
#include "toolkit/tetmesh/tet_check.h"

namespace delmesh::test {

/// In-domain tets outside [low, high] touching no small input angle, and the volume of
/// each region.
inline std::size_t bad_tets(const tet3d::RefineState& state, double low, double high, std::map<int, double>& volume) {
  const TetMesh& mesh = state.mesh;
  const std::vector<std::uint8_t> small = tet3d::small_angle_tets(state);
  std::size_t bad = 0;
  volume.clear();
  for (std::uint32_t t = 0; t < mesh.tet_slots(); ++t) {
    if (mesh.is_dead(t) || mesh.is_infinite(t) || !tet3d::in_domain(state.tet_region[t])) continue;
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
inline void expect_valid(tet3d::RefineState& state, const std::string& name) {
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
      const int other = mesh.is_infinite(u) ? tet3d::kRegionExterior : state.tet_region[u];
      if (other == state.tet_region[t]) continue;
      const auto& o = kFaceVertex[f];
      EXPECT_NE(tet3d::subface_of(state, v[o[0]], v[o[1]], v[o[2]]), nullptr) << name << ": region change off the facets";
    }
  }
  std::size_t listed = 0;
  for (std::size_t f = 0; f < state.facets.size(); ++f) {
    for (const Subface& s : state.facets[f].subfaces()) {
      ++listed;
      const std::uint32_t* owner = tet3d::subface_of(state, s[0], s[1], s[2]);
      ASSERT_NE(owner, nullptr) << name;
      EXPECT_EQ(*owner, f) << name;
      EXPECT_TRUE(mesh.find_face(s[0], s[1], s[2]).has_value()) << name << ": subfacet not a face";
    }
  }
  EXPECT_EQ(listed, state.subfaces.size()) << name;
}

}  // namespace delmesh::test
