// CAD solids to PLC (see cad_to_plc.h).
//
// One shared vertex set: every TopoDS_Vertex becomes one PLC vertex, and every interior
// node of an edge's discretisation one PLC vertex, keyed by (edge, curve parameter).
// BRepMesh discretises each edge once and stores that discretisation as a polygon on the
// triangulation of every face using the edge (two polygons for a seam), so looking nodes
// up by parameter gives faces sharing an edge identical vertex ids along it, and the
// facets of adjacent faces meet along shared segments. Face-interior nodes are private
// to their face.
//
// Planar faces: the outer wire and the inner wires, walked in order, give the facet's
// polygons; each inner loop gets a hole point (polygon_interior_point.h). Facet
// planarity is decided exactly (orient3d), so vertices of faces lying in a coordinate
// plane (x, y or z constant, the common case in machined parts) are first snapped onto
// that plane's coordinate, after the plane values of each axis within the plane tolerance
// (TessellationParameters::plane_merge_tolerance) are merged into one (coordinate_planes.h:
// the parts of an assembly place the same plane a few ulps apart); a vertex asked to snap
// to two different values on one axis is left alone. Planar faces whose vertices still are not exactly coplanar (tilted planes)
// are written as triangles instead, each carrying the face marker.
//
// Curved faces and those fallback planar faces start from BRepMesh's triangulation and
// are refined for bounded angles (surface_refinement.h); refinement splits CAD edges in
// every face using them. It is accepted face by face: a face whose smallest angle it
// lowers (below the bound), that it folds, or whose triangles it makes cross another
// face's is excluded (one with loose edges that folds is first refined with its edges'
// offsets blended into it, offset_blend.h, then on its own tessellation) and the
// refinement rerun from BRepMesh's triangulation; only if that
// does not settle is it undone for the model.
//
// BRepMesh sometimes folds the triangulation of a face over a small neighbouring face, so
// that both contain the same triangle with opposite orientations; such pairs bound no
// volume and are removed before refinement (counted in the report), which keeps the
// boundary closed.
//
// Regions: a point strictly inside each solid. From the centroids of the largest boundary
// triangles (planar faces first) a ray is cast inward and the midpoint of its first
// crossing taken; the deepest candidate that BRepClass3d_SolidClassifier places inside and
// whose distance to the planar faces is positive and to the curved faces exceeds the
// chordal deflection (so it is inside the tessellated boundary too) wins.
#include "importers/step/cad_to_plc.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <memory>
#include <numbers>
#include <optional>
#include <set>
#include <vector>

#include <BRepAdaptor_Curve.hxx>
#include <BRepAdaptor_Surface.hxx>
#include <BRepBuilderAPI_MakeVertex.hxx>
#include <BRepClass3d_SolidClassifier.hxx>
#include <BRepExtrema_DistShapeShape.hxx>
#include <BRepMesh_IncrementalMesh.hxx>
#include <BRepTools.hxx>
#include <BRepTools_WireExplorer.hxx>
#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <GeomAbs_SurfaceType.hxx>
#include <IntCurvesFace_ShapeIntersector.hxx>
#include <Precision.hxx>
#include <ShapeAnalysis_Surface.hxx>
#include <gp_Lin.hxx>
#include <Poly_PolygonOnTriangulation.hxx>
#include <Poly_Triangulation.hxx>
#include <TColStd_HArray1OfReal.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Compound.hxx>
#include <TopoDS_Edge.hxx>
#include <TopoDS_Face.hxx>
#include <TopoDS_Wire.hxx>
#include <gp_Pln.hxx>
#include <gp_Pnt2d.hxx>

#include <Eigen/Geometry>

#include "importers/step/coordinate_planes.h"
#include "importers/step/offset_blend.h"
#include "importers/step/polygon_interior_point.h"
#include "importers/step/surface_coarsening.h"
#include "importers/step/surface_mesh_quality.h"
#include "importers/step/surface_refinement.h"
#include "importers/step/tessellation_surface.h"
#include "toolkit/plc/plc_validate.h"
#include "toolkit/predicates/predicates.h"

namespace delmesh::step {
namespace {

constexpr std::int64_t kUnset = -1;
/// Refinement may not fold a face more sharply than this (or than BRepMesh did): the
/// dihedral angle between two of its triangles at an edge inside it, in degrees.
constexpr double kMinFaceDihedralDeg = 120.0;
/// A blended face (offset_blend.h) ramps from its edges onto its surface over this many
/// times its largest edge offset, its boundary sampled this many times per reach.
constexpr double kBlendReach = 2.0;
constexpr double kBlendSamplesPerReach = 8.0;
/// Points per boundary side at which the largest offset is looked for.
constexpr int kBlendProbes = 16;
/// At most about this many boundary pieces per blended face (plus one per side).
constexpr double kBlendMaxPieces = 20000.0;
/// A face crossing another after refinement, or folded, gets up to this many rounds of a
/// 4 times tighter deflection bound around the places before it is excluded.
constexpr int kTightenings = 4;
/// A face whose nodes lie farther than this many chordal deflections from its surface at
/// their parameters is refined with offsets (set_loose_face_offsets).
constexpr double kLooseNodeDeflections = 0.5;
/// ... or farther from it than this fraction of the shortest edge at the node
/// (gmsh-t106-blade's extrusion face 4: nodes up to 0.15 units off its surface, under half
/// the deflection, beside the 0.064-unit segments of the trailing edge; with a quarter
/// gmsh-fusee-rocket's tessellation would change too, with a half only that face's on
/// the corpus).
constexpr double kLooseNodeEdgeFraction = 0.5;

Vec3 to_vec(const gp_Pnt& p) { return Vec3(p.X(), p.Y(), p.Z()); }

/// Exactly collinear (or coincident) 3D points: every coordinate projection degenerates.
bool collinear(const Vec3& a, const Vec3& b, const Vec3& c) {
  for (Axis axis : {Axis::X, Axis::Y, Axis::Z}) {
    if (predicates::orient2d_projected(a.data(), b.data(), c.data(), axis) != Sign::Zero) return false;
  }
  return true;
}

struct EdgeNodes {
  std::vector<double> parameters;  ///< increasing
  std::vector<std::uint32_t> ids;  ///< PLC vertex of each parameter
};

struct PlanarLoops {
  bool usable = false;
  bool coordinate_plane = false;  ///< perpendicular to a coordinate axis (vertices snapped)
  Axis axis = Axis::Z;
  std::vector<Plc::Polygon> loops;  ///< outer first
};

class PlcBuilder {
 public:
  PlcBuilder(const CadModel& model, const TessellationParameters& parameters,
             const std::string& file, TessellationReport& report)
      : model_(model), parameters_(parameters), file_(file), report_(report) {
    TopExp::MapShapes(model.shape, TopAbs_FACE, faces_);
    TopExp::MapShapes(model.shape, TopAbs_EDGE, edges_);
    TopExp::MapShapes(model.shape, TopAbs_VERTEX, vertices_);
    TopExp::MapShapes(model.shape, TopAbs_SOLID, solids_);
    int next_face_id = model.face_count;
    for (int f = 1; f <= faces_.Extent(); ++f) {
      face_markers_.push_back(model.face_ids.IsBound(faces_(f)) ? model.face_ids.Find(faces_(f)) : ++next_face_id);
    }
    vertex_ids_.assign(static_cast<std::size_t>(vertices_.Extent()) + 1, kUnset);
    edge_nodes_.resize(static_cast<std::size_t>(edges_.Extent()) + 1);
    face_node_ids_.resize(static_cast<std::size_t>(faces_.Extent()) + 1);
    report_.faces = faces_.Extent();
  }

  Expected<Plc> build() {
    if (Expected<void> shared = map_boundary_nodes(); !shared) return shared.error();
    build_surface_meshes();
    cancel_opposite_triangles();
    mark_polygon_faces();
    refine_surfaces();
    std::vector<PlanarLoops> planar(static_cast<std::size_t>(faces_.Extent()) + 1);
    for (int f = 1; f <= faces_.Extent(); ++f) planar[f] = planar_loops(f);
    snap_to_coordinate_planes();
    for (int f = 1; f <= faces_.Extent(); ++f) {
      if (!(planar[f].usable && add_polygon_facet(f, planar[f]))) add_triangle_facets(f);
    }
    remove_unused_points();
    plc_.facet_marker_names = model_.face_id_names;
    for (const auto& [id, rgb] : model_.face_id_colors) plc_.facet_marker_colors[id] = {rgb[0], rgb[1], rgb[2]};
    if (Expected<void> regions = add_regions(); !regions) return regions.error();
    return std::move(plc_);
  }

 private:
  std::uint32_t vertex_id(const TopoDS_Vertex& v) {
    const int index = vertices_.FindIndex(v);
    DELMESH_CHECK(index > 0, "vertex outside the model");
    if (vertex_ids_[index] == kUnset) {
      vertex_ids_[index] = static_cast<std::int64_t>(plc_.points.size());
      plc_.points.push_back(to_vec(BRep_Tool::Pnt(v)));
    }
    return static_cast<std::uint32_t>(vertex_ids_[index]);
  }

