// Coordinate planes of a CAD model that are one plane up to rounding. A planar face lying
// in a coordinate plane (x, y or z constant) becomes a polygonal facet once its vertices
// are snapped exactly onto that plane's coordinate (cad_to_plc.cpp); the parts of an
// assembly each carry their own placement, so the same plane can reach the importer as
// several values a few units in the last place apart (46.718433566482929 and
// 46.718433566482965 in one SolidWorks assembly). A vertex asked to snap to two of them is
// left where it is and its faces fall back to triangles. Merging the values of each axis
// that lie within a tolerance (an option relative to the model size) into one lets those
// faces stay polygons. No OCCT here.
#pragma once

#include <cstdint>
#include <vector>

namespace delmesh::step {

/// A request to move `vertex` onto the plane where coordinate `axis` (0, 1, 2) equals `value`.
struct PlaneSnap {
  std::uint32_t vertex = 0;
  int axis = 0;
  double value = 0.0;
};

/// Groups the plane values of each axis: sorted, a value joins the group of the smallest
/// value not more than `tolerance` below it (so a group spans at most `tolerance`), and
/// every snap of a group takes the group's value with the most snaps (the smallest on a
/// tie). Returns the number of distinct values replaced (0: nothing changed; also when
/// `tolerance` <= 0).
int merge_coordinate_plane_values(std::vector<PlaneSnap>& snaps, double tolerance);

}  // namespace delmesh::step
