// Piecewise linear complex (PLC): the input of 3D Delaunay refinement (notes §2.1.4,
// §4.1). Plain data built by the importers (STEP, surface meshes, TetGen .poly/.smesh)
// or by a library user; ids are 0-based indices into the vectors.
//
// A facet is a planar polygon with holes, given as TetGen does: a list of polygons in
// one plane (the first is usually the outer boundary; further loops bound holes or are
// internal constraints; a 2-vertex polygon is a segment lying in the facet and a 1-vertex
// polygon a point in it), plus hole points in the facet's plane that mark the holes.
// Every edge of a facet polygon is a segment of the PLC; `segments` lists extra ones.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "toolkit/geometry/vec3.h"

namespace delmesh {

struct Plc {
  using Polygon = std::vector<std::uint32_t>;

  struct Facet {
    std::vector<Polygon> polygons;
    std::vector<Vec3> holes;  ///< points in the facet plane inside its hole loops
    int marker = 0;           ///< boundary tag (CAD face id, .poly marker)
  };

  struct Segment {
    std::uint32_t a = 0, b = 0;
    int marker = 0;
  };

  /// A colour with sRGB components in [0, 1] (CAD face and solid colours).
  struct Color {
    double r = 0.0, g = 0.0, b = 0.0;
  };

  struct Region {
    Vec3 point = Vec3::Zero();  ///< a point strictly inside the region
    int id = 0;                 ///< region number written to each tet (CAD solid id, .poly attribute)
    double max_volume = -1.0;   ///< volume bound for its tets; <= 0: none
  };

  std::vector<Vec3> points;
  std::vector<int> point_markers;  ///< empty or one per point
  std::vector<Facet> facets;
  std::vector<Segment> segments;   ///< segments not already edges of facet polygons
  std::vector<Vec3> holes;         ///< points inside volume holes (tets removed there)
  std::vector<Region> regions;
  std::map<int, std::string> facet_marker_names;  ///< e.g. CAD face names
  std::map<int, std::string> region_names;        ///< e.g. STEP product / solid names
  std::map<int, Color> facet_marker_colors;       ///< e.g. CAD face colours (STEP XDE)
  std::map<int, Color> region_colors;             ///< e.g. CAD solid colours (STEP XDE)
};

}  // namespace delmesh
