// Uniform bucketing grid over boxes (see box_grid.h).
#include "toolkit/plc/box_grid.h"

#include <algorithm>
#include <cmath>

namespace delmesh {

BoxGrid::BoxGrid(std::vector<Box3> boxes) : boxes_(std::move(boxes)) {
  Box3 all;
  for (const Box3& b : boxes_) {
    if (b.lo.x() > b.hi.x()) continue;
    all.extend(b.lo);
    all.extend(b.hi);
  }
  const std::size_t n = std::max<std::size_t>(boxes_.size(), 1);
  if (all.lo.x() <= all.hi.x()) {
    origin_ = all.lo;
    const Vec3 extent = all.hi - all.lo;
    double volume = 1.0;
    int dims = 0;
    for (int k = 0; k < 3; ++k) {
      if (extent[k] > 0 && std::isfinite(extent[k])) {
        volume *= extent[k];
        ++dims;
      }
    }
    if (dims > 0) {
      const double cell = std::pow(volume / static_cast<double>(n), 1.0 / dims);
      for (int k = 0; k < 3; ++k) {
        if (!(extent[k] > 0) || !std::isfinite(extent[k]) || !(cell > 0)) continue;
        const double r = std::clamp(std::ceil(extent[k] / cell), 1.0, 512.0);
        res_[k] = static_cast<int>(r);
        inv_cell_[k] = r / extent[k];
      }
    }
  }
  const std::size_t cells = static_cast<std::size_t>(res_[0]) * res_[1] * res_[2];
  cell_start_.assign(cells + 1, 0);
  auto for_cells = [&](const Box3& b, auto&& f) {
    const auto lo = cell_coords(b.lo), hi = cell_coords(b.hi);
    for (int z = lo[2]; z <= hi[2]; ++z)
      for (int y = lo[1]; y <= hi[1]; ++y)
        for (int x = lo[0]; x <= hi[0]; ++x) f(index({x, y, z}));
  };
  for (const Box3& b : boxes_) {
    if (b.lo.x() > b.hi.x()) continue;
    for_cells(b, [&](std::size_t c) { ++cell_start_[c + 1]; });
  }
  for (std::size_t c = 0; c < cells; ++c) cell_start_[c + 1] += cell_start_[c];
  cell_items_.resize(cell_start_[cells]);
  std::vector<std::uint32_t> fill(cell_start_.begin(), cell_start_.end() - 1);
  for (std::size_t i = 0; i < boxes_.size(); ++i) {
    if (boxes_[i].lo.x() > boxes_[i].hi.x()) continue;
    for_cells(boxes_[i], [&](std::size_t c) { cell_items_[fill[c]++] = static_cast<std::uint32_t>(i); });
  }
}

std::array<int, 3> BoxGrid::cell_coords(const Vec3& p) const {
  std::array<int, 3> c{0, 0, 0};
  for (int k = 0; k < 3; ++k) {
    const double t = (p[k] - origin_[k]) * inv_cell_[k];
    if (t > 0) c[k] = static_cast<int>(std::min(t, static_cast<double>(res_[k] - 1)));
  }
  return c;
}

}  // namespace delmesh
