// Local optimisation of CAD face tessellations after refinement (notes §2.2.4, smoothing
// and topological transformations; Freitag and Ollivier-Gooch 1997, "Tetrahedral mesh
// improvement using swapping and smoothing"): every node inside a face (on no CAD edge)
// whose star holds a triangle below the angle bound is moved on the surface to raise the
// smallest 3D angle of its star (a compass search in the face's parameter plane, the
// steps scaled by the star's least-squares first fundamental form), and edges inside a
// face are flipped where that raises the smallest 3D angle of their two triangles. Every
// move and flip keeps each face a valid triangulation of its parameter domain (exact
// orientation tests), turns no triangle against the surface normal and bends the face no
// more sharply than before (or than kMaxBendDeg), and creates no edge that another face
// already has. Triangles whose smallest angle lies between two CAD segments, or that touch
// a face corner under kSmallFaceCornerDeg (surface_mesh_quality.h), are fixed by the
// input: the search does not aim at them but never makes them worse. No OCCT here.
#pragma once

#include <cstddef>
#include <vector>

#include "importers/step/surface_refinement.h"
#include "toolkit/geometry/vec3.h"

namespace delmesh::step {

struct SurfaceSmoothingOptions {
  double min_angle_deg = 20.0;  ///< nodes whose star has a triangle below this move
  int passes = 8;               ///< rounds of moves and flips
};

struct SurfaceSmoothingStats {
  std::size_t moves = 0;
  std::size_t flips = 0;
};

/// Improves the faces of `meshes` marked refine in place (moves interior nodes, whose
/// points in `points` change, and flips inner edges).
SurfaceSmoothingStats smooth_surface_meshes(SurfaceMeshes& meshes, std::vector<Vec3>& points,
                                            const SurfaceSmoothingOptions& options,
                                            const SurfacePoint& surface_point,
                                            const SurfaceNormal& surface_normal);

}  // namespace delmesh::step