  std::uint32_t new_point(const gp_Pnt& p) {
    plc_.points.push_back(to_vec(p));
    return static_cast<std::uint32_t>(plc_.points.size() - 1);
  }

  /// Gives every node on an edge of every face its shared PLC vertex id.
  Expected<void> map_boundary_nodes() {
    for (int f = 1; f <= faces_.Extent(); ++f) {
      const TopoDS_Face& face = TopoDS::Face(faces_(f));
      TopLoc_Location location;
      const Handle(Poly_Triangulation)& triangulation = BRep_Tool::Triangulation(face, location);
      if (triangulation.IsNull()) {
        return make_error(ErrorCode::InvalidInput,
                          file_ + ": CAD face " + std::to_string(f) + " could not be tessellated");
      }
      face_node_ids_[f].assign(static_cast<std::size_t>(triangulation->NbNodes()) + 1, kUnset);
      for (TopExp_Explorer it(face, TopAbs_EDGE); it.More(); it.Next()) {
        const TopoDS_Edge& edge = TopoDS::Edge(it.Current());
        const Handle(Poly_PolygonOnTriangulation)& polygon =
            BRep_Tool::PolygonOnTriangulation(edge, triangulation, location);
        if (polygon.IsNull()) {
          return make_error(ErrorCode::InvalidInput,
                            file_ + ": an edge of CAD face " + std::to_string(f) +
                                " has no discretisation");
        }
        map_edge(f, edge, *polygon, *triangulation, location);
      }
    }
    return {};
  }

  void map_edge(int f, const TopoDS_Edge& edge, const Poly_PolygonOnTriangulation& polygon,
                const Poly_Triangulation& triangulation, const TopLoc_Location& location) {
    const int e = edges_.FindIndex(edge);
    DELMESH_CHECK(e > 0, "edge outside the model");
    const int n = polygon.NbNodes();
    const Handle(TColStd_HArray1OfReal)& given = polygon.Parameters();
    std::vector<std::pair<double, int>> nodes;  // (parameter, triangulation node)
    for (int i = 1; i <= n; ++i) {
      nodes.emplace_back(given.IsNull() ? static_cast<double>(i) : given->Value(i), polygon.Node(i));
    }
    std::sort(nodes.begin(), nodes.end());
    EdgeNodes& shared = edge_nodes_[e];
    std::vector<std::int64_t>& node_ids = face_node_ids_[f];
    if (shared.ids.empty()) {
      TopoDS_Vertex first, last;
      TopExp::Vertices(edge, first, last);
      const bool degenerated = BRep_Tool::Degenerated(edge);
      for (int i = 0; i < n; ++i) {
        std::uint32_t id = 0;
        if (degenerated || i == 0) {
          id = vertex_id(first);
        } else if (i == n - 1) {
          id = vertex_id(last);
        } else {
          id = new_point(triangulation.Node(nodes[i].second).Transformed(location.Transformation()));
        }
        shared.parameters.push_back(nodes[i].first);
        shared.ids.push_back(id);
      }
    }
    for (const auto& [parameter, node] : nodes) {
      const auto& params = shared.parameters;
      auto at = std::lower_bound(params.begin(), params.end(), parameter);
      if (at == params.end() || *at != parameter) {
        ++report_.edge_node_mismatches;
        if (at == params.end() ||
            (at != params.begin() && parameter - *(at - 1) < *at - parameter)) {
          --at;
        }
      }
      if (node_ids[node] == kUnset) node_ids[node] = shared.ids[at - params.begin()];
    }
  }

  std::uint32_t face_node(int f, int node, const Poly_Triangulation& triangulation,
                          const TopLoc_Location& location) {
    std::int64_t& id = face_node_ids_[f][node];
    if (id == kUnset) id = new_point(triangulation.Node(node).Transformed(location.Transformation()));
    return static_cast<std::uint32_t>(id);
  }

  /// The loops of a planar face from its wires (outer first), or usable=false.
  PlanarLoops planar_loops(int f) {
    PlanarLoops result;
    const TopoDS_Face& face = TopoDS::Face(faces_(f));
    BRepAdaptor_Surface surface(face, Standard_False);
    if (surface.GetType() != GeomAbs_Plane) return result;
    const gp_Dir normal = surface.Plane().Axis().Direction();
    const std::array<double, 3> n{std::abs(normal.X()), std::abs(normal.Y()), std::abs(normal.Z())};
    result.axis = static_cast<Axis>(std::max_element(n.begin(), n.end()) - n.begin());
    const TopoDS_Wire outer = BRepTools::OuterWire(face);
    if (outer.IsNull()) return result;
    std::vector<TopoDS_Wire> wires{outer};
    for (TopExp_Explorer it(face, TopAbs_WIRE); it.More(); it.Next()) {
      if (!it.Current().IsSame(outer)) wires.push_back(TopoDS::Wire(it.Current()));
    }
    for (const TopoDS_Wire& wire : wires) {
      Plc::Polygon loop;
      int walked = 0;
      for (BRepTools_WireExplorer it(wire, face); it.More(); it.Next()) {
        const TopoDS_Edge& edge = it.Current();
        ++walked;
        const EdgeNodes& shared = edge_nodes_[edges_.FindIndex(edge)];
        if (shared.ids.empty()) return result;
        std::vector<std::uint32_t> ids = shared.ids;
        if (edge.Orientation() == TopAbs_REVERSED) std::reverse(ids.begin(), ids.end());
        loop.insert(loop.end(), ids.begin(), ids.end() - 1);
      }
      int edges_in_wire = 0;
      for (TopExp_Explorer it(wire, TopAbs_EDGE); it.More(); it.Next()) ++edges_in_wire;
      if (walked != edges_in_wire) return result;
      loop.erase(std::unique(loop.begin(), loop.end()), loop.end());
      while (loop.size() > 1 && loop.front() == loop.back()) loop.pop_back();
      std::vector<std::uint32_t> sorted = loop;
      std::sort(sorted.begin(), sorted.end());
      if (loop.size() < 3 || std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end()) {
        return result;
      }
      result.loops.push_back(std::move(loop));
    }
    const int k = static_cast<int>(result.axis);
    if (n[(k + 1) % 3] < 1e-12 && n[(k + 2) % 3] < 1e-12) {
      result.coordinate_plane = true;
      const double value = surface.Plane().Location().Coord(k + 1);
      for (const Plc::Polygon& loop : result.loops) {
        for (std::uint32_t v : loop) snaps_.push_back({v, k, value});
      }
    }
    result.usable = true;
    return result;
  }

  /// Moves vertices of faces lying in coordinate planes exactly onto them (within the
  /// CAD tolerance they already are), unless a vertex is asked for two values on an axis;
  /// plane values within the plane tolerance are first merged (coordinate_planes.h).
  void snap_to_coordinate_planes() {
    report_.coordinate_plane_values_merged =
        merge_coordinate_plane_values(snaps_, parameters_.plane_merge_tolerance);
    std::sort(snaps_.begin(), snaps_.end(), [](const PlaneSnap& a, const PlaneSnap& b) {
      return a.vertex != b.vertex ? a.vertex < b.vertex : a.axis < b.axis;
    });
    for (std::size_t i = 0; i < snaps_.size();) {
      std::size_t j = i;
      bool agree = true;
      while (j < snaps_.size() && snaps_[j].vertex == snaps_[i].vertex && snaps_[j].axis == snaps_[i].axis) {
        agree = agree && snaps_[j].value == snaps_[i].value;
        ++j;
      }
      if (agree) plc_.points[snaps_[i].vertex][snaps_[i].axis] = snaps_[i].value;
      i = j;
    }
    snaps_.clear();
  }

  /// The polygonal facet of planar face f, or nullopt if its vertices are not exactly
  /// coplanar or a hole loop has no interior point.
  std::optional<Plc::Facet> polygon_facet(int f, const PlanarLoops& planar) const {
    const Plc::Polygon& outer = planar.loops.front();
    const Vec3& a = plc_.points[outer[0]];
    const Vec3& b = plc_.points[outer[1]];
    std::size_t third = 2;
    while (third < outer.size() && collinear(a, b, plc_.points[outer[third]])) ++third;
    if (third == outer.size()) return std::nullopt;
    const Vec3& c = plc_.points[outer[third]];
    for (const Plc::Polygon& loop : planar.loops) {
      for (std::uint32_t v : loop) {
        if (predicates::orient3d(a.data(), b.data(), c.data(), plc_.points[v].data()) != Sign::Zero) {
          return std::nullopt;
        }
      }
    }
    Plc::Facet facet;
    facet.marker = face_markers_[f - 1];
    facet.polygons = planar.loops;
    for (std::size_t l = 1; l < planar.loops.size(); ++l) {
      std::vector<Vec3> loop;
      for (std::uint32_t v : planar.loops[l]) loop.push_back(plc_.points[v]);
      const std::optional<Vec3> inside = polygon_interior_point(loop, planar.axis);
      if (!inside) return std::nullopt;
      facet.holes.push_back(*inside);
    }
    return facet;
  }

