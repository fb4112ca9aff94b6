// Change tracking for the improvement pass (sliver_improvement.h; notes §2.2.4): which
// vertices' surroundings changed since a step failed there, so that a step which would
// fail again on the same tets is not retried pass after pass.
//
// The mesh changes in two ways during improvement: tets are made (flips, vertex
// insertion, vertex deletion; each made tet replaces tets whose vertices are among its
// own, or the deleted vertex) and vertices move (smoothing). ChangeClock counts the
// changes and marks, per change, the vertices of the made tets (and a vertex deleted by
// the change), or the vertices of the moved vertex's star. Then, for every vertex x not marked since clock value s, the star
// of x (its tets, their vertices and those vertices' coordinates) is what it was at s:
// a tet made around x has x, and a vertex moved in x's star has x in its own star.
// FailureRecords keeps, per tet slot or vertex, the clock of a step's last failure there,
// in a hash map: steps are tried at the bad tets and their neighbours only, a small part
// of the mesh, so a dense array per tet slot (8 bytes, grown to twice the slots) would
// cost more memory than the records.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <unordered_map>
#include <vector>

#include "toolkit/tetmesh/tet_mesh.h"

namespace delmesh::tet3d {

class ChangeClock {
 public:
  /// A clock for a mesh of `vertices` vertices, none of them changed yet.
  explicit ChangeClock(std::size_t vertices = 0) : changed_(vertices, 0) {}

  /// One change: tets were made with these vertices (a vertex id beyond the known ones,
  /// a vertex just inserted, extends the clock).
  void mark(std::span<const std::uint32_t> vertices);
  /// Tets `made` were made in `mesh`: marks their vertices.
  void made(const TetMesh& mesh, std::span<const std::uint32_t> made);
  /// A vertex moved; `star` holds its tets: marks their vertices.
  void moved(const TetMesh& mesh, std::span<const std::uint32_t> star);

  /// The clock now: the value to record for a failure seen now (never 0).
  std::uint64_t now() const { return now_; }
  /// Has none of `vertices` been marked after clock value `since`? False for since = 0
  /// (nothing recorded) and for vertices the clock does not know.
  bool unchanged_since(std::span<const std::uint32_t> vertices, std::uint64_t since) const;

 private:
  std::uint64_t now_ = 1;
  std::vector<std::uint64_t> changed_;  ///< per vertex: the clock of its last change
};

/// The clock of the last failure of one step per id (tet slot or vertex); 0 for none.
class FailureRecords {
 public:
  void record(std::uint32_t id, const ChangeClock& clock) { at_[id] = clock.now(); }
  std::uint64_t at(std::uint32_t id) const {
    const auto it = at_.find(id);
    return it == at_.end() ? 0 : it->second;
  }
  /// Did the step fail at `id` with none of `vertices` changed since?
  bool still_fails(std::uint32_t id, std::span<const std::uint32_t> vertices, const ChangeClock& clock) const {
    return clock.unchanged_since(vertices, at(id));
  }

 private:
  std::unordered_map<std::uint32_t, std::uint64_t> at_;
};

}  // namespace delmesh::tet3d
