// The radius-edge polish (refiners/tet3d/radius_edge_polish.h): on a refined state whose
// interior vertex was pushed toward a neighbour (its short edge puts tets of its star above
// the radius-edge bound, every tet still positively oriented), the polish moves it back
// until none of them is above the bound, moves no boundary vertex, keeps every tet
// positively oriented (exact orient3d), adds no tet above the bound and takes no tet out of
// the dihedral window; tets touching a small input angle are left as they are.
#include <cstdio>

#include "refiners/tet3d/radius_edge_polish.h"
#include "refined_test_state.h"
#include "toolkit/predicates/predicates.h"
#include "toolkit/tetmesh/tet_check.h"

namespace delmesh::test {
namespace {

using namespace delmesh::tet3d;

constexpr double kBound = 1.414;
constexpr double kLow = 20.0, kHigh = 150.0;

struct Counts {
  std::size_t above = 0, outside = 0, not_positive = 0;
};

Counts count(const RefineState& state) {
  Counts c;
  for (std::uint32_t t = 0; t < state.mesh.tet_slots(); ++t) {
    if (state.mesh.is_dead(t) || state.mesh.is_infinite(t) || !in_domain(state.tet_region[t])) continue;
    const auto& v = state.mesh.tet(t).v;
    const Vec3 &a = state.mesh.point(v[0]), &b = state.mesh.point(v[1]), &cc = state.mesh.point(v[2]),
               &d = state.mesh.point(v[3]);
    c.above += !(radius_edge_ratio(a, b, cc, d) <= kBound);
    c.outside += dihedral_outside(a, b, cc, d, kLow, kHigh);
    c.not_positive += predicates::orient3d(a.data(), b.data(), cc.data(), d.data()) != Sign::Positive;
  }
  return c;
}

/// Pushes an interior vertex of the refined state 60% of the way toward its nearest
/// neighbour (less where a tet of its star would not stay positively oriented); the
/// vertex moved, kNone if none could be.
std::uint32_t push_interior_vertex(RefineState& state) {
  TetMesh& mesh = state.mesh;
  std::vector<std::uint32_t> star, neighbours;
  for (std::uint32_t v = 1; v < mesh.num_vertices(); ++v) {
    if (state.vertices[v].kind != VertexKind::Interior) continue;
    mesh.star(v, star);
    bool inside = !star.empty();
    for (const std::uint32_t s : star) inside = inside && mesh.is_finite(s) && in_domain(state.tet_region[s]);
    if (!inside) continue;
    mesh.vertex_neighbors(v, neighbours);
    const Vec3 origin = mesh.point(v);
    std::uint32_t nearest = neighbours.front();
    for (const std::uint32_t w : neighbours)
      if ((mesh.point(w) - origin).norm() < (mesh.point(nearest) - origin).norm()) nearest = w;
    for (double fraction = 0.6; fraction > 0.1; fraction -= 0.1) {
      mesh.move_point(v, origin + fraction * (mesh.point(nearest) - origin));
      bool positive = true;
      for (const std::uint32_t s : star) {
        const auto& q = mesh.tet(s).v;
        positive = positive && predicates::orient3d(mesh.coords(q[0]), mesh.coords(q[1]), mesh.coords(q[2]),
                                                    mesh.coords(q[3])) == Sign::Positive;
      }
      if (positive && count(state).above > 0) return v;
    }
    mesh.move_point(v, origin);
  }
  return kNone;
}

class Tet3dRadiusEdgePolish : public ::testing::Test {
 protected:
  void SetUp() override {
    options_.max_radius_edge = kBound;
    options_.max_volume = input_.volume / 500.0;
    state_ = std::make_unique<RefineState>(input_.plc, options_);
    refine_for_improvement(*state_, input_);
    ASSERT_EQ(count(*state_).above, 0u);
    for (std::uint32_t v = 0; v < state_->mesh.num_vertices(); ++v) before_.push_back(state_->mesh.point(v));
    pushed_ = push_interior_vertex(*state_);
    ASSERT_NE(pushed_, kNone) << "no interior vertex to push";
  }

  TestPlc input_ = unit_cube();
  MeshOptions options_;  ///< the state keeps a reference
  std::unique_ptr<RefineState> state_;
  std::vector<Vec3> before_;
  std::uint32_t pushed_ = kNone;
};

TEST_F(Tet3dRadiusEdgePolish, MovesTheInteriorVertexBackUnderTheBound) {
  const Counts pushed = count(*state_);
  const std::vector<std::uint8_t> away(state_->mesh.tet_slots(), 0);
  const RadiusEdgePolishStats stats = polish_radius_edge(*state_, away, kLow, kHigh);
  const Counts after = count(*state_);
  std::printf("%zu tets above %.3f after the push (%zu outside [%g, %g]), %zu after %zu moves (%zu outside)\n",
              pushed.above, kBound, pushed.outside, kLow, kHigh, after.above, stats.moves, after.outside);
  EXPECT_EQ(stats.tets_before, pushed.above);
  EXPECT_GT(stats.moves, 0u);
  EXPECT_EQ(stats.tets_after, 0u);
  EXPECT_EQ(after.above, 0u);
  EXPECT_LE(after.outside, pushed.outside);
  EXPECT_EQ(after.not_positive, 0u);
  EXPECT_TRUE(check_topology(state_->mesh).empty());
  for (std::uint32_t v = 0; v < state_->mesh.num_vertices(); ++v) {
    if (state_->vertices[v].kind != VertexKind::Interior) {
      EXPECT_EQ(state_->mesh.point(v), before_[v]) << v;
    }
  }
}

TEST_F(Tet3dRadiusEdgePolish, LeavesTetsTouchingSmallAngles) {
  const Vec3 pushed_to = state_->mesh.point(pushed_);
  const std::size_t above = count(*state_).above;
  const std::vector<std::uint8_t> touching(state_->mesh.tet_slots(), 1);
  const RadiusEdgePolishStats stats = polish_radius_edge(*state_, touching, kLow, kHigh);
  EXPECT_EQ(stats.tets_before, 0u);
  EXPECT_EQ(stats.moves, 0u);
  EXPECT_EQ(count(*state_).above, above);
  EXPECT_EQ(state_->mesh.point(pushed_), pushed_to);
}

}  // namespace
}  // namespace delmesh::test
