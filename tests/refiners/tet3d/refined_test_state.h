// The refined state the improvement-pass tests start from: a TestPlc's boundary
// recovered, its domain marked and its quality refined, as mesh_plc leaves the state
// before the improvement pass (refiners/tet3d/sliver_improvement.h).
#pragma once

#include <gtest/gtest.h>

#include "refiners/tet3d/boundary_recovery.h"
#include "refiners/tet3d/domain_marking.h"
#include "refiners/tet3d/plc_preparation.h"
#include "refiners/tet3d/quality_refinement.h"
#include "refiners/tet3d/sliver_improvement.h"
#include "test_plcs.h"

namespace delmesh::test {

/// Refines `state` (made from `input`) up to the improvement pass; fails the test with
/// the input's name where a stage fails.
inline void refine_for_improvement(tet3d::RefineState& state, const TestPlc& input) {
  using namespace delmesh::tet3d;
  ASSERT_TRUE(prepare_plc(state).has_value()) << input.name;
  ASSERT_TRUE(restore_conformity(state, true).has_value()) << input.name;
  for (const auto& [key, facet] : state.subfaces) state.subface_queue.push_back({key});
  ASSERT_TRUE(restore_conformity(state, false).has_value()) << input.name;
  mark_domain(state);
  init_sliver_budget(state);
  ASSERT_TRUE(refine_quality(state, input.plc.points.size()).has_value()) << input.name;
  mark_domain(state);
}

}  // namespace delmesh::test