  bool add_polygon_facet(int f, const PlanarLoops& planar) {
    std::optional<Plc::Facet> facet = polygon_facet(f, planar);
    if (!facet) return false;
    plc_.facets.push_back(std::move(*facet));
    ++report_.planar_polygon_facets;
    return true;
  }

  /// One local triangulation per face (BRepMesh's, with parameter-plane coordinates) and
  /// the edge discretisations, for cancellation and refinement.
  void build_surface_meshes() {
    meshes_.faces.resize(static_cast<std::size_t>(faces_.Extent()));
    for (int f = 1; f <= faces_.Extent(); ++f) {
      const TopoDS_Face& face = TopoDS::Face(faces_(f));
      TopLoc_Location location;
      const Handle(Poly_Triangulation)& triangulation = BRep_Tool::Triangulation(face, location);
      SurfaceMeshes::Face& mesh = meshes_.faces[f - 1];
      for (int i = 1; i <= triangulation->NbNodes(); ++i) {
        mesh.node_vertex.push_back(face_node(f, i, *triangulation, location));
        if (triangulation->HasUVNodes()) {
          const gp_Pnt2d uv = triangulation->UVNode(i);
          mesh.uv.push_back({uv.X(), uv.Y()});
        } else {
          mesh.uv.push_back({0.0, 0.0});
        }
      }
      for (int t = 1; t <= triangulation->NbTriangles(); ++t) {
        int n1 = 0, n2 = 0, n3 = 0;
        triangulation->Triangle(t).Get(n1, n2, n3);
        mesh.triangles.push_back({static_cast<std::uint32_t>(n1 - 1), static_cast<std::uint32_t>(n2 - 1),
                                  static_cast<std::uint32_t>(n3 - 1)});
      }
    }
    meshes_.edges.resize(static_cast<std::size_t>(edges_.Extent()));
    for (int e = 1; e <= edges_.Extent(); ++e) {
      meshes_.edges[e - 1].parameters = edge_nodes_[e].parameters;
      meshes_.edges[e - 1].vertices = edge_nodes_[e].ids;
    }
  }

  /// A place where refinement went wrong: two triangles crossing, a sharp hinge.
  struct Crossing {
    Vec3 center;
    double radius;
  };
  using FacePair = std::pair<std::size_t, std::size_t>;

  /// Smallest 3D angle (degrees) of face f of `meshes` that refinement can change.
  double face_min_angle_deg(const SurfaceMeshes& meshes, std::size_t f) const {
    return smallest_unforced_angle_deg(meshes, f, plc_.points);
  }

  /// Smallest dihedral angle (degrees) between two triangles of face f of `meshes` at an
  /// edge inside the face (180 where the face is flat; small where it folds).
  double face_min_dihedral_deg(const SurfaceMeshes& meshes, std::size_t f, double sharp_below = 0.0,
                               std::vector<Crossing>* sharp = nullptr) const {
    const SurfaceMeshes::Face& mesh = meshes.faces[f];
    std::map<std::pair<std::uint32_t, std::uint32_t>, Vec3> normal_of_side;
    const auto normal = [&](const std::array<std::uint32_t, 3>& tri) {
      const Vec3& a = plc_.points[mesh.node_vertex[tri[0]]];
      const Vec3 n = (plc_.points[mesh.node_vertex[tri[1]]] - a).cross(plc_.points[mesh.node_vertex[tri[2]]] - a);
      return n.norm() > 0.0 ? Vec3(n.normalized()) : Vec3(Vec3::Zero());
    };
    for (const auto& tri : mesh.triangles) {
      for (int k = 0; k < 3; ++k) normal_of_side[{tri[k], tri[(k + 1) % 3]}] = normal(tri);
    }
    double smallest = 180.0;
    for (const auto& [side, n] : normal_of_side) {
      const auto other = normal_of_side.find({side.second, side.first});
      if (other == normal_of_side.end() || n.isZero() || other->second.isZero()) continue;
      const double between = std::atan2(n.cross(other->second).norm(), n.dot(other->second));
      const double dihedral = 180.0 - between * 180.0 / std::numbers::pi;
      smallest = std::min(smallest, dihedral);
      if (sharp && dihedral < sharp_below) {
        const Vec3& a = plc_.points[mesh.node_vertex[side.first]];
        const Vec3& b = plc_.points[mesh.node_vertex[side.second]];
        sharp->push_back({(a + b) / 2.0, (b - a).norm()});
      }
    }
    return smallest;
  }

  /// Pairs of faces (0-based, smaller first) whose triangles in `meshes` meet other than
  /// at shared vertices and edges (exact, validate_plc on the triangles of all faces),
  /// with the places where they do.
  std::map<FacePair, std::vector<Crossing>> intersecting_faces(const SurfaceMeshes& meshes) const {
    Plc triangles;
    triangles.points = plc_.points;
    for (std::size_t f = 0; f < meshes.faces.size(); ++f) {
      const SurfaceMeshes::Face& mesh = meshes.faces[f];
      for (const auto& tri : mesh.triangles) {
        const std::uint32_t a = mesh.node_vertex[tri[0]], b = mesh.node_vertex[tri[1]], c = mesh.node_vertex[tri[2]];
        if (a == b || b == c || c == a || collinear(plc_.points[a], plc_.points[b], plc_.points[c])) continue;
        Plc::Facet facet;
        facet.polygons.push_back({a, b, c});
        facet.marker = static_cast<int>(f);
        triangles.facets.push_back(std::move(facet));
      }
    }
    PlcValidationOptions options;
    options.require_closed = false;
    options.check_points_inside = false;
    options.max_issues = std::numeric_limits<std::size_t>::max();
    std::map<FacePair, std::vector<Crossing>> pairs;
    for (const PlcIssue& issue : validate_plc(triangles, options)) {
      if (issue.kind != PlcIssueKind::Intersection || issue.facets.empty()) continue;
      const auto f = static_cast<std::size_t>(triangles.facets[issue.facets.front()].marker);
      const auto g = static_cast<std::size_t>(triangles.facets[issue.facets.back()].marker);
      std::vector<Vec3> corners;
      for (std::uint32_t t : issue.facets) {
        for (std::uint32_t v : triangles.facets[t].polygons.front()) corners.push_back(plc_.points[v]);
      }
      Vec3 center = Vec3::Zero();
      for (const Vec3& p : corners) center += p / static_cast<double>(corners.size());
      double radius = 0.0;
      for (const Vec3& p : corners) radius = std::max(radius, (p - center).norm());
      pairs[std::minmax(f, g)].push_back({center, radius});
    }
    return pairs;
  }

