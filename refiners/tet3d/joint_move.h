// Joint move of the two vertices of a tet's worst edge, for the polish's trades (notes
// §2.2.4, optimization-based smoothing; Freitag and Ollivier-Gooch 1997 and Klingner and
// Shewchuk 2007 move one vertex at a time, this moves two at once).
//
// At a local optimum of single-vertex smoothing a tet's worst dihedral angle, at edge
// (a, b), can be held by tets around a that only a move of b would mend and tets around b
// that only a move of a would: each vertex's star has a tet the other one's move must
// raise first. The joint move ascends over both positions together: the objective is the
// worst quality of the tets touching no small input angle in the union of the two stars,
// its ascent direction the minimum-norm element of the convex hull of the active tets'
// gradients in the product of the two vertices' tangent spaces (finite differences), with
// a backtracking line search, each vertex within its own constraint (an interior vertex
// free, a facet vertex in its facet's plane, a segment vertex on its segment's line; an
// input vertex, or a vertex touching a small input angle, is not moved; nor is a vertex
// with a convex hull face that is not a subfacet).
// It is judged by the trade rules of the polish (sliver_improvement.h, step 5,
// hold_for_trade): a tet of the union touching a small angle stays at or above
// JointMoveRules::trade_fraction of the least window dihedral sine of such tets in the
// union, within the trade's extreme dihedral angles (or its own, where it lies beyond
// them already) and within the radius-edge and volume bounds where it kept them; a tet
// touching none inside the window that breaks a bound stays inside the window; every
// other tet touching none stays at or above the least window dihedral sine of them
// before, within the bounds where it kept them (the objective alone lets such a tet start
// breaking one where the worst of them already does: on gmsh-netgen-hinge and cgal-boeing
// 7 and 15 tets were left outside [20, 150] away from small angles without this rule, 5
// and 13 with it, the joint moves then made right after each polish round's smoothing of
// the tets touching none), and makes the objective, which must rise by JointMoveRules::min_gain; the union
// has no more tets outside the window away from small angles after the move, and more
// of them touching a small angle only where fewer lie away from them or the least window
// dihedral sine of the tets touching one does not fall. Every tet of the union stays
// positively oriented (exact orient3d with both vertices moved) and every subfacet around
// either vertex counterclockwise in its facet (exact orient2d_projected, checked for a
// with b where it was and for b with a moved: a subfacet holding both is checked twice).
// The ascent makes at most kJointIterations steps of at most kJointHalvings halvings; where
// the shortest step breaks a rule of a tet of the union, the measure that rule keeps joins
// the active gradients and the step is tried again (at most kJointWalls such tets): minus
// the gradient of the tet's radius-edge ratio where it kept the bounds and crosses one (on
// trimesh-tray-bottom a tet at radius-edge 1.998 otherwise ended both ascents where they
// started), the gradient of its signed volume (over the cube of the shortest edge at a or
// b) where it lies outside the domain and inverts, else the gradient of its window
// dihedral sine (a tet touching a small angle falling below its floor or beyond its
// extreme angles, one touching none falling below the least of them before or leaving the
// window as a bound breaker). With [20, 150], the tets left outside the window away from
// small angles whose ascents all stopped at their first step so: occt-sh2's 2 and
// cgal-homer's tet at 19.59 degrees (held by tets touching a small angle, at their floor),
// cgal-boeing's facet-edge tet at 19.05 degrees (its one movable vertex, on the facet,
// inverted a flat exterior tet at every step length).
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <vector>

#include "refiners/tet3d/refine_state.h"
#include "refiners/tet3d/trade_rules.h"
#include "toolkit/geometry/vec3.h"

namespace delmesh::tet3d {

/// Most steps of a joint ascent and halvings of its line search.
inline constexpr int kJointIterations = 12;
inline constexpr int kJointHalvings = 8;
/// Most tets whose rule a joint ascent keeps as a direction once its shortest step broke
/// it (joint_move.cpp, ascend).
inline constexpr std::size_t kJointWalls = 4;

/// The trade rules and the objective a joint move is judged by.
struct JointMoveRules : TradeRules {
  /// The improvement objective of an in-domain tet (its window dihedral sine, ranked below
  /// every tet keeping the bounds where it breaks one).
  std::function<double(int, const Vec3&, const Vec3&, const Vec3&, const Vec3&)> quality;
};

/// A joint move found by plan_joint_move: a to pa, b to pb; `tets` the union of their
/// stars (finite tets).
struct JointMove {
  std::uint32_t a = 0, b = 0;
  Vec3 pa = Vec3::Zero(), pb = Vec3::Zero();
  std::vector<std::uint32_t> tets;
};

/// A move of a and b (an edge of the mesh) by the rules above, into `move`; false when
/// either may not move or no point gains. The mesh is left as it was.
bool plan_joint_move(RefineState& state, const JointMoveRules& rules, std::uint32_t a, std::uint32_t b,
                     JointMove& move);

}  // namespace delmesh::tet3d
