// Quality improvement of the tessellation of CAD faces before they become PLC facets:
// edge flips that raise the smallest 3D angle and longest-edge bisection (Rivara 1984,
// "Algorithms for refining triangular grids suitable for adaptive and multigrid
// techniques") of triangles whose smallest 3D angle is below a bound, with new interior
// nodes placed on the surface at the midpoint of the edge in the face's parameter plane
// and new boundary nodes on the CAD edge at the parameter midpoint. A split boundary
// segment is split in every face that uses it, so faces keep sharing their edge
// discretisation. Validity is kept in each face's parameter plane with exact orientation
// tests. No OCCT here: the caller evaluates surfaces and curves.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

#include "toolkit/geometry/vec3.h"
#include "toolkit/mesh2d/pslg.h"

namespace delmesh::step {

struct SurfaceMeshes {
  struct Face {
    bool refine = true;  ///< flips and interior bisection allowed (boundary splits always apply)
    /// Boundary splits must not give this face a triangle with a smaller angle than its
    /// smallest one before refinement (or the bound): for faces excluded from refinement
    /// because refining them made them worse.
    bool keep_min_angle = false;
    /// Longest-edge bisection where a circumcentre cannot go in (off for faces that
    /// bisection folded or left worse).
    bool bisect = true;
    bool bisected = false;  ///< set by refinement: a longest-edge bisection went in
    std::vector<std::uint32_t> node_vertex;  ///< local node -> PLC vertex
    std::vector<Point2> uv;                  ///< local node -> surface parameters
    std::vector<std::array<std::uint32_t, 3>> triangles;  ///< local nodes
    /// Local node -> its 3D point minus the surface point at its parameters, on faces whose
    /// edge nodes lie off their surface (loose CAD tolerances: the edges' 3D curves and
    /// their curves on the face disagree); empty on the others. New nodes go to the
    /// surface point plus the offset interpolated from their triangle's (or edge's) nodes,
    /// so the refined face follows its edge nodes instead of twisting between them and the
    /// surface.
    std::vector<Vec3> offset;
    /// Balls where the deflection bound is tighter than the options' (where an earlier
    /// refinement made this face cross another: closer chords keep them apart).
    struct DeflectionZone {
      Vec3 center = Vec3::Zero();
      double radius = 0.0;
      double max_deflection = 0.0;
    };
    std::vector<DeflectionZone> zones;
  };
  /// The discretisation of one CAD edge: PLC vertices at increasing curve parameters.
  struct Edge {
    std::vector<double> parameters;
    std::vector<std::uint32_t> vertices;
  };
  std::vector<Face> faces;
  std::vector<Edge> edges;
};

struct SurfaceRefinementOptions {
  double min_angle_deg = 20.0;        ///< bisect triangles whose smallest angle is below
  double min_edge_length = 0.0;       ///< never split an edge shorter than this (3D)
  /// Also split triangles whose centre is farther than this from the surface (<= 0: off).
  double max_deflection = 0.0;
  std::size_t max_new_points = 0;     ///< budget of new vertices
};

struct SurfaceRefinementStats {
  std::size_t flips = 0;
  std::size_t interior_splits = 0;
  std::size_t boundary_splits = 0;
  double min_angle_before_deg = 180.0;  ///< over triangles of refined faces
  double min_angle_after_deg = 180.0;
};

/// Surface point of face `face` at parameters `uv`.
using SurfacePoint = std::function<Vec3(std::size_t face, const Point2& uv)>;
/// Unit normal Su x Sv of face `face` at parameters `uv` (zero where it is undefined).
using SurfaceNormal = std::function<Vec3(std::size_t face, const Point2& uv)>;
/// Point of CAD edge `edge` at curve parameter `t`.
using EdgePoint = std::function<Vec3(std::size_t edge, double t)>;
/// Parameters of the point of face `face`'s surface nearest to `point`, searched from
/// parameters `start` (nothing where the projection fails).
using SurfaceParameters =
    std::function<std::optional<Point2>(std::size_t face, const Vec3& point, const Point2& start)>;

/// Improves `meshes` in place; new vertices are appended to `points`. With a
/// `surface_normal`, no flip or split creates a triangle (other than a thin one, below
/// 5 degrees, which the following flips replace) whose normal points away from the
/// surface normal at its centre (more than 90 degrees from it) unless a triangle it
/// replaces already did: refinement does not fold faces over. With `surface_parameters`,
/// on a face with a pole (a triangle of BRepMesh's joins two copies of one node) the
/// circumcentre of a triangle whose parameter-plane circumcentre (the 3D circumcentre's
/// barycentric coordinates applied to the parameters) falls outside the face's parameter
/// range is found by projecting the 3D circumcentre onto the surface instead: beside a
/// pole the parameters are polar coordinates, and a triangle reaching round the pole has
/// its circumcentre near the pole in 3D but far outside the face by that affine map. At a
/// pole that is a corner of a face (a CAD edge ends there), the collapsed triangle gets a
/// node at the distance of the corner's first edge nodes when its apex lies more than
/// twice as far; triangles whose smallest angle lies at a face corner narrower than the
/// bound are not refined. A circumcentre that a segment never split blocks (it lies in the
/// segment's diametral circle and would make a triangle on it under the bound) is replaced
/// by the point lifted off the segment to where its triangle with the segment meets the
/// bound; a lifted point splits no segment.
SurfaceRefinementStats refine_surface_meshes(SurfaceMeshes& meshes, std::vector<Vec3>& points,
                                             const SurfaceRefinementOptions& options,
                                             const SurfacePoint& surface_point,
                                             const EdgePoint& edge_point,
                                             const SurfaceNormal& surface_normal = {},
                                             const SurfaceParameters& surface_parameters = {});

}  // namespace delmesh::step
