// Merging of coordinate-plane values within a tolerance (see coordinate_planes.h).
#include "importers/step/coordinate_planes.h"

#include <algorithm>
#include <map>

namespace delmesh::step {

int merge_coordinate_plane_values(std::vector<PlaneSnap>& snaps, double tolerance) {
  if (!(tolerance > 0.0)) return 0;
  int replaced = 0;
  for (int axis = 0; axis < 3; ++axis) {
    std::map<double, int> counts;  // value -> number of snaps, in increasing order
    for (const PlaneSnap& snap : snaps) {
      if (snap.axis == axis) ++counts[snap.value];
    }
    std::map<double, double> target;  // value -> its group's value
    for (auto first = counts.begin(); first != counts.end();) {
      auto best = first;
      auto end = first;
      while (end != counts.end() && end->first - first->first <= tolerance) {
        if (end->second > best->second) best = end;
        ++end;
      }
      for (auto it = first; it != end; ++it) {
        target[it->first] = best->first;
        if (it != best) ++replaced;
      }
      first = end;
    }
    for (PlaneSnap& snap : snaps) {
      if (snap.axis == axis) snap.value = target[snap.value];
    }
  }
  return replaced;
}

}  // namespace delmesh::step
