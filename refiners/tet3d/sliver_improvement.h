// Mesh improvement after 3D Delaunay refinement: topological flips and optimization-
// based vertex smoothing that raise the worst dihedral angles (notes §2.2.4 and the end
// of §4.4; Freitag and Ollivier-Gooch, "Tetrahedral mesh improvement using swapping and
// smoothing", 1997; Klingner and Shewchuk, "Aggressive tetrahedral mesh improvement",
// 2007).
//
// The objective is the minimum sine of the dihedral angles (toolkit/quality:
// min_dihedral_sine), small for angles near 0 and near 180 degrees alike; for a window
// with both ends the sines of obtuse angles are scaled so that both ends score the same
// (min_window_dihedral_sine: for [20, 150] an angle of 150 degrees scores sin 20, where
// the plain sine ranks it with 30 degrees and the steps left tets at 150-158 degrees
// because a neighbour at 21 degrees looked worse). Work starts
// from the in-domain tets whose dihedral angles leave the window (ImprovementTarget:
// [MeshOptions::min_dihedral_deg, max_dihedral_deg], or without one the default
// improvement's, default_improvement.h) and repeats, a few passes at most
// (improvement_schedule.h: passes stop when one gains little, and the tries of each step
// are bounded by a constant times the bad tets at the start):
//   1. Flips. For each such tet, its edges in order of their dihedral sine (worst first)
//      are offered to edge removal (toolkit/tetmesh: 3-2, 4-4 and larger removals, the
//      ring triangulation chosen by dynamic programming to maximize the worst new tet),
//      then its faces to 2-3 flips. A flip is made only if the worst new tet is better
//      than the worst old one. Flips never remove a subfacet or a subsegment and act only
//      on tets of one region (never exterior, hole or infinite tets), so the boundary,
//      the markers and the regions stay as they are.
//   2. Smoothing. Each movable vertex of such a tet is moved to raise the minimum sine
//      over its star: steepest ascent of the nonsmooth minimum along the minimum-norm
//      element of the convex hull of the active gradients (finite differences), with a
//      backtracking line search. Interior vertices move freely, facet vertices within
//      their facet's plane, segment vertices on their segment's line; input vertices
//      never move. A vertex of the convex hull moves only if the hull stays convex at
//      the edges of its hull faces that are not subfacets (exact orient3d, as
//      check_delaunay tests it; its subfacets stay in their planes): on trimesh-tray-
//      bottom, whose rim is on the hull, that took the tets outside [20, 150] from 11 to
//      5, where the rule before froze every hull vertex with a hull face that is not a
//      subfacet. A move is accepted only if every
//      tet of the star stays positively oriented (exact orient3d) and every subfacet
//      around the vertex stays counterclockwise in its facet triangulation (exact
//      orient2d_projected), and the minimum improves by at least as much as a flip must.
//   3. Vertex insertion. For each tet still bad, a new interior vertex replaces a cavity:
//      the tet and the tets of its region whose circumspheres hold the vertex's starting
//      point (exact insphere), grown across faces that are not subfacets, swallowing no
//      vertex and no subsegment, bounded by a topological sphere. The starting points
//      tried in turn are the centroid, then the centroid pushed both ways along the
//      common normal of the tet's worst edge and its opposite edge (the direction a
//      sliver, or a flat tet filling a shallow fold of the boundary alone, is thinnest
//      in) by a few fractions of its longest edge: a vertex off the flat tet's plane on
//      the domain's side splits its worst angle between two tets. The vertex is placed
//      by the ascent of step 2 over the tets it makes with the cavity's boundary faces;
//      it is kept only if every new tet is positively oriented (exact orient3d) and the
//      worst new tet beats the worst cavity tet (Klingner and Shewchuk's vertex
//      insertion, simplified).
//   4. Vertex deletion. For each tet still bad, each of its interior Steiner vertices is
//      offered to contraction onto each of its neighbours (vertex_deletion.h: the star
//      re-coned from the neighbour, every new tet positively oriented by exact orient3d);
//      the contraction with the best worst new tet is made if that beats the worst tet
//      of the star and leaves no more tets outside the window. An interior vertex has no
//      subfacet or subsegment through it, so the boundary is untouched.
//   5. Polish. After the passes, for the tets still bad: up to kPolishRounds rounds of
//      smoothing, first of the other vertices of the tets nearly as bad (within
//      kPolishMargin of the objective, sliver_improvement.cpp) in the stars of the bad
//      tets' vertices, then of the bad tets' own vertices, each move made only if it adds no tet outside the
//      window to its star (so the count of bad tets never grows). At a local optimum of
//      the max-min objective a bad tet's vertex is held by such a neighbouring tet, inside
//      the window or not, whose other vertices no step moved: on seven corpus inputs with
//      [20, 150] the polish took the tets left outside away from small angles from 203 to
//      141 (improvement_schedule.h bounds its tries).
//      Small-angle holds (ImprovementTarget::small_angle_holds, with a window): each round
//      polishes the bad tets touching no small input angle (small_angles.h) first, then
//      all; and where a move fails because a tet touching a small angle is the worst of
//      the star, worse than every tet touching none, the move is tried again with the
//      tets touching a small angle held as constraints (none falls below the worst of them
//      that is outside the window, none inside the window leaves it) and the worst tet
//      touching none as the objective. A held tet inside the window that breaks the
//      radius-edge or volume bound is held by its angles (it stays inside the window and
//      may go on breaking the bound), not as one outside it: the objective's penalty
//      ranked it below every tet outside the window, so it was the worst held tet of the
//      star and no move could lower it at all. Of the holders in the stars of the tets
//      left outside away from small angles on main before the change, 385 of 1001 on
//      gmsh-netgen-hinge, 410 of 742 on cgal-boeing and 1119 of 2641 on cgal-anchor were
//      such tets (radius-edge above 2, inside [20, 150]), and 530, 196 and 1420 more were
//      above the bound and outside. A move without holds in the polish (with holds on)
//      must keep every tet of the star at or above the least window dihedral sine of the
//      star before it: judged by the objective alone, where a bound breaker is the star's
//      worst, a tet keeping the bounds may fall to any positive sine while the breaker
//      rises (on cgal-anchor such moves made a tet touching a small angle of 0.04 degrees,
//      main's least there being 0.27). Such a tet, left by the termination floors where
//      the small angle makes the bounds unreachable, was the worst of the stars of one or
//      more vertices of 50-76% of the tets left outside [20, 150] away from small angles
//      on cgal-anchor, occt-sh2, cgal-boeing, gmsh-netgen-hinge and cgal-couplingdown, and
//      froze them: no move of those vertices raised the star's worst. Where the held move
//      fails too, it is tried with relaxed holds: every tet touching a small angle held
//      only to the worst of them (one inside the window may leave it), made only if the
//      star then has no more tets outside the window in all and no more of them away from
//      small angles (on gmsh-netgen-hinge, of the 163 tets the polish with strict holds
//      left outside away from small angles, by the table taken at the start of the pass,
//      63 had a vertex whose move gains under relaxed holds and 90 more one that gains
//      only where a tet touching a small angle falls below the worst of them, which no
//      step makes). And each round tries, once per four vertices, a vertex
//      insertion for each bad tet touching no small angle (insert_at; the passes tried
//      each tet once, before the polish moved its vertices), under holds where the
//      cavity's worst tet touches a small angle and is worse than every cavity tet
//      touching none: the new tets touching one are held to that worst and no more of
//      them may leave the window, and the worst new tet touching none must beat the worst
//      old one; then, once per four vertices too, the flips of step 1 for each such tet
//      (the passes retried them only while a pass followed, and the polish's moves change
//      the rings around the tets it leaves) and a vertex deletion (try_delete), judged as
//      the insertion where a tet touching a small angle is the worst of the deleted
//      vertex's star. Before the deletion, edge removal at the holders: the tets of the
//      stars of such a tet's vertices that touch a small angle and are worse than it
//      (which held moves may not lower, so they hold the vertices) are offered edge
//      removal once per four vertices, made if the worst new tet beats the worst of the
//      ring and no new tet touching no small angle lies outside the window (on
//      gmsh-netgen-hinge, cgal-boeing and cgal-anchor the classification of the final
//      mesh found 79 of 82, 92 of 104 and 140 of 142 of the tets left outside away from
//      small angles with a vertex whose star's worst tet touches a small angle and is
//      worse than the tet). Tets touching a small angle never become inverted or degenerate by
//      these steps (exact orient3d on every new or moved tet) nor fall below the worst of
//      them in the star or cavity, by the objective and by their angles alone (the
//      objective ranks a tet breaking a bound below every other whatever its angles: held
//      to it alone, a held tet on cgal-anchor fell to 0.03 degrees where main's worst at
//      small angles is 0.23).
//      Trades: after the polish's rounds, up to kTradeRounds rounds for the bad tets
//      touching no small angle smooth the vertices the polish picks with one more try
//      where the strict and relaxed holds find no move (hold_for_trade): the tets touching
//      a small angle are held only to a floor, each at or above kTradeFraction (one half)
//      of the least window dihedral sine of them in the star, within the smallest and
//      largest dihedral angles of such tets when the trades start (flat tets lying on a
//      facet aside; so the mesh's extreme angles stay those the polish left) and within
//      the bounds where they kept them, a tet touching none inside the window that breaks
//      a bound held inside it by its angles, every other tet touching none kept at or above
//      the least window dihedral sine of them before; made if the worst tet touching none, outside
//      the window, rises and the star has no more tets outside the window away from small
//      angles, and more of them touching a small angle only where fewer lie away from
//      them, or where the least window dihedral sine of the traded tets does not fall;
//      then the polish's steps without trades for the same tets. The trade rounds have
//      kTradeTriesPerTet tries per such tet where less is left of the polish's (on
//      cgal-couplingdown its rounds spent them all on the tets touching a small angle),
//      and a round that leaves as many such tets is followed by another where it made
//      one it was not offered. A smoothing move is tried under the strict holds, then
//      the relaxed ones, then (in the trade rounds) the trade holds wherever the kind
//      before finds no gain or breaks one of its rules, a count rule included; and with
//      small-angle holds no move adds a tet outside the window away from small angles to
//      its star. With [20, 150]
//      the tets left outside the window away from small angles go from 63 to 36 on
//      gmsh-netgen-hinge, 73 to 36 on cgal-boeing and 134 to 75 on cgal-anchor, the
//      extreme angles of the mesh unchanged. A trade's move (trade_move) ascends up to
//      kTradeAscents times, each from the best point of the one before, and where the
//      point reached breaks a trade rule (the ascent scores a traded tet by its sine
//      alone) it is pulled back along the move by halves to the first point that keeps
//      them all and still gains: on main with the improvement rounds 31 -> 25, 28 -> 20
//      and 46 -> 33 on those three inputs.
//      Joint moves (joint_move.h): at the end of each polish round and in each trade
//      round after its trades, a bad tet's two vertices of an edge (worst angle first)
//      move together under the trade rules (polish_joint_moves), where a move of either
//      alone is held by tets only the other's move mends. With [20, 150] the tets left
//      outside away from small angles go from 22 to 10 on gmsh-netgen-hinge, 38 to 16 on
//      cgal-anchor, 25 to 10 on cgal-couplingdown and 14 to 6 on occt-sh2. Made in each
//      polish round right after the smoothing of the bad tets touching none (before the
//      smoothing of those touching one), they left 5, 9, 9 and 6, but cgal-dino 1 (0 on
//      main) and td-slit-1's smallest angle 3.80 degrees (3.86 on main): the smoothing
//      after them raised the worst tets touching a small angle less far.
//      Joint moves with a neighbour: in each trade round after the joint moves, each vertex
//      of a bad tet touching no small angle (of its edges, worst angle first) moves jointly
//      with each of its neighbours outside the tet, under the same rules
//      (polish_neighbour_joint_moves): the worst angle at an edge is set by the whole ring
//      around it, whose other vertices may hold the tet's own. With [20, 150], together
//      with the joint ascent's walls of any rule (joint_move.h), the tets left outside away
//      from small angles go from 20 to 7 on the ten inputs of issue 6's list (docs/MESHING.md,
//      "Joint moves with a neighbour, and walls of any rule (polish)"). Once the trade
//      rounds have started, the plain, held and relaxed smoothing moves keep the tets
//      touching a small angle within the trade's extreme angles too (keeps_trade_extremes),
//      as the traded moves do.
//      Flip trades (flip_trade.h): in each trade round after its joint moves, a bad tet's
//      edges (worst angle first) are offered to edge removal and its faces to 2-3 flips
//      under the trade rules (polish_flip_trades): new tets touching a small angle at or
//      above half the least window dihedral sine of the old ones touching one, within
//      the trade's extremes and the bounds; no more new tets touching none outside the
//      window or breaking a bound than old ones, the worst of them rising. With [20, 150]
//      cgal-anchor's tets outside away from small angles go from 18 to 9 (main at
//      deed1bb); made after the polish rounds' joint moves too, 7, and occt-sh2 4 -> 3,
//      but 43 and 44 more tets above the radius-edge bound on gmsh-netgen-hinge and
//      cgal-boeing, whose counts did not fall.
// The work list after the first scan of the mesh holds only the tets a step made or
// changed, so a pass costs in proportion to the bad tets, not to the mesh. A flip,
// smoothing or deletion that failed is not retried while the stars it read are unchanged
// (change_clock.h: it would fail again, so the result is the same), and vertex insertion
// is tried once per tet (not again for the same four vertices).
// Neither step may create a tet that breaks the radius-edge or volume bounds of the
// options unless it replaces one that already did (under ImprovementTarget::strict_bounds
// not even then: default_improvement.h); such tets rank below every tet that
// keeps the bounds but still by their angles, so where refinement's termination floors
// left skinny tets (quality_refinement.h) the steps may trade them for skinny tets with
// better angles, never for worse ones. The tetrahedralization is no longer
// Delaunay afterwards: run this last, after refinement.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "refiners/tet3d/improvement_schedule.h"
#include "refiners/tet3d/refine_state.h"

