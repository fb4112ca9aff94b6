// Change tracking for the improvement pass (see change_clock.h).
#include "refiners/tet3d/change_clock.h"

namespace delmesh::tet3d {

void ChangeClock::mark(std::span<const std::uint32_t> vertices) {
  ++now_;
  for (const std::uint32_t x : vertices) {
    if (x >= changed_.size()) changed_.resize(std::size_t{x} + 1, 0);
    changed_[x] = now_;
  }
}

void ChangeClock::made(const TetMesh& mesh, std::span<const std::uint32_t> made) {
  for (const std::uint32_t t : made) mark(mesh.tet(t).v);
}

void ChangeClock::moved(const TetMesh& mesh, std::span<const std::uint32_t> star) {
  for (const std::uint32_t t : star) mark(mesh.tet(t).v);
}

bool ChangeClock::unchanged_since(std::span<const std::uint32_t> vertices, std::uint64_t since) const {
  if (since == 0) return false;
  for (const std::uint32_t x : vertices)
    if (x >= changed_.size() || changed_[x] > since) return false;
  return true;
}

}  // namespace delmesh::tet3d
