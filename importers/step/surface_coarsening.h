// Removal of crowded inner nodes from refined CAD face tessellations (notes §2.2.4,
// topological transformations; the half-edge collapse of mesh simplification, Hoppe
// 1996, "Progressive meshes"): BRepMesh may place a face's inner nodes in columns far
// closer across than along the face (gmsh-fusee-rocket's strip face 107: columns of nodes
// 0.13 apart, 1.6 to 4.8 apart along it), leaving needles between the columns that
// Delaunay refinement, which never removes a node, cannot repair where their
// circumcentres are blocked by a segment held unsplit. After refinement, before the node
// moves (surface_smoothing.h), a node inside a face (on no CAD edge, one copy) whose star
// holds a triangle below the angle bound is merged into the neighbour that gives the
// star's polygon the largest smallest 3D angle, where that angle is larger than the
// star's now: the neighbour stays where it is, so no point moves and shared edge
// discretisations are untouched. A collapse keeps the face a valid triangulation of its
// parameter domain (exact orientation tests), creates no edge the face or another face
// already has, turns no triangle against the surface normal (beyond 90 degrees, unless a
// triangle it replaces was) and lets no triangle's centre lie farther from the surface
// than the deflection bound (or than before). No OCCT here.
#pragma once

#include <cstddef>
#include <vector>

#include "importers/step/surface_refinement.h"
#include "toolkit/geometry/vec3.h"

namespace delmesh::step {

struct SurfaceCoarseningOptions {
  double min_angle_deg = 20.0;   ///< nodes whose star has a triangle below this may go
  double max_deflection = 0.0;   ///< bound on a new triangle's centre from the surface (<= 0: off)
};

/// Collapses crowded inner nodes of the faces of `meshes` marked refine (faces with
/// offsets excepted); returns how many nodes were removed. Removed nodes stay in the
/// face's node lists, used by no triangle.
std::size_t coarsen_surface_meshes(SurfaceMeshes& meshes, const std::vector<Vec3>& points,
                                   const SurfaceCoarseningOptions& options, const SurfacePoint& surface_point,
                                   const SurfaceNormal& surface_normal);

}  // namespace delmesh::step
