// Uniform grid over axis-aligned boxes: the broad phase of PLC intersection checks.
//
// Items (facet or segment bounding boxes) are bucketed into the cells their boxes overlap;
// the grid resolution is chosen so that there are about as many cells as items. A pair of
// overlapping boxes shares at least one cell and is reported exactly once, from the cell
// that holds the low corner of the boxes' intersection. Cell indices are computed in
// floating point, but only to bucket: every geometric decision is made later by exact
// predicates, and box overlap itself is an exact comparison of coordinates.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "toolkit/geometry/vec3.h"

namespace delmesh {

struct Box3 {
  Vec3 lo = Vec3::Constant(1.0);
  Vec3 hi = Vec3::Constant(-1.0);  ///< lo > hi: empty

  void extend(const Vec3& p) {
    if (lo.x() > hi.x()) {
      lo = hi = p;
      return;
    }
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  bool overlaps(const Box3& o) const {
    return lo.x() <= o.hi.x() && o.lo.x() <= hi.x() && lo.y() <= o.hi.y() &&
           o.lo.y() <= hi.y() && lo.z() <= o.hi.z() && o.lo.z() <= hi.z();
  }
};

class BoxGrid {
 public:
  explicit BoxGrid(std::vector<Box3> boxes);

  std::size_t size() const { return boxes_.size(); }
  const Box3& box(std::size_t i) const { return boxes_[i]; }

  /// Calls f(i, j), i < j, once for every pair of items whose closed boxes overlap.
  template <class F>
  void for_each_overlapping_pair(F&& f) const {
    for (std::size_t cell = 0; cell + 1 < cell_start_.size(); ++cell) {
      const std::uint32_t begin = cell_start_[cell], end = cell_start_[cell + 1];
      for (std::uint32_t x = begin; x < end; ++x) {
        for (std::uint32_t y = x + 1; y < end; ++y) {
          std::uint32_t i = cell_items_[x], j = cell_items_[y];
          if (i > j) std::swap(i, j);
          const Box3& a = boxes_[i];
          const Box3& b = boxes_[j];
          if (!a.overlaps(b)) continue;
          if (cell_of(a.lo.cwiseMax(b.lo)) != cell) continue;
          f(i, j);
        }
      }
    }
  }

  /// Calls f(i) once for every item whose closed box overlaps `query`.
  template <class F>
  void for_each_overlapping(const Box3& query, F&& f) const {
    if (boxes_.empty() || query.lo.x() > query.hi.x()) return;
    const auto lo = cell_coords(query.lo), hi = cell_coords(query.hi);
    for (int z = lo[2]; z <= hi[2]; ++z) {
      for (int y = lo[1]; y <= hi[1]; ++y) {
        for (int x = lo[0]; x <= hi[0]; ++x) {
          const std::size_t cell = index({x, y, z});
          for (std::uint32_t k = cell_start_[cell]; k < cell_start_[cell + 1]; ++k) {
            const std::uint32_t i = cell_items_[k];
            const Box3& b = boxes_[i];
            if (!b.overlaps(query)) continue;
            if (cell_of(b.lo.cwiseMax(query.lo)) != cell) continue;
            f(i);
          }
        }
      }
    }
  }

 private:
  std::array<int, 3> cell_coords(const Vec3& p) const;
  std::size_t index(const std::array<int, 3>& c) const {
    return (static_cast<std::size_t>(c[2]) * res_[1] + c[1]) * res_[0] + c[0];
  }
  std::size_t cell_of(const Vec3& p) const { return index(cell_coords(p)); }

  std::vector<Box3> boxes_;
  Vec3 origin_ = Vec3::Zero();
  Vec3 inv_cell_ = Vec3::Zero();
  std::array<int, 3> res_{1, 1, 1};
  std::vector<std::uint32_t> cell_start_;  ///< CSR offsets, one per cell plus one
  std::vector<std::uint32_t> cell_items_;
};

}  // namespace delmesh
