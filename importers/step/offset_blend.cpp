// Offsets of a loose face's edges blended into the face over a reach (offset_blend.h).
#include "importers/step/offset_blend.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace delmesh::step {

OffsetBlend::OffsetBlend(std::vector<Piece> pieces, double reach) : pieces_(std::move(pieces)), reach_(reach) {}

Vec3 OffsetBlend::offset(const Vec3& surface) const {
  double nearest = std::numeric_limits<double>::infinity();
  Vec3 weighted = Vec3::Zero();
  double weights = 0.0;
  for (const Piece& piece : pieces_) {
    const Vec3 along = piece[1].surface - piece[0].surface;
    const double length2 = along.squaredNorm();
    const double t = length2 > 0.0 ? std::clamp((surface - piece[0].surface).dot(along) / length2, 0.0, 1.0) : 0.0;
    const Vec3 offset = (1.0 - t) * piece[0].offset + t * piece[1].offset;
    const double d2 = (surface - (piece[0].surface + t * along)).squaredNorm();
    if (!(d2 > 0.0)) return offset;
    nearest = std::min(nearest, d2);
    weighted += offset / d2;
    weights += 1.0 / d2;
  }
  const double distance = std::sqrt(nearest);
  if (!(distance < reach_) || !(weights > 0.0)) return Vec3::Zero();
  const double fade = 1.0 - distance / reach_;
  return weighted / weights * (fade * fade);
}

}  // namespace delmesh::step