  /// Flips and circumcentre insertion for bounded angles in each face's parameter plane
  /// (surface_refinement.h), with new nodes on the exact surface, then node moves and
  /// flips that raise the smallest angle further where refinement stopped short
  /// (surface_smoothing.h); the refined edge discretisations replace the shared ones. Refinement is checked in 3D face by face:
  /// a face folded more sharply (a dihedral inside the face below BRepMesh's and
  /// kMinFaceDihedralDeg) or crossing another face where BRepMesh's triangles did not
  /// (exact, validate_plc) first gets a tighter deflection bound around those places
  /// (kTightenings rounds). A face left with a smaller angle than BRepMesh's (below the
  /// bound; angles between CAD segments not counted) is refined again with its smallest
  /// angle guarded (keep_min_angle: no boundary split, its own or a neighbour's, may
  /// lower it). A face still folded, crossing or worse that took a longest-edge
  /// bisection is then refined again without (SurfaceMeshes::Face::bisect). A face with
  /// offsets still folded then is refined on its surface plus its edges' offsets blended
  /// over a reach (offset_blend.h, its inner nodes moved there), and if that folds too on
  /// its own tessellation (BRepMesh's triangles as its surface, tessellation_surface.h);
  /// each time its deflection zones and bisection start again. A face still
  /// folded, crossing or worse after that, or with an interior edge used other than once
  /// each way that BRepMesh's triangles did not already have (BRepMesh
  /// leaves such edges on some periodic faces), is excluded (its
  /// triangles then only take the neighbours' boundary splits, and only where that
  /// keeps its smallest angle). The refinement is run again from BRepMesh's
  /// triangulation after each change, up to kAttempts times.
  void refine_surfaces() {
    std::vector<std::unique_ptr<BRepAdaptor_Surface>> surfaces(static_cast<std::size_t>(faces_.Extent()));
    std::vector<std::unique_ptr<BRepAdaptor_Curve>> curves(static_cast<std::size_t>(edges_.Extent()));
    // Faces refined on their own tessellation instead of their surface (where refinement
    // on the surface folded them; tessellation_surface.h).
    std::vector<std::unique_ptr<TessellationSurface>> tessellations(meshes_.faces.size());
    // Faces refined on their surface plus their edges' offsets blended over a reach
    // (offset_blend.h), where interpolated offsets folded them; their inner nodes moved
    // onto that surface, with the points they had.
    std::vector<std::unique_ptr<OffsetBlend>> blends(meshes_.faces.size());
    std::vector<std::vector<std::pair<std::uint32_t, Vec3>>> unblended(meshes_.faces.size());
    const SurfacePoint surface_point = [&](std::size_t f, const Point2& uv) {
      if (tessellations[f]) return tessellations[f]->point(uv);
      if (!surfaces[f]) {
        surfaces[f] = std::make_unique<BRepAdaptor_Surface>(TopoDS::Face(faces_(static_cast<int>(f) + 1)));
      }
      const Vec3 p = to_vec(surfaces[f]->Value(uv[0], uv[1]));
      return blends[f] ? Vec3(p + blends[f]->offset(p)) : p;
    };
    const SurfaceNormal surface_normal = [&](std::size_t f, const Point2& uv) {
      surface_point(f, uv);  // creates the adaptor
      gp_Pnt p;
      gp_Vec du, dv;
      surfaces[f]->D1(uv[0], uv[1], p, du, dv);
      const gp_Vec n = du.Crossed(dv);
      const double length = n.Magnitude();
      return length > 0.0 ? Vec3(n.X() / length, n.Y() / length, n.Z() / length) : Vec3(Vec3::Zero());
    };
    std::vector<Handle(ShapeAnalysis_Surface)> projectors(static_cast<std::size_t>(faces_.Extent()));
    const SurfaceParameters surface_parameters = [&](std::size_t f, const Vec3& p,
                                                     const Point2& start) -> std::optional<Point2> {
      if (projectors[f].IsNull()) {
        projectors[f] = new ShapeAnalysis_Surface(BRep_Tool::Surface(TopoDS::Face(faces_(static_cast<int>(f) + 1))));
      }
      // Newton from `start` first (NextValueOfUV), the global search only if that fails.
      const gp_Pnt2d uv = projectors[f]->NextValueOfUV(gp_Pnt2d(start[0], start[1]), gp_Pnt(p.x(), p.y(), p.z()),
                                                       Precision::Confusion());
      if (!std::isfinite(uv.X()) || !std::isfinite(uv.Y())) return std::nullopt;
      return Point2{uv.X(), uv.Y()};
    };
    const EdgePoint edge_point = [&](std::size_t e, double t) {
      if (!curves[e]) curves[e] = std::make_unique<BRepAdaptor_Curve>(TopoDS::Edge(edges_(static_cast<int>(e) + 1)));
      return to_vec(curves[e]->Value(t));
    };
    SurfaceRefinementOptions options;
    options.min_angle_deg = parameters_.min_angle_deg;
    options.min_edge_length = parameters_.min_edge_length;
    options.max_deflection = parameters_.linear_deflection;
    options.max_new_points = 2 * plc_.points.size() + 2000;
    set_loose_face_offsets(surface_point);
    SurfaceMeshes unrefined = meshes_;
    const std::size_t unrefined_points = plc_.points.size();
    const std::size_t faces = meshes_.faces.size();
    std::vector<double> before(faces), dihedral_before(faces);
    for (std::size_t f = 0; f < faces; ++f) {
      before[f] = face_min_angle_deg(unrefined, f);
      dihedral_before[f] = face_min_dihedral_deg(unrefined, f);
    }
    const std::map<FacePair, std::vector<Crossing>> crossing_before = intersecting_faces(unrefined);
    // Edges BRepMesh already leaves defective (on some periodic and revolved
    // faces): refinement is not blamed for those.
    std::set<std::pair<std::uint32_t, std::uint32_t>> defective_before;
    faces_with_interior_edge_defects(nullptr, &defective_before);
    std::vector<bool> excluded(faces, false);
    std::vector<std::string> reasons(faces);
    std::vector<bool> guarded(faces, false);  // refined with keep_min_angle
    std::vector<bool> unbisected(faces, false);  // refined without longest-edge bisection
    std::vector<int> tightened(faces, 0);  // deflection zones added to each face so far
    std::vector<std::vector<SurfaceMeshes::Face::DeflectionZone>> zones(faces);
    // A face with offsets (its nodes off its surface: loose CAD tolerances) still folded
    // where it would be excluded is refined once more on its surface plus its edges'
    // offsets blended over a reach (offset_blend.h): its inner nodes move onto that
    // surface, new nodes go there with the (now small) interpolated offsets of their
    // triangles' nodes, the deflection zones and bisection start again. BRepMesh's first
    // row of triangles bridged the offsets wherever it lay (gmsh-t106-blade's face 3: a lip
    // 0.72 units wide 0.01 above the cap, folded with interpolated offsets, 5.9 degrees on
    // its tessellation); blended, they ramp over twice their size.
    const auto refine_on_blend = [&](std::size_t f) {
      SurfaceMeshes::Face& mesh = unrefined.faces[f];
      if (blends[f] || tessellations[f] || mesh.offset.empty()) return false;
      // The face's boundary: sides of one triangle only.
      std::map<std::pair<std::uint32_t, std::uint32_t>, int> sides;
      for (const auto& tri : mesh.triangles) {
        for (int k = 0; k < 3; ++k) ++sides[std::minmax(tri[k], tri[(k + 1) % 3])];
      }
      std::vector<bool> on_boundary(mesh.uv.size(), false);
      // A boundary side's point at fraction s (the chord between its nodes: their edge's
      // curve within BRepMesh's deflection) and the surface point at the parameters
      // interpolated the same way: its offset, largest between the nodes where the surface
      // bulges away from a straight edge (face 3's cap edge, 0.72 units off between nodes
      // 0.02 units off).
      const auto sample = [&](std::uint32_t i, std::uint32_t j, double s) {
        const Point2 uv{mesh.uv[i][0] + s * (mesh.uv[j][0] - mesh.uv[i][0]),
                        mesh.uv[i][1] + s * (mesh.uv[j][1] - mesh.uv[i][1])};
        const Vec3 surface = surface_point(f, uv);
        const Vec3 chord = (1.0 - s) * plc_.points[mesh.node_vertex[i]] + s * plc_.points[mesh.node_vertex[j]];
        return OffsetBlend::Sample{surface, Vec3(chord - surface)};
      };
      double largest = 0.0;
      for (const auto& [side, count] : sides) {
        if (count != 1) continue;
        on_boundary[side.first] = on_boundary[side.second] = true;
        for (int k = 0; k <= kBlendProbes; ++k) {
          const OffsetBlend::Sample probe = sample(side.first, side.second, static_cast<double>(k) / kBlendProbes);
          if (!probe.surface.allFinite() || !probe.offset.allFinite()) return false;
          largest = std::max(largest, probe.offset.norm());
        }
      }
      if (!(largest > 0.0)) return false;
      const double reach = kBlendReach * largest;
      // Samples along each boundary side, kBlendSamplesPerReach per reach, fewer where that
      // would make more than kBlendMaxPieces pieces (each surface point costs one pass over
      // them).
      double wanted = 0.0;
      const auto side_length = [&](const std::pair<std::uint32_t, std::uint32_t>& side) {
        return (plc_.points[mesh.node_vertex[side.first]] - plc_.points[mesh.node_vertex[side.second]]).norm();
      };
      for (const auto& [side, count] : sides) {
        if (count == 1) wanted += side_length(side) * kBlendSamplesPerReach / reach;
      }
      const double density = kBlendSamplesPerReach / reach * std::min(1.0, kBlendMaxPieces / wanted);
      std::vector<OffsetBlend::Piece> pieces;
      for (const auto& [side, count] : sides) {
        if (count != 1) continue;
        const int n = static_cast<int>(std::clamp(std::ceil(side_length(side) * density), 1.0, kBlendMaxPieces));
        OffsetBlend::Sample last = sample(side.first, side.second, 0.0);
        for (int k = 1; k <= n; ++k) {
          const OffsetBlend::Sample next = sample(side.first, side.second, static_cast<double>(k) / n);
          pieces.push_back({last, next});
          last = next;
        }
      }
      blends[f] = std::make_unique<OffsetBlend>(std::move(pieces), reach);
      // Inner nodes move onto the blended surface; boundary nodes are samples, on it already,
      // and a node of a CAD edge (shared with other faces, or on the edge's curve) stays.
      std::set<std::uint32_t> edge_vertices;
      for (const SurfaceMeshes::Edge& edge : unrefined.edges) edge_vertices.insert(edge.vertices.begin(), edge.vertices.end());
      for (std::size_t i = 0; i < mesh.uv.size(); ++i) {
        if (on_boundary[i] || edge_vertices.count(mesh.node_vertex[i]) > 0) continue;
        const Vec3 p = surface_point(f, mesh.uv[i]);
        if (!p.allFinite()) continue;
        unblended[f].push_back({mesh.node_vertex[i], plc_.points[mesh.node_vertex[i]]});
        plc_.points[mesh.node_vertex[i]] = p;
      }
      for (std::size_t i = 0; i < mesh.uv.size(); ++i) {
        mesh.offset[i] = plc_.points[mesh.node_vertex[i]] - surface_point(f, mesh.uv[i]);
        if (!mesh.offset[i].allFinite()) mesh.offset[i] = Vec3::Zero();
      }
      zones[f].clear();
      tightened[f] = 0;
      unbisected[f] = false;
      ++report_.faces_blended;
      return true;
    };
    // The blend undone: the inner nodes back at BRepMesh's points, the offsets as they were.
    const auto unblend = [&](std::size_t f) {
      if (!blends[f]) return;
      SurfaceMeshes::Face& mesh = unrefined.faces[f];
      for (const auto& [vertex, point] : unblended[f]) plc_.points[vertex] = point;
      unblended[f].clear();
      blends[f].reset();
      for (std::size_t i = 0; i < mesh.uv.size(); ++i) {
        mesh.offset[i] = plc_.points[mesh.node_vertex[i]] - surface_point(f, mesh.uv[i]);
        if (!mesh.offset[i].allFinite()) mesh.offset[i] = Vec3::Zero();
      }
    };
    // A face that still folds is refined once more on its tessellation (BRepMesh's
    // triangles as its surface: new nodes on them, offsets zero). Faces whose nodes lie on
    // their surface keep the exclusion: their surface is the better guide (at 26 degrees
    // the tessellation would replace the refinement of gmsh-wing-fuselage's wing tip and
    // occt-screw's torus at the default bound, step_importer.cpp).
    const auto refine_on_tessellation = [&](std::size_t f) {
      SurfaceMeshes::Face& mesh = unrefined.faces[f];
      if (tessellations[f] || mesh.offset.empty()) return false;
      unblend(f);
      std::vector<Vec3> points(mesh.node_vertex.size());
      for (std::size_t i = 0; i < points.size(); ++i) points[i] = plc_.points[mesh.node_vertex[i]];
      auto tessellation = std::make_unique<TessellationSurface>(mesh.uv, points, mesh.triangles);
      if (tessellation->empty()) return false;
      tessellations[f] = std::move(tessellation);
      mesh.offset.assign(mesh.uv.size(), Vec3::Zero());
      // The surface's tighter deflection zones and the refusal of bisection were set for
      // folds on the surface; on the tessellation they start again.
      zones[f].clear();
      tightened[f] = 0;
      unbisected[f] = false;
      ++report_.faces_on_tessellation;
      return true;
    };
    constexpr int kAttempts = 12 + 2 * kTightenings;  // blend and tessellation stages each with their tightenings
    bool accepted = false;
    for (int attempt = 0; attempt < kAttempts && !accepted; ++attempt) {
      meshes_ = unrefined;
      plc_.points.resize(unrefined_points);
      for (std::size_t f = 0; f < faces; ++f) {
        meshes_.faces[f].refine = unrefined.faces[f].refine && !excluded[f];
        meshes_.faces[f].keep_min_angle = unrefined.faces[f].refine && (excluded[f] || guarded[f]);
        meshes_.faces[f].zones = zones[f];
        meshes_.faces[f].bisect = !unbisected[f];
      }
      report_.refinement = refine_surface_meshes(meshes_, plc_.points, options, surface_point, edge_point, surface_normal,
                                                 surface_parameters);
      accepted = true;
      for (std::size_t f : faces_with_interior_edge_defects(&defective_before)) {
        if (excluded[f]) continue;
        excluded[f] = true;
        reasons[f] = "an interior edge used other than once each way (a fold, an overlap or a chord shared with another face)";
        accepted = false;
      }
      if (!accepted) continue;  // rerun before the costlier checks
      for (const auto& [pair, places] : intersecting_faces(meshes_)) {
        const auto [f, g] = pair;
        if (crossing_before.count(pair) > 0) continue;
        // A new crossing: the refined face(s) of the pair get a tighter deflection bound
        // around the crossing (their chords come closer to the surfaces, which do not
        // cross), kTightenings times; then they are excluded. If neither is refined
        // (boundary splits alone made it), exclusion cannot help.
        accepted = false;
        bool changed = false;
        for (std::size_t h : {f, g}) {
          if (!unrefined.faces[h].refine || excluded[h] || tightened[h] >= kTightenings) continue;
          ++tightened[h];
          const double deflection = parameters_.linear_deflection / std::pow(4.0, tightened[h]);
          for (const Crossing& place : places) zones[h].push_back({place.center, 2.0 * place.radius, deflection});
          changed = true;
        }
        if (changed) continue;
        for (std::size_t h : {f, g}) {
          if (unrefined.faces[h].refine && !excluded[h] && !unbisected[h] && meshes_.faces[h].bisected) {
            unbisected[h] = changed = true;
          }
        }
        if (changed) continue;
        for (std::size_t h : {f, g}) {
          if (unrefined.faces[h].refine && !excluded[h]) {
            excluded[h] = changed = true;
            unblend(h);
            reasons[h] = "its triangles cross those of face " + std::to_string(face_markers_[h == f ? g : f]);
          }
        }
        if (!changed) {
          excluded.assign(faces, true);
          for (std::size_t h = 0; h < faces; ++h) unblend(h);
          attempt = kAttempts;
        }
        accepted = false;
      }
      for (std::size_t f = 0; f < faces; ++f) {
        if (!unrefined.faces[f].refine || excluded[f]) continue;
        // A fold (a hinge inside the face sharper than BRepMesh's and kMinFaceDihedralDeg)
        // gets tighter deflection zones first, like a crossing.
        const double sharp_below = std::min(dihedral_before[f], kMinFaceDihedralDeg);
        std::vector<Crossing> sharp;
        const bool folded = face_min_dihedral_deg(meshes_, f, sharp_below, &sharp) < sharp_below;
        const bool worse = face_min_angle_deg(meshes_, f) < std::min(before[f], parameters_.min_angle_deg);
        if (folded && !worse && tightened[f] < kTightenings) {
          ++tightened[f];
          const double deflection = parameters_.linear_deflection / std::pow(4.0, tightened[f]);
          for (const Crossing& place : sharp) zones[f].push_back({place.center, 2.0 * place.radius, deflection});
          accepted = false;
          continue;
        }
        if (worse && !folded && !guarded[f]) {
          // First the face is refined again with its smallest angle guarded against the
          // boundary splits of its own and its neighbours' refinement.
          guarded[f] = true;
          accepted = false;
          continue;
        }
        if ((folded || worse) && !unbisected[f] && meshes_.faces[f].bisected) {
          // Last before exclusion: refined again without longest-edge bisection.
          unbisected[f] = true;
          accepted = false;
          continue;
        }
        if (folded && (refine_on_blend(f) || refine_on_tessellation(f))) {
          accepted = false;
          continue;
        }
        if (folded || worse) {
          excluded[f] = true;
          unblend(f);  // an excluded face keeps BRepMesh's triangles and points
          reasons[f] = folded ? "folded (an inner dihedral below " + std::to_string(sharp_below) + " degrees)"
                              : "smallest angle " + std::to_string(face_min_angle_deg(meshes_, f)) +
                                    " below BRepMesh's " + std::to_string(before[f]);
          accepted = false;
        }
      }
    }
    report_.faces_excluded_from_refinement =
        static_cast<int>(std::count(excluded.begin(), excluded.end(), true));
    for (std::size_t f = 0; f < faces; ++f) {
      if (!unrefined.faces[f].refine) continue;
      ++report_.faces_refined;
      report_.min_unforced_angle_before_deg = std::min(report_.min_unforced_angle_before_deg, before[f]);
    }
    if (!accepted) {
      // Safety net: refinement must never make the surface less of a closed, consistently
      // oriented 2-manifold than BRepMesh left it, nor any face's smallest angle smaller.
      // Keep BRepMesh's tessellation then.
      for (std::size_t f = 0; f < faces; ++f) unblend(f);
      meshes_ = unrefined;
      plc_.points.resize(unrefined_points);
      report_.refinement_reverted = true;
      report_.min_unforced_angle_after_deg = report_.min_unforced_angle_before_deg;
      for (std::size_t f = 0; f < faces; ++f) {
        if (!unrefined.faces[f].refine) continue;
        report_.min_angle_away_from_small_corners_deg =
            std::min(report_.min_angle_away_from_small_corners_deg,
                     smallest_unforced_angle(meshes_, f, plc_.points).away_from_small_corners_deg);
      }
      return;
    }
    smooth_refined_faces(surface_point, surface_normal, defective_before);
    for (std::size_t f = 0; f < faces; ++f) {
      if (!unrefined.faces[f].refine) continue;
      const UnforcedAngle after = smallest_unforced_angle(meshes_, f, plc_.points);
      report_.min_unforced_angle_after_deg = std::min(report_.min_unforced_angle_after_deg, after.angle_deg);
      report_.min_angle_away_from_small_corners_deg =
          std::min(report_.min_angle_away_from_small_corners_deg, after.away_from_small_corners_deg);
      report_.refined_faces.push_back({face_markers_[f], surface_type_name(static_cast<int>(f) + 1), before[f],
                                       after.angle_deg, after.corner_deg, after.away_from_small_corners_deg,
                                       excluded[f], reasons[f]});
    }
    for (int e = 1; e <= edges_.Extent(); ++e) {
      edge_nodes_[e].parameters = meshes_.edges[e - 1].parameters;
      edge_nodes_[e].ids = meshes_.edges[e - 1].vertices;
    }
  }

