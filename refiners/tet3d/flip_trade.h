// Flip trades: edge removal and 2-3 flips at a bad tet touching no small input angle,
// judged by the trade rules of the polish (notes §2.2.4 on topological transformations;
// Shewchuk 2002's edge removal by dynamic programming, toolkit/tetmesh; the trade rules
// of sliver_improvement.h, step 5, hold_for_trade).
//
// At a local optimum of the polish a bad tet's edge or face may be held by a tet touching
// a small input angle that every flip of the ring would make worse than the worst old tet,
// so the ordinary flips (a flip is made only if the worst new tet beats the worst old one)
// refuse it. A flip trade may make such tets worse within the trade floors, to bring the
// tets touching none into the window:
//   - the old tets (the ring of edge (a, b), or the two tets of a face) lie in one region
//     of the domain, the edge is no subsegment and no face removed is a subfacet (so the
//     boundary, its markers and the regions stay as they are), and at least one old tet
//     touching no small angle lies outside the window;
//   - every new tet touching no small angle lies inside the window (so the tets outside
//     the window away from small angles fall by one at least), and no more of them break
//     the radius-edge or volume bounds than old tets touching none did;
//   - every new tet touching a small angle has a window dihedral sine at or above
//     FlipTradeRules::trade_fraction of the least of the old tets touching one, dihedral
//     angles within the trade's extremes (or the old tets' own where they lie beyond
//     them: the mesh's extreme angles never get worse), and no more of the new tets
//     touching a small angle break the radius-edge or volume bounds than old tets
//     touching one did (where none did, none may: a tet touching a small angle never
//     starts breaking a bound unless another such tet stops). On cgal-boeing with
//     [20, 150] the 3-2 flip of an edge whose ring held a tet touching none at 10.4
//     degrees and two tets touching a small angle, one of them above radius-edge 2,
//     gives two tets at 25.6 to 143.4 degrees, one above radius-edge 2 (3.2): refused
//     while every new tet touching a small angle had to keep the bounds;
//   - the worst new tet touching none beats the worst old one by FlipTradeRules::min_gain.
// Edge removal chooses the ring triangulation maximizing the worst new tet touching none
// among those keeping the per-tet rules (toolkit/tetmesh remove_edge, planned first with
// the same dynamic programming for the count of bound breakers); every new tet is checked
// positively oriented by exact orient3d before the mesh changes, so no tet inverts and
// the old tets' volume is filled exactly.
#pragma once

#include <cstdint>
#include <vector>

#include "refiners/tet3d/refine_state.h"
#include "refiners/tet3d/trade_rules.h"
#include "toolkit/geometry/vec3.h"

namespace delmesh::tet3d {

/// The trade rules and the largest ring a flip trade is judged by.
struct FlipTradeRules : TradeRules {
  /// Most tets around an edge offered to removal.
  std::size_t max_ring = 12;
};

/// Removes edge (a, b) by the rules above; the new tets into `created`, and `region`
/// their region. False (the mesh unchanged) where no ring triangulation keeps them.
bool trade_remove_edge(RefineState& state, const FlipTradeRules& rules, std::uint32_t a, std::uint32_t b,
                       std::vector<std::uint32_t>& created, int& region);

/// 2-3 flip of face f of tet t by the rules above; as trade_remove_edge.
bool trade_flip23(RefineState& state, const FlipTradeRules& rules, std::uint32_t t, int f,
                  std::vector<std::uint32_t>& created, int& region);

}  // namespace delmesh::tet3d
