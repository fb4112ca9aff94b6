// Offsets of a loose face's edges blended into the face over a reach in 3D. On a loose CAD
// model an edge's 3D curve may lie far from the face's surface at the edge's parameters
// (gmsh-t106-blade's extrusion face 3: 0.72 units at the trailing edge, beside 0.07-unit
// segments). BRepMesh puts the edge nodes on the curve and the inner nodes on the surface,
// and its first row of triangles bridges the offset wherever that row lies: on face 3,
// 0.01 units above the z = 0 cap, a lip 0.72 units wide lying almost in the cap's plane
// (its triangles' smallest angles 1.3 degrees, the 3D mesh's tets between lip and cap
// flat), squeezed 70-fold in the face's parameter plane. Interpolating the
// nodes' offsets over BRepMesh's triangles keeps the lip; this blend instead gives every
// point of the surface the offset of the boundary near it (Shepard's inverse-square
// distance weights over pieces of the face's boundary, each piece contributing the offset
// interpolated at its point nearest to the surface point: a piece's own offset on the
// piece, and no steps between samples) scaled by (1 - d / reach)^2, d the distance to the
// nearest piece, zero beyond the reach: the face ramps from its edges onto its surface
// over the reach (twice the largest offset) and the parameter plane keeps the surface's
// metric.
// Distances are taken between surface points, so the blend depends on where a point lies
// on the surface, not on the triangulation. No OCCT here.
#pragma once

#include <array>
#include <vector>

#include "toolkit/geometry/vec3.h"

namespace delmesh::step {

class OffsetBlend {
 public:
  struct Sample {
    Vec3 surface = Vec3::Zero();  ///< the surface point at a boundary place
    Vec3 offset = Vec3::Zero();   ///< the boundary's point minus that surface point
  };
  /// A straight piece of the boundary between two samples, the offset linear along it.
  using Piece = std::array<Sample, 2>;
  /// Blend of the boundary pieces' offsets over `reach` (3D).
  OffsetBlend(std::vector<Piece> pieces, double reach);

  /// The offset at surface point `surface` (zero farther than the reach from every piece).
  Vec3 offset(const Vec3& surface) const;

 private:
  std::vector<Piece> pieces_;
  double reach_ = 0.0;
};

}  // namespace delmesh::step
