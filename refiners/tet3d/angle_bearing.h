// Skinny tets that bear a small input angle (notes §3.8, carried to 3D): "any Delaunay
// refinement algorithm should be modified so that it does not try to split any skinny
// triangle that bears a small input angle". Quality refinement (quality_refinement.h)
// leaves such tets as they are.
//
// A tet bears the angle at vertex a when its shortest edge (v1, v2) joins vertices on two
// different segments that meet at a, a is a vertex of the tet, and the angle v1 a v2 is
// small. Concentric shells (boundary_split.h) put v1 and v2 at equal distances d from a,
// so the face (a, v1, v2) is isosceles with apex angle alpha and radius-edge ratio
// 1 / (2 sin alpha); every tet on that face has a ratio at least as large. Splitting the
// tet only moves the short edge: its circumcenter encroaches the two subsegments at a,
// whose splits (on the next shell, d / 2) make a new free edge opposite the same angle,
// half as long, and the cycle of Figure 3.34 runs on until the termination floors stop
// it, leaving a cloud of short edges and skinny tets around a that do not touch a.
//
// The threshold: the angle is small when sin alpha < kBearingMargin / (2 B), i.e. when
// the face's ratio exceeds B / kBearingMargin. With kBearingMargin = 1 only faces that
// can never meet B would count (alpha < 20.7 degrees at B = 1.414); measured on the STEP
// tessellations (whose triangle corners of 20-27 degrees are the apices that start the
// cycles at B = 1.414), 1.2 stops the cycles: 25.1 degrees at B = 1.414, 17.4 at B = 2,
// where the rule changes nothing measurable. The apex a is an input vertex where segments
// meet below 60 degrees, so the tets left here are counted among the tets at small angles
// (small_angles.h, rule (a)). The angle is computed in floating point: the rule only
// chooses which tets to refine, and either answer leaves a valid mesh.
#pragma once

#include <cstdint>

#include "refiners/tet3d/refine_state.h"

namespace delmesh::tet3d {

/// Margin of the bearing rule: the face bearing the angle has a radius-edge ratio above
/// B / kBearingMargin.
inline constexpr double kBearingMargin = 1.2;

/// Does tet t bear a small input angle for radius-edge bound `radius_edge` (above)?
bool bears_small_angle(const RefineState& state, std::uint32_t t, double radius_edge);

/// The smallest triangle angle (degrees) to ask of a CAD tessellation meshed at radius-edge
/// bound `radius_edge` (StepImportOptions::surface_min_angle_deg): above the bearing
/// threshold arcsin(kBearingMargin / (2 B)), rounded up, and at least the importer's
/// default 20 (B = 1.414: 26; B >= 1.76: 20). A triangle corner below the threshold is a
/// small input angle whose tets this rule leaves skinny: with the default 20 degrees, 95 of
/// the 120 tets left above 1.414 on pocc-io1-ug-214 bear corners of 20-25 degrees.
double tessellation_min_angle_deg(double radius_edge);

}  // namespace delmesh::tet3d
