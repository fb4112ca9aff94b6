// pass_over_insertion (refiners/tet3d/boundary_split.h): a point ruled out before its
// cavity is prepared advances the location walk's random state exactly as
// prepare_insertion would, so that the walks after it, and the mesh, are those of a run
// that prepared the point. Two states of the same PLC take the same random points, one
// preparing each, the other passing over it (both inserting every fifth point alike, so
// that the meshes grow), on the Delaunay tetrahedralization and, constrained, on the
// recovered boundary as on the CCDT.
#include <gtest/gtest.h>

#include <random>

#include "refiners/tet3d/boundary_recovery.h"
#include "refiners/tet3d/boundary_split.h"
#include "refiners/tet3d/plc_preparation.h"
#include "test_plcs.h"

namespace delmesh::test {
namespace {

using namespace delmesh::tet3d;

/// Random points in the PLC's bounding box, prepared in one state and passed over in the
/// other; returns how many changed the walk's state (the test must see some).
// Every fifth point, when it could be prepared, is then inserted in both.
int check_same_walks(const TestPlc& input, bool constrained, std::uint64_t seed) {
  MeshOptions options;
  options.segment_recovery = SegmentRecovery::StronglyDelaunay;
  RefineState prepared(input.plc, options);
  RefineState passed(input.plc, options);
  int changed = 0;
  for (RefineState* state : {&prepared, &passed}) {
    EXPECT_TRUE(prepare_plc(*state).has_value()) << input.name;
    if (constrained) {
      EXPECT_TRUE(restore_conformity(*state, true).has_value()) << input.name;
      state->constrained = true;
    }
  }
  Vec3 lo = input.plc.points.front(), hi = lo;
  for (const Vec3& p : input.plc.points) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int k = 0; k < 200; ++k) {
    const Vec3 p = lo + Vec3(unit(rng), unit(rng), unit(rng)).cwiseProduct(hi - lo);
    const std::uint32_t hint = kNone;  // the last tet made: the same in both meshes
    const std::uint64_t before = passed.cavity.rng;
    const bool ok = prepare_insertion(prepared, p, hint);
    pass_over_insertion(passed, p, hint);
    EXPECT_EQ(prepared.cavity.rng, passed.cavity.rng) << input.name << " point " << k;
    if (passed.cavity.rng != before) ++changed;
    if (k % 5 != 0 || !ok) continue;
    VertexInfo info;
    info.kind = VertexKind::Interior;
    // Both prepare the point once more, then insert it.
    EXPECT_TRUE(prepare_insertion(prepared, p, hint)) << input.name << " point " << k;
    EXPECT_TRUE(prepare_insertion(passed, p, hint)) << input.name << " point " << k;
    commit_insertion(prepared, p, info);
    commit_insertion(passed, p, info);
    EXPECT_EQ(prepared.cavity.rng, passed.cavity.rng) << input.name << " point " << k;
  }
  return changed;
}

TEST(Tet3dPassOverInsertion, AdvancesTheLocationWalkAsThePreparationWould) {
  std::uint64_t seed = 11;
  int changed = 0;
  for (const TestPlc& input : all_test_plcs()) {
    changed += check_same_walks(input, false, seed++);
    changed += check_same_walks(input, true, seed++);
  }
  EXPECT_GT(changed, 100);
}

}  // namespace
}  // namespace delmesh::test
