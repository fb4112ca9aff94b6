// Small-angle holds of the improvement pass's polish (refiners/tet3d/sliver_improvement.h,
// step 5; Improver::hold_small_angle_tets): where a tet touching a small input angle
// (refiners/tet3d/small_angles.h) is the worst tet of a vertex's star, the move raises the
// worst tet touching none instead, the held tets outside the window kept at or above the
// worst of them, those inside kept inside. On refined states of PLCs with a needle of two free segments and with a sharp
// wedge, with the window [20, 150], the pass with holds leaves fewer tets outside the
// window away from small angles than the same pass without them (ImprovementTarget::
// small_angle_holds), makes moves under holds (none without them), the same in two runs
// (the vertices the pass inserts lie beyond the small-angle table taken before it: once
// read out of bounds, which made runs differ), keeps the mesh valid
// and its subfacets, and the polish adds no tet outside the window (no move adds one to
// its star). In all, the count may end higher or lower than without holds: the polish
// spends its tries on the tets touching no small angle first. Tets outside away from small
// angles without -> with holds: needle of 0.5 degrees 18 -> 1 since the polish's trades
// (sliver_improvement.h, step 5; the needle at 1 degree 3 -> 1 unchanged), 18 -> 4 since held bound breakers
// inside the window are held by their angles, the polish removes edges at holding tets and
// its moves without holds keep the star's least window sine (18 -> 5 without that floor,
// 18 -> 6 with the removals alone; 18 -> 4 before them, since the polish's flips and the held tets' hold by
// angles; 6 before that hold, 9 with the polish's vertex insertions and deletions alone,
// which run with holds only, 18 with the insertions alone, 17 before them), needle of 1
// degree 3 -> 1 (added with the insertions), sharp wedge 0 -> 0.
#include <cstdio>
#include <numbers>
#include <vector>

#include "refiners/tet3d/small_angles.h"
#include "refiners/tet3d/sliver_improvement.h"
#include "refined_test_state.h"
#include "toolkit/predicates/predicates.h"
#include "toolkit/tetmesh/tet_check.h"

