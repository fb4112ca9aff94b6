// A copy of what the polish changes in a refinement state, to undo a trial (see
// state_snapshot.h; notes §2.2.4).
#include "refiners/tet3d/state_snapshot.h"

#include <algorithm>

#include "toolkit/core/error.h"

namespace delmesh::tet3d {

StateSnapshot::StateSnapshot(const RefineState& state)
    : mesh_(state.mesh),
      cavity_(state.cavity),
      cavity_serial_(state.cavity_serial),
      cavity_elements_(state.cavity_elements),
      vertices_(state.vertices),
      segments_(state.segments),
      subsegments_(state.subsegments),
      facet_pool_(state.facet_pool->save()),
      facets_(state.facets),
      subfaces_(state.subfaces),
      tet_region_(state.tet_region),
      subsegment_queue_(state.subsegment_queue),
      subface_queue_(state.subface_queue),
      new_tets_(state.new_tets),
      sliver_splits_left_(state.sliver_splits_left),
      stage_steiner_(state.stage_steiner),
      stage_segment_splits_(state.stage_segment_splits),
      cavity_shrinks_(state.cavity_shrinks),
      cavity_rejections_(state.cavity_rejections) {}

void StateSnapshot::restore(RefineState& state) const {
  DELMESH_CHECK(state.facets.size() == facets_.size(), "state snapshot: the facets changed in number");
  // Assigned in place: the facet pool keeps a reference to the mesh's coordinate array.
  state.mesh = mesh_;
  state.cavity = cavity_;
  state.cavity_serial = cavity_serial_;
  state.cavity_elements = cavity_elements_;
  state.vertices = vertices_;
  state.segments = segments_;
  state.subsegments = subsegments_;
  state.facet_pool->restore(facet_pool_);
  // Element by element: the records stay where they are (the array never grows after
  // preparation, and callers may hold references into it).
  std::copy(facets_.begin(), facets_.end(), state.facets.begin());
  state.subfaces = subfaces_;
  state.tet_region = tet_region_;
  state.subsegment_queue = subsegment_queue_;
  state.subface_queue = subface_queue_;
  state.new_tets = new_tets_;
  state.sliver_splits_left = sliver_splits_left_;
  state.stage_steiner = stage_steiner_;
  state.stage_segment_splits = stage_segment_splits_;
  state.cavity_shrinks = cavity_shrinks_;
  state.cavity_rejections = cavity_rejections_;
}

}  // namespace delmesh::tet3d
