// The tessellation of a CAD face as its own surface (tessellation_surface.h).
#include "importers/step/tessellation_surface.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace delmesh::step {

TessellationSurface::TessellationSurface(const std::vector<Point2>& uv, const std::vector<Vec3>& points,
                                         const std::vector<std::array<std::uint32_t, 3>>& triangles) {
  low_ = {std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
  high_ = {-std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()};
  for (const auto& tri : triangles) {
    Triangle t;
    for (int k = 0; k < 3; ++k) {
      t.uv[k] = uv[tri[k]];
      t.points[k] = points[tri[k]];
    }
    const double area = (t.uv[1][0] - t.uv[0][0]) * (t.uv[2][1] - t.uv[0][1]) -
                        (t.uv[1][1] - t.uv[0][1]) * (t.uv[2][0] - t.uv[0][0]);
    if (!(std::abs(area) > 0.0)) continue;
    for (const Point2& p : t.uv) {
      for (int a = 0; a < 2; ++a) {
        low_[a] = std::min(low_[a], p[a]);
        high_[a] = std::max(high_[a], p[a]);
      }
    }
    triangles_.push_back(t);
  }
  if (triangles_.empty()) return;
  // About one triangle per cell, in a grid shaped like the parameter box.
  const double width = std::max(high_[0] - low_[0], 0.0), height = std::max(high_[1] - low_[1], 0.0);
  const double n = static_cast<double>(triangles_.size());
  if (width > 0.0 && height > 0.0) {
    columns_ = static_cast<std::size_t>(std::clamp(std::sqrt(n * width / height), 1.0, n));
    rows_ = static_cast<std::size_t>(std::clamp(n / static_cast<double>(columns_), 1.0, n));
  }
  cells_.assign(columns_ * rows_, {});
  for (std::size_t t = 0; t < triangles_.size(); ++t) {
    Point2 lo = triangles_[t].uv[0], hi = triangles_[t].uv[0];
    for (const Point2& p : triangles_[t].uv) {
      for (int a = 0; a < 2; ++a) {
        lo[a] = std::min(lo[a], p[a]);
        hi[a] = std::max(hi[a], p[a]);
      }
    }
    const std::size_t first = cell_of(lo), last = cell_of(hi);
    for (std::size_t r = first / columns_; r <= last / columns_; ++r) {
      for (std::size_t c = first % columns_; c <= last % columns_; ++c) {
        cells_[r * columns_ + c].push_back(static_cast<std::uint32_t>(t));
      }
    }
  }
}

std::size_t TessellationSurface::cell_of(const Point2& uv) const {
  const auto index = [](double x, double lo, double hi, std::size_t count) -> std::size_t {
    if (!(hi > lo)) return 0;
    const double s = (x - lo) / (hi - lo) * static_cast<double>(count);
    if (!(s > 0.0)) return 0;
    return std::min(static_cast<std::size_t>(s), count - 1);
  };
  return index(uv[1], low_[1], high_[1], rows_) * columns_ + index(uv[0], low_[0], high_[0], columns_);
}

std::array<double, 3> TessellationSurface::barycentric(std::size_t t, const Point2& uv) const {
  const auto& p = triangles_[t].uv;
  const double det = (p[1][0] - p[0][0]) * (p[2][1] - p[0][1]) - (p[1][1] - p[0][1]) * (p[2][0] - p[0][0]);
  const double wb = ((uv[0] - p[0][0]) * (p[2][1] - p[0][1]) - (uv[1] - p[0][1]) * (p[2][0] - p[0][0])) / det;
  const double wc = ((p[1][0] - p[0][0]) * (uv[1] - p[0][1]) - (p[1][1] - p[0][1]) * (uv[0] - p[0][0])) / det;
  return {1.0 - wb - wc, wb, wc};
}

Vec3 TessellationSurface::point(const Point2& uv) const {
  if (triangles_.empty()) return Vec3::Zero();
  const auto best_of = [&](const std::vector<std::uint32_t>& candidates, std::size_t& best, double& best_min) {
    for (std::uint32_t t : candidates) {
      const std::array<double, 3> w = barycentric(t, uv);
      const double smallest = std::min({w[0], w[1], w[2]});
      if (smallest > best_min) {
        best_min = smallest;
        best = t;
      }
    }
  };
  std::size_t best = 0;
  double best_min = -std::numeric_limits<double>::infinity();
  best_of(cells_[cell_of(uv)], best, best_min);
  if (!(best_min >= 0.0)) {
    // Not inside a triangle of its cell: outside the face, or across a cell edge that a
    // triangle's box missed by rounding. Every triangle is asked.
    std::vector<std::uint32_t> all(triangles_.size());
    for (std::size_t t = 0; t < all.size(); ++t) all[t] = static_cast<std::uint32_t>(t);
    best_of(all, best, best_min);
  }
  const std::array<double, 3> w = barycentric(best, uv);
  const Triangle& t = triangles_[best];
  return w[0] * t.points[0] + w[1] * t.points[1] + w[2] * t.points[2];
}

}  // namespace delmesh::step