namespace delmesh::tet3d {

/// Dihedral-bound refinement (notes §4.4) splits tets outside the dihedral window at
/// their circumcenters like skinny tets, after them (quality_refinement.cpp). On faceted
/// surfaces a sliver split can breed new slivers for a long time before the termination
/// floors stop it, so the splits made for slivers are budgeted: kSliverSplitsPerVertex
/// times the vertices present when refinement starts. Slivers left then are the
/// improvement pass's.
inline constexpr double kSliverSplitsPerVertex = 0.25;
/// Sets the budget from the current vertex count.
void init_sliver_budget(RefineState& state);
/// Uses one split of the budget; false when it is spent.
bool take_sliver_split(RefineState& state);

struct ImprovementStats {
  std::size_t flips23 = 0;
  std::size_t edge_removals = 0;  ///< 3-2, 4-4 and larger edge removals
  std::size_t vertex_moves = 0;   ///< accepted smoothing moves
  std::size_t held_moves = 0;     ///< of which made under small-angle holds
  std::size_t relaxed_held_moves = 0;  ///< of those, with the relaxed holds (step 5)
  std::size_t traded_moves = 0;  ///< of those, with the trade holds (step 5)
  /// Of those, made at a point pulled back along the move from where the ascents ended
  /// (step 5).
  std::size_t pulled_back_trades = 0;
  /// Joint moves of the two vertices of a bad tet's edge in the trade rounds (step 5,
  /// joint_move.h).
  std::size_t joint_moves = 0;
  /// Joint move tries: at most one per bad tet touching no small angle in each polish and
  /// trade round, outside the polish's budget of tries.
  std::size_t joint_tries = 0;
  /// Joint moves of a bad tet's vertex with a neighbour outside it made in the trade
  /// rounds, and the tets they were tried for (polish_neighbour_joint_moves).
  std::size_t neighbour_joint_moves = 0;
  std::size_t neighbour_joint_tries = 0;
  /// Flip trades (flip_trade.h): edge removals and 2-3 flips at a bad tet touching no
  /// small angle judged by the trade rules, after each trade round's joint moves (step 5).
  std::size_t flip_trades = 0;
  /// Flip trade tries: at most one per bad tet touching no small angle in each trade
  /// round, outside the polish's budget of tries.
  std::size_t flip_trade_tries = 0;
  /// The smallest and largest dihedral angles of the tets touching a small input angle
  /// when the polish's trades started, which no trade passes (step 5; 0 and 180 without
  /// trades).
  double trade_min_deg = 0.0, trade_max_deg = 180.0;
  /// Of the held moves, those holding a tet inside the window that breaks a bound by its
  /// angles alone (step 5).
  std::size_t breaker_held_moves = 0;
  std::size_t insertions = 0;     ///< vertices inserted (interior Steiner points)
  std::size_t polish_insertions = 0;  ///< of which made by the polish (step 5)
  std::size_t deletions = 0;      ///< interior Steiner vertices deleted (vertex_deletion.h)
  std::size_t polish_deletions = 0;  ///< of which by the polish (step 5)
  std::size_t polish_flips = 0;   ///< flips of all kinds made by the polish (step 5)
  std::size_t holder_removals = 0;  ///< of which edge removals at holding tets (step 5)
  std::size_t facet_edge_flips = 0;  ///< edges inside a facet flipped (facet_edge_flip.h)
  std::size_t passes = 0;
  std::size_t tries = 0;          ///< steps tried, all kinds (improvement_schedule.h)
  std::size_t polish_tries = 0;   ///< smoothing tries of the polish after the passes
  std::size_t bad_before = 0;     ///< in-domain tets outside the dihedral window, before
  std::size_t bad_after = 0;      ///< and after
  std::size_t bad_after_passes = 0;  ///< after the passes, before the polish
};

/// The window a run of the pass works towards and how much work it may do.
struct ImprovementTarget {
  double min_dihedral_deg = 0.0;
  double max_dihedral_deg = 180.0;
  /// Refuse every step that would make a tet breaking the radius-edge or volume bound of
  /// the options, or a flat one, whatever it removes (a step may still remove such
  /// tets): the count of tets above the bounds never grows. Without it bound breakers
  /// rank below the others by their angles (above).
  bool strict_bounds = false;
  /// The polish may hold tets touching a small input angle as constraints where one of
  /// them is the worst of a star, and smooths for the tets touching none first (step 5).
  bool small_angle_holds = true;
  int max_passes = kMaxPasses;
  std::size_t tries_per_bad_tet = kTriesPerBadTet;
  /// Where given, the pass starts from the bad tets among these tets (slots of the mesh
  /// when it starts; they may repeat) instead of scanning the whole mesh for them: every
  /// step then works from those and the tets the steps make or change, so the pass reads
  /// and changes only a neighbourhood of them (deferred_split.h's polish after a split).
  const std::vector<std::uint32_t>* start_tets = nullptr;
};

/// Improves the in-domain tets of a marked, refined state whose dihedral angles fall
/// outside [target.min_dihedral_deg, target.max_dihedral_deg]. Keeps tet_region up to
/// date, the facet triangulations' coordinates equal to the tetrahedralization's, and
/// state.subfaces / state.subsegments valid.
ImprovementStats improve_slivers(RefineState& state, const ImprovementTarget& target);
/// improve_slivers for the window [options.min_dihedral_deg, options.max_dihedral_deg].
ImprovementStats improve_slivers(RefineState& state);

}  // namespace delmesh::tet3d