  /// BRepMesh gives a node on a CAD edge the parameters of the edge's curve on the face
  /// and the point of the edge's 3D curve; where the CAD tolerances are loose the surface
  /// at those parameters lies far from the node (gmsh-t106-blade, sewn at 0.092: up to
  /// 0.99 of the chordal deflection on its extrusion and B-spline faces; under 0.25 of it on
  /// every other corpus model). On a face where some node lies farther than
  /// kLooseNodeDeflections of the deflection (or than kLooseNodeEdgeFraction of the
  /// shortest edge at the node) from the surface at its parameters, every
  /// node keeps that difference as its offset (SurfaceMeshes::Face::offset), and new nodes
  /// follow the offsets interpolated from theirs: placed on the surface itself they made
  /// triangles that fold against their neighbours beside the edges.
  void set_loose_face_offsets(const SurfacePoint& surface_point) {
    for (std::size_t f = 0; f < meshes_.faces.size(); ++f) {
      SurfaceMeshes::Face& mesh = meshes_.faces[f];
      if (!mesh.refine) continue;
      std::vector<Vec3> offset(mesh.uv.size());
      double largest = 0.0;
      for (std::size_t i = 0; i < mesh.uv.size(); ++i) {
        offset[i] = plc_.points[mesh.node_vertex[i]] - surface_point(f, mesh.uv[i]);
        if (!offset[i].allFinite()) offset[i] = Vec3::Zero();
        largest = std::max(largest, offset[i].norm());
      }
      // Or farther than half the shortest edge at some node: nodes at that edge's scale
      // cannot be placed on the surface consistently with it.
      std::vector<double> shortest(mesh.uv.size(), std::numeric_limits<double>::infinity());
      for (const auto& tri : mesh.triangles) {
        for (int k = 0; k < 3; ++k) {
          const double length = (plc_.points[mesh.node_vertex[tri[k]]] - plc_.points[mesh.node_vertex[tri[(k + 1) % 3]]]).norm();
          if (!(length > 0.0)) continue;
          shortest[tri[k]] = std::min(shortest[tri[k]], length);
          shortest[tri[(k + 1) % 3]] = std::min(shortest[tri[(k + 1) % 3]], length);
        }
      }
      bool beyond_edges = false;
      for (std::size_t i = 0; i < mesh.uv.size(); ++i) {
        beyond_edges = beyond_edges || offset[i].norm() > kLooseNodeEdgeFraction * shortest[i];
      }
      if (!(largest > kLooseNodeDeflections * parameters_.linear_deflection) && !beyond_edges) continue;
      mesh.offset = std::move(offset);
      ++report_.faces_with_offsets;
    }
  }

