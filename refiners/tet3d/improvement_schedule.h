// Scheduling of the improvement pass (sliver_improvement.h; notes §2.2.4 and the end of
// §4.4): how many passes it makes and how much work it may do, so that it ends in time
// proportional to the mesh on every input.
//
// The pass repeats flips, smoothing, vertex insertion and vertex deletion over the tets
// outside the dihedral window (Klingner and Shewchuk, "Aggressive tetrahedral mesh
// improvement", 2007, repeat until a pass no longer improves the mesh). Where the window
// cannot be met (flat tets between nearly coplanar facets, skinny tets the refinement's
// termination floors left near small input angles) every pass makes a few moves that
// change the stars of the bad tets without making them good, and those changes make the
// next pass try the same tets again: on cgal-anchor.off (166000 tets, some 10000 of them
// outside the window whatever is done) eight passes took 43 s of wall time after 4.5 s
// of refinement, the first taking the bad tets from 26687 to 12658 and each one after
// the second removing 0.4 to 4.7% of them. Five rules bound the work:
//   1. Passes. At most kMaxPasses, and another pass only if the one before removed at
//      least kMinPassGain of the tets outside the window it started with (the first pass
//      makes almost all the gain).
//   2. Tries. Over all passes each step (flips of a tet, smoothing of a vertex, vertex
//      insertion for a tet, vertex deletion for a tet) is tried at most kTriesPerBadTet
//      times the number of tets outside the window before the first pass. A try costs a
//      bounded amount of work (edge rings of at most 12 tets, insertion cavities of at
//      most 48, a fixed number of ascent steps over a vertex star), so after the one scan
//      of the mesh the pass costs at most a constant times the tets it starts from.
//   3. Vertex insertion is tried once per tet: not again for the same four vertices, even
//      if smoothing moved one of them since (a move large enough to make room for a
//      vertex is rare; a moved tet tried again was the largest cost of the later passes).
//   4. A vertex move, like a flip, must raise the worst quality of its star by a minimum
//      gain (sliver_improvement.cpp, kMinFlipGain): without it, moves with any gain at
//      all, however small, changed the stars pass after pass and so re-enabled every
//      other step (on gmsh-part.step the rule alone took the tets left outside the window
//      from 126 to 102).
//   5. The polish after the passes (sliver_improvement.h, step 5) makes at most
//      kPolishRounds rounds and kPolishTriesPerBadTet tries per tet still outside the
//      window (smoothing tries, and its flips, edge removals at holding tets, vertex
//      insertions and deletions, each tried once per four vertices), and stops after a
//      round that removes none; then at most kTradeRounds trade rounds from the tries
//      left, or kTradeTriesPerTet per tet outside the window away from small angles where
//      fewer are left, each ending the trades when it leaves as many tets away from small
//      angles and made none of them that it was not offered (their joint moves and flip
//      trades, one try per bad tet and round, take no tries and run even where none is left).
// On gmsh-part.step (35600 tets, 2824 outside the window before the pass) the rules take
// the pass from 8 passes to 4, its CPU time to some 60% of what it was and the tets left
// outside the window from 126 to 105; on the benchmark inputs at radius-edge 1.414 it
// leaves pocc-io1-ug-214 with 3 tets outside (3 before) and cgal-fandisk with 6 (4
// before), both under 0.01% of the tets.
// Together with the retry rules of change_clock.h (a failed flip, smoothing or deletion
// is not retried on unchanged stars) the work stops when the gain does. With a window the
// pass runs up to kMaxImprovementRounds times, the later runs its polish alone
// (improvement_rounds.h), each bounded as above.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <set>

namespace delmesh::tet3d {

/// Most passes of the improvement pass.
inline constexpr int kMaxPasses = 8;
/// Least share of the bad tets a pass must remove for another pass to follow.
inline constexpr double kMinPassGain = 0.05;
/// Tries of each step over all passes, per tet outside the window before the first pass.
inline constexpr std::size_t kTriesPerBadTet = 4;
/// Rounds of the polish after the passes (sliver_improvement.h, step 5).
inline constexpr int kPolishRounds = 3;
/// Tries of the polish, per tet outside the window after the passes (measured
/// over 13 corpus inputs with a neighbour margin of 0.1: 10 tries left 1265 tets outside
/// [20, 150] away from small angles, 40 left 1225, no polish 1487; its cost grows with it,
/// some 1.5 s of CPU on occt-sh2's 10 s at 40).
inline constexpr std::size_t kPolishTriesPerBadTet = 20;

/// Most trade rounds after the polish's rounds (sliver_improvement.h, step 5), from what
/// is left of the polish's tries (measured with [20, 150] on gmsh-netgen-hinge, cgal-boeing
/// and cgal-anchor: 3 rounds left 37, 36 and 83 tets outside the window away from small
/// angles, 8 left 36, 36 and 75).
inline constexpr int kTradeRounds = 8;

/// Tries of the trade rounds per tet outside the window away from small angles when they
/// start, where less is left of the polish's tries (with [20, 150] on cgal-couplingdown the
/// polish's rounds spent them all on the tets touching a small angle in every run of the
/// pass, so no trade round ran; with 200 the rounds end by themselves, within the tries).
inline constexpr std::size_t kTradeTriesPerTet = 200;

/// The steps of a pass, each with its own budget of tries.
enum class ImprovementStep { Flips, Smoothing, Insertion, Deletion };

class ImprovementSchedule {
 public:
  /// A schedule for a mesh with `bad_before` tets outside the window, of at most
  /// `max_passes` passes and `tries_per_bad_tet` tries of each step per such tet.
  explicit ImprovementSchedule(std::size_t bad_before, int max_passes = kMaxPasses,
                               std::size_t tries_per_bad_tet = kTriesPerBadTet);

  /// After `passes` passes, the last of which started with `bad_at_start` bad tets and
  /// ended with `bad_now`, having changed the mesh or not: is another pass due?
  bool another_pass(int passes, std::size_t bad_at_start, std::size_t bad_now, bool changed) const;

  /// Takes one try of `step` from its budget; false when the budget is spent.
  bool take(ImprovementStep step);
  /// Tries of `step` taken so far.
  std::size_t taken(ImprovementStep step) const { return taken_[static_cast<int>(step)]; }

  /// Was vertex insertion tried for a tet with these four vertices (any order) before?
  bool insertion_tried(std::array<std::uint32_t, 4> vertices) const;
  /// Records a vertex insertion tried for a tet with these vertices.
  void record_insertion(std::array<std::uint32_t, 4> vertices);

 private:
  std::size_t budget_;
  int max_passes_;
  std::array<std::size_t, 4> taken_{};
  std::set<std::array<std::uint32_t, 4>> insertions_;
};

}  // namespace delmesh::tet3d