namespace delmesh::test {
namespace {

using namespace delmesh::tet3d;

constexpr double kLow = 20.0, kHigh = 150.0;

struct Outside {
  std::size_t at_small_angles = 0, elsewhere = 0;
};

Outside count_outside(const RefineState& state) {
  const std::vector<std::uint8_t> small = small_angle_tets(state);
  Outside out;
  for (std::uint32_t t = 0; t < state.mesh.tet_slots(); ++t) {
    if (state.mesh.is_dead(t) || state.mesh.is_infinite(t) || !in_domain(state.tet_region[t])) continue;
    const auto& v = state.mesh.tet(t).v;
    if (!dihedral_outside(state.mesh.point(v[0]), state.mesh.point(v[1]), state.mesh.point(v[2]),
                          state.mesh.point(v[3]), kLow, kHigh))
      continue;
    (small[t] != 0 ? out.at_small_angles : out.elsewhere) += 1;
  }
  return out;
}

/// Mesh options of the window [kLow, kHigh] under the volume bound `volume` (a RefineState
/// keeps a reference to its options: hold them in a variable that outlives it).
MeshOptions window_options(double volume) {
  MeshOptions options;
  options.max_volume = volume;
  options.min_dihedral_deg = kLow;
  options.max_dihedral_deg = kHigh;
  return options;
}

/// Refines `state` and runs the improvement pass for the window, with or without the
/// small-angle holds.
ImprovementStats polish_for_window(RefineState& state, const TestPlc& input, bool holds) {
  refine_for_improvement(state, input);
  ImprovementTarget target;
  target.min_dihedral_deg = kLow;
  target.max_dihedral_deg = kHigh;
  target.small_angle_holds = holds;
  return improve_slivers(state, target);
}

TEST(Tet3dSmallAngleHolds, LeaveFewerTetsOutsideTheWindowAwayFromSmallAngles) {
  std::size_t without_total = 0, with_total = 0, held_moves = 0;
  for (const TestPlc& input : {cube_with_needle(0.5), cube_with_needle(1.0), sharp_wedge()}) {
    Outside result[2];
    std::vector<Vec3> points[2];
    for (const int run : {0, 1, 2}) {
      const bool holds = run > 0;
      const MeshOptions options = window_options(0.0005);
      RefineState state(input.plc, options);
      const ImprovementStats stats = polish_for_window(state, input, holds);
      EXPECT_LE(stats.bad_after, stats.bad_after_passes) << input.name;  // the polish adds none
      result[holds] = count_outside(state);
      // Deterministic: the second run with holds moves every vertex as the first did.
      std::vector<Vec3> now;
      for (std::uint32_t v = 0; v < state.mesh.num_vertices(); ++v) now.push_back(state.mesh.point(v));
      if (run == 2) {
        EXPECT_TRUE(now == points[1]) << input.name << ": two runs with holds differ";
        continue;
      }
      points[holds] = now;
      if (!holds) {
        EXPECT_EQ(stats.held_moves, 0u) << input.name;
      }
      if (run == 1) held_moves += stats.held_moves;
      std::printf("%-8s holds %d: %zu -> %zu outside [20, 150], %zu of them away from small angles\n",
                  input.name.c_str(), holds ? 1 : 0, stats.bad_before, stats.bad_after,
                  result[holds].elsewhere);
      EXPECT_TRUE(check_topology(state.mesh).empty()) << input.name;
      for (const auto& [key, facet] : state.subfaces)
        EXPECT_TRUE(state.mesh.find_face(key[0], key[1], key[2]).has_value()) << input.name;
    }
    EXPECT_LE(result[1].elsewhere, result[0].elsewhere) << input.name;
    without_total += result[0].elsewhere;
    with_total += result[1].elsewhere;
  }
  EXPECT_GT(held_moves, 0u);
  EXPECT_LT(with_total, without_total);
}

// The polish's relaxed holds, flips, vertex insertions and deletions (sliver_improvement.h,
// step 5): on refined states of cubes with needles of 1 and 0.2 degrees and two volume
// bounds (measured: 20 relaxed moves, 448 held moves holding bound breakers inside the
// window by their angles, 82 flips of which 16 edge removals at holding tets, 13 insertions
// and 3 deletions in the polish in all, leaving 29 tets outside the window away from small
// angles since the polish's trades (53 before, below; the trades' own test:
// tet3d_small_angle_trades_test.cpp), leaving 53 tets outside the window away from small
// angles (45 without the polish's least-sine floor on moves without holds, with 254 such held
// moves and 94 flips; 45 with the removals at holding tets alone, with 98 flips, 31 of them
// there; 52 before all three, with 70 flips, 9 insertions and 1 deletion); the needles of 0.5 to 10 degrees
// at other bounds and the sharp wedge make fewer or none, measured before the flips), the
// pass with holds makes relaxed moves, moves holding bound breakers by their angles, flips,
// edge removals at holding tets, insertions and deletions in the polish (none without holds), the polish adds no tet outside the window, the mesh stays valid with its subfacets, every tet positively
// oriented (exact orient3d), and a second run gives the same mesh.
TEST(Tet3dSmallAngleHolds, RelaxedMovesAndPolishInsertions) {
  std::size_t relaxed = 0, insertions = 0, deletions = 0, flips = 0, holder_removals = 0, breaker_holds = 0;
  for (const TestPlc& input : {cube_with_needle(1.0), cube_with_needle(0.2)}) {
    for (const double volume : {0.0003, 0.0001}) {
      std::vector<Vec3> first;
      for (const int run : {0, 1, 2}) {
        const bool holds = run > 0;
        const MeshOptions options = window_options(volume);
        RefineState state(input.plc, options);
        const ImprovementStats stats = polish_for_window(state, input, holds);
        EXPECT_LE(stats.bad_after, stats.bad_after_passes) << input.name;
        EXPECT_LE(stats.relaxed_held_moves, stats.held_moves) << input.name;
        EXPECT_LE(stats.polish_insertions, stats.insertions) << input.name;
        EXPECT_LE(stats.polish_deletions, stats.deletions) << input.name;
        EXPECT_LE(stats.holder_removals, stats.polish_flips) << input.name;
        EXPECT_LE(stats.breaker_held_moves, stats.held_moves) << input.name;
        if (!holds) {
          EXPECT_EQ(stats.relaxed_held_moves, 0u) << input.name;
          EXPECT_EQ(stats.polish_insertions, 0u) << input.name;
          EXPECT_EQ(stats.polish_deletions, 0u) << input.name;
          EXPECT_EQ(stats.polish_flips, 0u) << input.name;
          EXPECT_EQ(stats.holder_removals, 0u) << input.name;
          EXPECT_EQ(stats.breaker_held_moves, 0u) << input.name;
          continue;
        }
        std::vector<Vec3> now;
        for (std::uint32_t v = 0; v < state.mesh.num_vertices(); ++v) now.push_back(state.mesh.point(v));
        if (run == 2) {
          EXPECT_TRUE(now == first) << input.name << ": two runs with holds differ";
          continue;
        }
        first = now;
        relaxed += stats.relaxed_held_moves;
        insertions += stats.polish_insertions;
        deletions += stats.polish_deletions;
        flips += stats.polish_flips;
        holder_removals += stats.holder_removals;
        breaker_holds += stats.breaker_held_moves;
        std::printf("%-8s volume %g: %zu relaxed moves, %zu polish insertions, %zu polish deletions, %zu polish "
                    "flips (%zu at holders), %zu held moves holding bound breakers by angles, %zu -> %zu outside, "
                    "%zu away from small angles\n",
                    input.name.c_str(), volume, stats.relaxed_held_moves, stats.polish_insertions,
                    stats.polish_deletions, stats.polish_flips, stats.holder_removals, stats.breaker_held_moves, stats.bad_before,
                    stats.bad_after, count_outside(state).elsewhere);
        EXPECT_TRUE(check_topology(state.mesh).empty()) << input.name;
        for (const auto& [key, facet] : state.subfaces)
          EXPECT_TRUE(state.mesh.find_face(key[0], key[1], key[2]).has_value()) << input.name;
        for (std::uint32_t t = 0; t < state.mesh.tet_slots(); ++t) {
          if (state.mesh.is_dead(t) || state.mesh.is_infinite(t)) continue;
          const auto& v = state.mesh.tet(t).v;
          EXPECT_EQ(predicates::orient3d(state.mesh.coords(v[0]), state.mesh.coords(v[1]), state.mesh.coords(v[2]),
                                         state.mesh.coords(v[3])),
                    Sign::Positive)
              << input.name << " tet " << t;
        }
      }
    }
  }
  EXPECT_GT(relaxed, 0u);
  EXPECT_GT(insertions, 0u);
  EXPECT_GT(deletions, 0u);
  EXPECT_GT(flips, 0u);
  EXPECT_GT(holder_removals, 0u);
  EXPECT_GT(breaker_holds, 0u);
}

}  // namespace
}  // namespace delmesh::test