  /// Collapses of crowded inner nodes (surface_coarsening.h), then node moves and flips
  /// (surface_smoothing.h) on the accepted refinement, for the faces still below the bound. Smoothing is undone face by face (each face's triangles, and
  /// the points of its nodes, as refinement left them) where it made the face cross
  /// another face (exact, validate_plc) that it did not cross before, fold more sharply
  /// (a dihedral inside it below the refined face's and kMinFaceDihedralDeg), hold an
  /// interior edge used other than once each way, or lower its smallest angle; every undo
  /// removes a face from the smoothed ones, so this ends.
  void smooth_refined_faces(const SurfacePoint& surface_point, const SurfaceNormal& surface_normal,
                            const std::set<std::pair<std::uint32_t, std::uint32_t>>& defective_before) {
    const SurfaceMeshes refined = meshes_;
    const std::vector<Vec3> refined_points = plc_.points;
    const std::size_t faces = meshes_.faces.size();
    std::vector<double> angle(faces), dihedral(faces);
    for (std::size_t f = 0; f < faces; ++f) {
      if (!meshes_.faces[f].refine) continue;
      angle[f] = face_min_angle_deg(meshes_, f);
      dihedral[f] = face_min_dihedral_deg(meshes_, f);
    }
    std::set<std::pair<std::uint32_t, std::uint32_t>> defective = defective_before;
    faces_with_interior_edge_defects(nullptr, &defective);
    const std::map<FacePair, std::vector<Crossing>> crossing = intersecting_faces(meshes_);
    SurfaceSmoothingOptions options;
    options.min_angle_deg = parameters_.min_angle_deg;
    SurfaceCoarseningOptions coarsening;
    coarsening.min_angle_deg = parameters_.min_angle_deg;
    coarsening.max_deflection = parameters_.linear_deflection;
    report_.smoothing_collapses = coarsen_surface_meshes(meshes_, plc_.points, coarsening, surface_point, surface_normal);
    report_.smoothing = smooth_surface_meshes(meshes_, plc_.points, options, surface_point, surface_normal);
    std::vector<bool> smoothed(faces, false);
    for (std::size_t f = 0; f < faces; ++f) {
      smoothed[f] = meshes_.faces[f].triangles != refined.faces[f].triangles ||
                    std::any_of(meshes_.faces[f].node_vertex.begin(), meshes_.faces[f].node_vertex.end(),
                                [&](std::uint32_t v) { return plc_.points[v] != refined_points[v]; });
    }
    const auto undo = [&](std::size_t f) {
      if (!smoothed[f]) return false;
      meshes_.faces[f] = refined.faces[f];
      for (std::uint32_t v : meshes_.faces[f].node_vertex) plc_.points[v] = refined_points[v];
      smoothed[f] = false;
      return true;
    };
    for (bool changed = true; changed;) {
      changed = false;
      for (std::size_t f : faces_with_interior_edge_defects(&defective)) changed = undo(f) || changed;
      for (std::size_t f = 0; f < faces; ++f) {
        if (!smoothed[f]) continue;
        if (face_min_angle_deg(meshes_, f) < angle[f] ||
            face_min_dihedral_deg(meshes_, f) < std::min(dihedral[f], kMinFaceDihedralDeg)) {
          changed = undo(f) || changed;
        }
      }
      if (changed) continue;
      for (const auto& [pair, places] : intersecting_faces(meshes_)) {
        if (crossing.count(pair) > 0) continue;
        changed = undo(pair.first) || changed;
        changed = undo(pair.second) || changed;
      }
    }
  }

  /// The kind of surface of face f, for the log.
  std::string surface_type_name(int f) const {
    switch (BRepAdaptor_Surface(TopoDS::Face(faces_(f)), Standard_False).GetType()) {
      case GeomAbs_Plane: return "plane";
      case GeomAbs_Cylinder: return "cylinder";
      case GeomAbs_Cone: return "cone";
      case GeomAbs_Sphere: return "sphere";
      case GeomAbs_Torus: return "torus";
      case GeomAbs_BezierSurface: return "Bezier";
      case GeomAbs_BSplineSurface: return "B-spline";
      case GeomAbs_SurfaceOfRevolution: return "surface of revolution";
      case GeomAbs_SurfaceOfExtrusion: return "surface of extrusion";
      case GeomAbs_OffsetSurface: return "offset surface";
      default: return "other surface";
    }
  }

