// Passes and tries of the improvement pass (see improvement_schedule.h).
#include "refiners/tet3d/improvement_schedule.h"

#include <algorithm>

namespace delmesh::tet3d {

ImprovementSchedule::ImprovementSchedule(std::size_t bad_before, int max_passes, std::size_t tries_per_bad_tet)
    : budget_(tries_per_bad_tet * bad_before), max_passes_(max_passes) {}

bool ImprovementSchedule::another_pass(int passes, std::size_t bad_at_start, std::size_t bad_now,
                                       bool changed) const {
  if (!changed || bad_now == 0 || passes >= max_passes_) return false;
  // Removed at least kMinPassGain of the pass's starting count (a pass may also add bad
  // tets: smoothing trades them within a star).
  const double removed = static_cast<double>(bad_at_start) - static_cast<double>(bad_now);
  return removed >= kMinPassGain * static_cast<double>(bad_at_start);
}

bool ImprovementSchedule::take(ImprovementStep step) {
  std::size_t& taken = taken_[static_cast<int>(step)];
  if (taken >= budget_) return false;
  ++taken;
  return true;
}

bool ImprovementSchedule::insertion_tried(std::array<std::uint32_t, 4> vertices) const {
  std::sort(vertices.begin(), vertices.end());
  return insertions_.count(vertices) > 0;
}

void ImprovementSchedule::record_insertion(std::array<std::uint32_t, 4> vertices) {
  std::sort(vertices.begin(), vertices.end());
  insertions_.insert(vertices);
}

}  // namespace delmesh::tet3d
