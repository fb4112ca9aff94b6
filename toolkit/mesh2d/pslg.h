// Planar straight line graph (PSLG): the input of 2D triangulation and refinement
// (notes §2.1.2). Plain data, as read from Triangle's .poly/.node files or built by a
// library user; ids are 0-based indices into the vectors.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace delmesh {

using Point2 = std::array<double, 2>;

struct Pslg {
  struct Region {
    Point2 point{};          ///< a point inside the region (flood-fill seed)
    double attribute = 0.0;  ///< regional attribute copied to its triangles (Triangle -A)
    double max_area = -1.0;  ///< area bound for the region's triangles (Triangle -a); <= 0: none
  };

  std::vector<Point2> points;
  std::vector<int> point_markers;             ///< empty or one per point
  int num_point_attributes = 0;
  std::vector<double> point_attributes;       ///< points.size() * num_point_attributes values
  std::vector<std::array<std::uint32_t, 2>> segments;
  std::vector<int> segment_markers;           ///< empty or one per segment
  std::vector<Point2> holes;                  ///< seeds of triangle-free regions
  std::vector<Region> regions;
};

}  // namespace delmesh
