// A copy of what the polish of the improvement pass changes in a refinement state (the
// tetrahedralization, the facet triangulations, the boundary tables, the per-vertex and
// per-tet records, the queues and the stage's counters), to undo a trial operation whose
// result is judged after it is made (deferred_split.h; notes §2.2.4 and the end of §4.4,
// where an improvement operation is kept only if the mesh it leaves is better).
//
// restore puts every copied part back as it was, so a run that undoes a trial goes on
// exactly as if it had not been made (the same mesh, byte for byte). The input (plc,
// options), the tables fixed before refinement (segment wedges, narrow partners, region
// volume bounds, facet markers) and the scratch buffers are not copied: the polish's
// operations do not change them.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "refiners/tet3d/refine_state.h"

namespace delmesh::tet3d {

class StateSnapshot {
 public:
  explicit StateSnapshot(const RefineState& state);
  /// Puts the copied parts back into `state`, the state the snapshot was taken of.
  void restore(RefineState& state) const;
  /// The copied tetrahedralization, vertex records and tet regions (what a trial's result
  /// is compared with, deferred_split.cpp).
  const TetMesh& mesh() const { return mesh_; }
  const MappedArray<VertexInfo>& vertices() const { return vertices_; }
  const MappedArray<int>& tet_region() const { return tet_region_; }

 private:
  TetMesh mesh_;
  Cavity cavity_;
  std::uint64_t cavity_serial_;
  CavityElements cavity_elements_;
  MappedArray<VertexInfo> vertices_;
  std::vector<SegmentData> segments_;
  SubsegmentTable subsegments_;
  FacetMeshPool::Saved facet_pool_;
  std::vector<FacetTriangulation> facets_;
  SubfaceTable subfaces_;
  MappedArray<int> tet_region_;
  std::vector<SubsegmentTask> subsegment_queue_;
  std::vector<SubfaceTask> subface_queue_;
  std::vector<std::uint32_t> new_tets_;
  std::size_t sliver_splits_left_;
  std::size_t stage_steiner_;
  SegmentSplitStats stage_segment_splits_;
  std::size_t cavity_shrinks_, cavity_rejections_;
};

}  // namespace delmesh::tet3d