  /// Faces holding an interior edge (on no CAD edge) that is not used exactly once in
  /// each direction by the faces' triangles (with the faces' orientations): a fold, an
  /// overlap, or the same vertex pair joined inside two faces.
  /// Edges in `known` (vertex pairs, smaller first) are not counted; the defective edges
  /// are added to `found`.
  std::set<std::size_t> faces_with_interior_edge_defects(
      const std::set<std::pair<std::uint32_t, std::uint32_t>>* known,
      std::set<std::pair<std::uint32_t, std::uint32_t>>* found = nullptr) const {
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::vector<std::size_t>> sides;
    for (std::size_t f = 0; f < meshes_.faces.size(); ++f) {
      const bool reversed = faces_(static_cast<int>(f) + 1).Orientation() == TopAbs_REVERSED;
      const SurfaceMeshes::Face& mesh = meshes_.faces[f];
      for (const auto& tri : mesh.triangles) {
        const auto& v = mesh.node_vertex;
        // A triangle collapsed at a pole (two copies of the pole's node) is dropped from
        // the PLC: its sides do not count.
        if (v[tri[0]] == v[tri[1]] || v[tri[1]] == v[tri[2]] || v[tri[2]] == v[tri[0]]) continue;
        for (int k = 0; k < 3; ++k) {
          std::uint32_t a = v[tri[k]], b = v[tri[(k + 1) % 3]];
          if (reversed) std::swap(a, b);
          sides[{a, b}].push_back(f);
        }
      }
    }
    std::set<std::pair<std::uint32_t, std::uint32_t>> on_cad_edges;
    for (const SurfaceMeshes::Edge& edge : meshes_.edges) {
      for (std::size_t k = 0; k + 1 < edge.vertices.size(); ++k) {
        on_cad_edges.insert(std::minmax(edge.vertices[k], edge.vertices[k + 1]));
      }
    }
    std::set<std::size_t> defective;
    for (const auto& [side, users] : sides) {
      const auto pair = std::minmax(side.first, side.second);
      if (on_cad_edges.count(pair) > 0 || (known && known->count(pair) > 0)) continue;
      const auto reverse = sides.find({side.second, side.first});
      if (users.size() != 1 || reverse == sides.end() || reverse->second.size() != 1) {
        if (found) found->insert(pair);
        defective.insert(users.begin(), users.end());
        if (reverse != sides.end()) defective.insert(reverse->second.begin(), reverse->second.end());
      }
    }
    return defective;
  }

  /// Faces in coordinate planes that will be written as polygonal facets (vertices
  /// exactly coplanar after snapping) keep their triangulation as is; every other face is
  /// refined, so that a face falling back to triangles has good ones. The test is
  /// repeated on the refined edges when the facets are written.
  void mark_polygon_faces() {
    std::vector<PlanarLoops> planar(static_cast<std::size_t>(faces_.Extent()) + 1);
    for (int f = 1; f <= faces_.Extent(); ++f) planar[f] = planar_loops(f);
    snap_to_coordinate_planes();
    for (int f = 1; f <= faces_.Extent(); ++f) {
      meshes_.faces[f - 1].refine =
          !(planar[f].usable && planar[f].coordinate_plane && polygon_facet(f, planar[f]).has_value());
    }
  }

  /// The final triangles of face f (its refined local mesh) as facets.
  void add_triangle_facets(int f) {
    const bool reversed = faces_(f).Orientation() == TopAbs_REVERSED;
    const bool planar = BRepAdaptor_Surface(TopoDS::Face(faces_(f)), Standard_False).GetType() == GeomAbs_Plane;
    if (planar) ++report_.planar_faces_triangulated;
    const SurfaceMeshes::Face& mesh = meshes_.faces[f - 1];
    for (const auto& tri : mesh.triangles) {
      const std::uint32_t a = mesh.node_vertex[tri[0]];
      std::uint32_t b = mesh.node_vertex[tri[1]];
      std::uint32_t c = mesh.node_vertex[tri[2]];
      if (reversed) std::swap(b, c);
      if (a == b || b == c || c == a || collinear(plc_.points[a], plc_.points[b], plc_.points[c])) {
        ++report_.dropped_degenerate_triangles;
        continue;
      }
      Plc::Facet facet;
      facet.marker = face_markers_[f - 1];
      facet.polygons.push_back({a, b, c});
      plc_.facets.push_back(std::move(facet));
      if (!planar) ++report_.curved_triangles;
    }
  }

  /// Drops points no facet uses (interior nodes of faces written as polygons, nodes of
  /// cancelled triangles) and renumbers.
  void remove_unused_points() {
    std::vector<std::int64_t> renumber(plc_.points.size(), kUnset);
    for (const Plc::Facet& facet : plc_.facets) {
      for (const Plc::Polygon& loop : facet.polygons) {
        for (std::uint32_t v : loop) renumber[v] = 0;
      }
    }
    std::vector<Vec3> kept;
    for (std::size_t v = 0; v < plc_.points.size(); ++v) {
      if (renumber[v] == kUnset) continue;
      renumber[v] = static_cast<std::int64_t>(kept.size());
      kept.push_back(plc_.points[v]);
    }
    plc_.points = std::move(kept);
    for (Plc::Facet& facet : plc_.facets) {
      for (Plc::Polygon& loop : facet.polygons) {
        for (std::uint32_t& v : loop) v = static_cast<std::uint32_t>(renumber[v]);
      }
    }
  }

  /// Removes pairs of triangles on the same three vertices with opposite orientations:
  /// where BRepMesh folds the triangulation of one face over a small neighbouring face,
  /// the two bound no volume and cancel (a zero-thickness fin).
  void cancel_opposite_triangles() {
    struct Entry {
      std::size_t face, triangle;
      std::array<std::uint32_t, 3> oriented;
    };
    std::map<std::array<std::uint32_t, 3>, std::vector<Entry>> by_vertices;
    for (std::size_t f = 0; f < meshes_.faces.size(); ++f) {
      const bool reversed = faces_(static_cast<int>(f) + 1).Orientation() == TopAbs_REVERSED;
      const SurfaceMeshes::Face& mesh = meshes_.faces[f];
      for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
        std::array<std::uint32_t, 3> oriented{mesh.node_vertex[mesh.triangles[t][0]],
                                              mesh.node_vertex[mesh.triangles[t][1]],
                                              mesh.node_vertex[mesh.triangles[t][2]]};
        if (reversed) std::swap(oriented[1], oriented[2]);
        std::array<std::uint32_t, 3> key = oriented;
        std::sort(key.begin(), key.end());
        if (key[0] == key[1] || key[1] == key[2]) continue;
        by_vertices[key].push_back({f, t, oriented});
      }
    }
    std::vector<std::vector<bool>> removed(meshes_.faces.size());
    for (std::size_t f = 0; f < meshes_.faces.size(); ++f) removed[f].assign(meshes_.faces[f].triangles.size(), false);
    for (const auto& [key, entries] : by_vertices) {
      for (std::size_t i = 0; i < entries.size(); ++i) {
        for (std::size_t j = i + 1; j < entries.size(); ++j) {
          const Entry& x = entries[i];
          const Entry& y = entries[j];
          if (removed[x.face][x.triangle] || removed[y.face][y.triangle]) continue;
          if (same_orientation(x.oriented, y.oriented)) continue;
          removed[x.face][x.triangle] = removed[y.face][y.triangle] = true;
          report_.cancelled_fin_triangles += 2;
        }
      }
    }
    for (std::size_t f = 0; f < meshes_.faces.size(); ++f) {
      auto& triangles = meshes_.faces[f].triangles;
      std::size_t kept = 0;
      for (std::size_t t = 0; t < triangles.size(); ++t) {
        if (!removed[f][t]) triangles[kept++] = triangles[t];
      }
      triangles.resize(kept);
    }
  }

  static bool same_orientation(const std::array<std::uint32_t, 3>& a, const std::array<std::uint32_t, 3>& b) {
    for (std::size_t shift = 0; shift < 3; ++shift) {
      if (a[0] == b[shift] && a[1] == b[(shift + 1) % 3] && a[2] == b[(shift + 2) % 3]) return true;
    }
    return false;
  }

  Expected<void> add_regions() {
    int next_solid_id = model_.solid_count;
    for (int s = 1; s <= solids_.Extent(); ++s) {
      const std::optional<Vec3> inside = solid_interior_point(solids_(s));
      if (!inside) {
        return make_error(ErrorCode::DegenerateInput,
                          file_ + ": found no point strictly inside solid " + std::to_string(s) +
                              " (a degenerate or inside-out solid)");
      }
      Plc::Region region;
      region.point = *inside;
      region.id = model_.solid_ids.IsBound(solids_(s)) ? model_.solid_ids.Find(solids_(s)) : ++next_solid_id;
      plc_.regions.push_back(region);
    }
    plc_.region_names = model_.solid_id_names;
    for (const auto& [id, rgb] : model_.solid_id_colors) plc_.region_colors[id] = {rgb[0], rgb[1], rgb[2]};
    return {};
  }

  /// Distance from p to the nearest face of `faces` (infinity for an empty compound).
  static double distance_to(const gp_Pnt& p, const TopoDS_Compound& faces, bool empty) {
    if (empty) return std::numeric_limits<double>::infinity();
    BRepExtrema_DistShapeShape distance(BRepBuilderAPI_MakeVertex(p).Vertex(), faces);
    return distance.IsDone() ? distance.Value() : 0.0;
  }

