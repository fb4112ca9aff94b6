// The tessellation of a CAD face as its own surface: the piecewise linear map from the
// face's parameter plane to 3D that BRepMesh's triangles define (each triangle's parameter
// points to its 3D points, affinely). A face whose refinement on its exact surface folds
// (gmsh-t106-blade's extrusion faces, whose edge nodes lie up to 0.68 units off the
// surface beside 0.06-unit segments at the trailing edge: the surface plus interpolated
// offsets twists there) is refined on this map instead: every new node lies on one of
// BRepMesh's triangles, so the refined face bends only where BRepMesh's did (within its
// chordal deflection of the exact surface), while the refinement itself (Ruppert's
// circumcentre insertion, notes §3.4, in the face's parameter plane with its exact
// orientation tests; surface_refinement.h) is unchanged.
// A parameter point outside every triangle takes the affine map of the triangle whose
// smallest barycentric coordinate is largest (linear continuation beyond the face's edge).
// No OCCT here.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "toolkit/geometry/vec3.h"
#include "toolkit/mesh2d/pslg.h"

namespace delmesh::step {

class TessellationSurface {
 public:
  /// `uv[i]` and `points[i]`: parameter point and 3D point of node i; triangles of local
  /// nodes. Triangles of zero parameter area (collapsed at a pole) are left out.
  TessellationSurface(const std::vector<Point2>& uv, const std::vector<Vec3>& points,
                      const std::vector<std::array<std::uint32_t, 3>>& triangles);

  /// The 3D point at parameter point `uv` (see the header comment); zero without triangles.
  Vec3 point(const Point2& uv) const;

  bool empty() const { return triangles_.empty(); }

 private:
  struct Triangle {
    std::array<Point2, 3> uv;
    std::array<Vec3, 3> points;
  };
  /// Barycentric coordinates of `uv` in triangle t.
  std::array<double, 3> barycentric(std::size_t t, const Point2& uv) const;
  /// Index of the grid cell holding `uv`, clamped to the grid.
  std::size_t cell_of(const Point2& uv) const;

  std::vector<Triangle> triangles_;
  Point2 low_{}, high_{};
  std::size_t columns_ = 1, rows_ = 1;
  std::vector<std::vector<std::uint32_t>> cells_;  ///< triangles overlapping each cell's box
};

}  // namespace delmesh::step
