// Inexact geometric constructions: circumcenters of triangles (in 3D, in the triangle's
// plane) and tetrahedra, computed relative to one vertex for accuracy (notes §3.5.2 on
// where Delaunay refinement inserts vertices). These only produce candidate positions;
// every decision about them is made afterwards with the exact predicates.
#pragma once

#include <optional>

#include "toolkit/geometry/vec3.h"

namespace delmesh {

/// Circumcenter of triangle abc in its plane; nullopt if abc is degenerate (collinear).
std::optional<Vec3> triangle_circumcenter(const Vec3& a, const Vec3& b, const Vec3& c);

/// Circumcenter of tetrahedron abcd; nullopt if abcd is flat.
std::optional<Vec3> tet_circumcenter(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d);

/// Index (0, 1, 2) of the coordinate axis along which `normal` has its largest magnitude:
/// the axis a planar facet is projected along for its 2D predicates.
int dominant_axis(const Vec3& normal);

}  // namespace delmesh