  /// A point inside the solid whose distance to every planar face is positive and to
  /// every curved face exceeds the chordal deflection, so that it also lies strictly
  /// inside the tessellated boundary. Candidates: from the centroid of a large boundary
  /// triangle (planar faces first), cast a ray inward and take the midpoint of the first
  /// crossing; the candidate with the longest inward chord whose clearance holds wins.
  std::optional<Vec3> solid_interior_point(const TopoDS_Shape& solid) const {
    struct Candidate {
      bool curved;
      double area;
      Vec3 centroid;
      Vec3 inward;  ///< unit
    };
    std::vector<Candidate> candidates;
    BRep_Builder builder;
    TopoDS_Compound planar_faces, curved_faces;
    builder.MakeCompound(planar_faces);
    builder.MakeCompound(curved_faces);
    bool any_planar = false, any_curved = false;
    for (TopExp_Explorer it(solid, TopAbs_FACE); it.More(); it.Next()) {
      const TopoDS_Face& face = TopoDS::Face(it.Current());
      const bool curved = BRepAdaptor_Surface(face, Standard_False).GetType() != GeomAbs_Plane;
      builder.Add(curved ? curved_faces : planar_faces, face);
      (curved ? any_curved : any_planar) = true;
      TopLoc_Location location;
      const Handle(Poly_Triangulation)& triangulation = BRep_Tool::Triangulation(face, location);
      if (triangulation.IsNull()) continue;
      const double side = face.Orientation() == TopAbs_REVERSED ? 1.0 : -1.0;
      for (int t = 1; t <= triangulation->NbTriangles(); ++t) {
        int n1 = 0, n2 = 0, n3 = 0;
        triangulation->Triangle(t).Get(n1, n2, n3);
        const Vec3 p1 = to_vec(triangulation->Node(n1).Transformed(location.Transformation()));
        const Vec3 p2 = to_vec(triangulation->Node(n2).Transformed(location.Transformation()));
        const Vec3 p3 = to_vec(triangulation->Node(n3).Transformed(location.Transformation()));
        const Vec3 normal = (p2 - p1).cross(p3 - p1);
        const double twice_area = normal.norm();
        if (!(twice_area > 0.0)) continue;
        candidates.push_back({curved, twice_area, (p1 + p2 + p3) / 3.0, side * normal / twice_area});
      }
    }
    constexpr std::size_t kTried = 12;
    const std::size_t tried = std::min(kTried, candidates.size());
    std::partial_sort(candidates.begin(), candidates.begin() + static_cast<std::ptrdiff_t>(tried),
                      candidates.end(), [](const Candidate& a, const Candidate& b) {
                        return a.curved != b.curved ? !a.curved : a.area > b.area;
                      });
    const double deflection = parameters_.linear_deflection;
    IntCurvesFace_ShapeIntersector intersector;
    intersector.Load(solid, 1e-3 * deflection);
    // Ray casts first (cheap); the exact clearance (a distance computation, costly on
    // free-form faces) only for the deepest candidates, in order, until one is clear.
    std::vector<std::pair<double, Vec3>> inside;  // (half chord, point)
    for (std::size_t i = 0; i < tried; ++i) {
      const Candidate& candidate = candidates[i];
      const gp_Pnt start(candidate.centroid.x(), candidate.centroid.y(), candidate.centroid.z());
      const gp_Dir direction(candidate.inward.x(), candidate.inward.y(), candidate.inward.z());
      const double skip = candidate.curved ? 2.0 * deflection : 1e-3 * deflection;
      intersector.Perform(gp_Lin(start, direction), skip, Precision::Infinite());
      if (!intersector.IsDone() || intersector.NbPnt() == 0) continue;
      double nearest = Precision::Infinite();
      for (int k = 1; k <= intersector.NbPnt(); ++k) nearest = std::min(nearest, intersector.WParameter(k));
      inside.emplace_back(0.5 * nearest, candidate.centroid + 0.5 * nearest * candidate.inward);
    }
    std::sort(inside.begin(), inside.end(), [](const auto& x, const auto& y) { return x.first > y.first; });
    BRepClass3d_SolidClassifier classifier(solid);
    std::optional<Vec3> best;
    for (const auto& [half_chord, p] : inside) {
      const gp_Pnt point(p.x(), p.y(), p.z());
      classifier.Perform(point, 1e-3 * deflection);
      if (classifier.State() != TopAbs_IN) continue;
      const double clearance = std::min(distance_to(point, planar_faces, !any_planar),
                                        distance_to(point, curved_faces, !any_curved) - deflection);
      if (clearance > 0.0) {
        best = p;
        break;
      }
    }
    return best;
  }

  const CadModel& model_;
  TessellationParameters parameters_;
  const std::string& file_;
  TessellationReport& report_;
  TopTools_IndexedMapOfShape faces_, edges_, vertices_, solids_;
  std::vector<int> face_markers_;  ///< marker (CAD face id) of each face of faces_
  std::vector<std::int64_t> vertex_ids_;
  std::vector<EdgeNodes> edge_nodes_;
  std::vector<std::vector<std::int64_t>> face_node_ids_;
  std::vector<PlaneSnap> snaps_;
  SurfaceMeshes meshes_;
  Plc plc_;
};

}  // namespace

Expected<Plc> tessellate_to_plc(const CadModel& model, const TessellationParameters& parameters,
                                const std::string& file, TessellationReport& report, LogSink* sink) {
  IMeshTools_Parameters mesh;
  mesh.Deflection = parameters.linear_deflection;
  mesh.Angle = parameters.angular_deflection;
  mesh.InParallel = Standard_False;
  mesh.Relative = Standard_False;
  BRepMesh_IncrementalMesh mesher(model.shape, mesh);
  if (!mesher.IsDone()) {
    return make_error(ErrorCode::InvalidInput, file + ": OpenCASCADE could not tessellate the model");
  }
  Expected<Plc> plc = PlcBuilder(model, parameters, file, report).build();
  if (plc && report.cancelled_fin_triangles > 0) {
    log(sink, LogLevel::Warning,
        file + ": " + std::to_string(report.cancelled_fin_triangles) +
            " triangles where the tessellation folds one face over another were removed in "
            "coincident opposite pairs");
  }
  if (plc) {
    for (const TessellationReport::RefinedFace& face : report.refined_faces) {
      if (!face.excluded && face.min_angle_after_deg >= parameters.min_angle_deg) continue;
      log(sink, face.excluded ? LogLevel::Info : LogLevel::Debug,
          file + ": face " + std::to_string(face.marker) + " (" + face.surface + ") smallest angle not between CAD segments " +
              std::to_string(face.min_angle_before_deg) + " -> " + std::to_string(face.min_angle_after_deg) +
              " degrees" + (face.corner_deg < 360.0 ? " beside a corner of " + std::to_string(face.corner_deg) + " degrees" : "") +
              " (" + std::to_string(face.min_angle_away_from_small_corners_deg) + " away from corners under " +
              std::to_string(static_cast<int>(kSmallFaceCornerDeg)) + " degrees)" +
              (face.excluded ? "; excluded from refinement: " + face.reason : ""));
    }
    log(sink, LogLevel::Info,
        file + ": " + std::to_string(report.faces) + " faces -> " +
            std::to_string(report.planar_polygon_facets) + " polygonal facets, " +
            std::to_string(report.curved_triangles) + " curved-face triangles, " +
            std::to_string(report.planar_faces_triangulated) + " planar faces triangulated, " +
            std::to_string(report.dropped_degenerate_triangles) + " degenerate triangles dropped, " +
            std::to_string(report.edge_node_mismatches) + " edge nodes matched approximately, " +
            std::to_string(report.cancelled_fin_triangles) + " folded triangles cancelled; refinement: " +
            std::to_string(report.refinement.flips) + " flips, " +
            std::to_string(report.refinement.interior_splits) + " interior and " +
            std::to_string(report.refinement.boundary_splits) + " edge splits, " +
            std::to_string(report.smoothing_collapses) + " node collapses, " + std::to_string(report.smoothing.moves) +
            " node moves and " + std::to_string(report.smoothing.flips) + " flips smoothing, smallest angle " +
            std::to_string(report.refinement.min_angle_before_deg) + " -> " +
            std::to_string(report.refinement.min_angle_after_deg) + " degrees, " +
            std::to_string(report.faces_refined) + " faces refined (" + std::to_string(report.faces_with_offsets) +
            " with offsets: nodes off their surface, " + std::to_string(report.faces_blended) +
            " with their edges' offsets blended: interpolated offsets folded them, " +
            std::to_string(report.faces_on_tessellation) +
            " on their tessellation: folded on their surface), " +
            std::to_string(report.faces_excluded_from_refinement) +
            " excluded (refining them folded them or lowered their smallest angle), smallest angle "
            "not between CAD segments " + std::to_string(report.min_unforced_angle_before_deg) + " -> " +
            std::to_string(report.min_unforced_angle_after_deg) + " degrees (" +
            std::to_string(report.min_angle_away_from_small_corners_deg) + " away from face corners under " +
            std::to_string(static_cast<int>(kSmallFaceCornerDeg)) + " degrees)" +
            (report.refinement_reverted ? "; reverted: no acceptable refinement" : ""));
  }
  return plc;
}

}  // namespace delmesh::step
