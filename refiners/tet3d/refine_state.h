// The shared state of 3D Delaunay refinement (notes §4.2.1): the Delaunay
// tetrahedralization of every vertex so far (toolkit/tetmesh), the subsegments of the
// input segments, one constrained Delaunay triangulation per facet in OpenMesh
// (toolkit/facet) whose triangles are the subfacets, per-vertex bookkeeping for the
// termination rule (quality_refinement.h), per-tet regions and the work queues.
//
// The tetrahedralization stays a true (symbolically perturbed) Delaunay
// tetrahedralization throughout, as in the notes: vertices are inserted by Bowyer–Watson
// without constraints, so a subsegment or subfacet can go missing when a vertex lands in
// its diametral or equatorial sphere. Such an element is encroached by definition and is
// put on its queue; it is split before any tet is considered again. Every insertion
// scans the edges and faces of its cavity for subsegments and subfacets, so the queues
// always hold every element that may be missing or encroached. After CCDT facet recovery
// (ccdt_facet_recovery.h) the mesh is only a conforming CDT and the quality stage inserts
// with constrained cavities instead (RefineState::constrained).
#pragma once

#include <array>
#include <cstdint>
#include <limits>
#include <memory>
#include <unordered_map>
#include <vector>

#include "refiners/tet3d/boundary_table.h"
#include "refiners/tet3d/mesh_plc.h"
#include "refiners/tet3d/segment_facet_list.h"
#include "toolkit/core/holding_log_sink.h"
#include "toolkit/facet/facet_triangulation.h"
#include "toolkit/mesh3d/tetra_mesh.h"
#include "toolkit/tetmesh/tet_insert.h"
#include "toolkit/tetmesh/tet_mesh.h"

namespace delmesh::tet3d {

/// Region values of tets that are not in a region of the domain.
inline constexpr int kRegionUnknown = -2147483647;  ///< before domain marking
inline constexpr int kRegionExterior = -2147483646;
inline constexpr int kRegionHole = -2147483645;
inline bool in_domain(int region) { return region > kRegionHole; }

enum class VertexKind : std::uint8_t { Input, OnSegment, OnFacet, Interior, Unused };

/// Fields ordered widest first: 24 bytes per vertex instead of 32.
struct VertexInfo {
  /// Termination floor of boundary recovery (quality_refinement.h): no vertex created on
  /// this vertex's behalf may have an insertion radius below it.
  double floor = 0.0;
  /// Termination floor of the quality stage: the Lipschitz field of termination_floor.h.
  double field_floor = 0.0;
  /// Segment id (OnSegment) or facet id (OnFacet).
  std::uint32_t owner = kNone;
  VertexKind kind = VertexKind::Input;
  /// Input vertex where PLC features meet below the §4.2.3 angles.
  bool small_angle = false;
};
static_assert(sizeof(VertexInfo) == 24);

/// Fields ordered widest first, the lists that few segments have (wedges, narrow
/// partners) kept in RefineState by segment id, and the facet list inline: 56 bytes per
/// segment and no allocation of its own, instead of 120 bytes and one allocation
/// (surfaces have one segment per input triangle edge: 113112 on cgal-bunny00, whose
/// strongly Delaunay mesh has 4.6 tets per segment).
struct SegmentData {
  SegmentFacetList facets;  ///< facets having the segment on their boundary
  /// Sine of the smallest angle below the §4.2.3 limits that the segment makes at its end
  /// a (b) with another segment or a facet; 0 when it makes none (small_angles.h, rule
  /// (d)).
  double sine_at_a = 0.0, sine_at_b = 0.0;
  std::uint32_t a = 0, b = 0;  ///< endpoint vertex ids (tet mesh ids)
  int marker = 0;
  /// The input vertex whose distances the segment's split points take on a dyadic grid
  /// (boundary_split.h): the apex of the narrowest corner of the cluster of segments
  /// meeting below kGridCornerDeg that the segment belongs to (plc_preparation.h), so
  /// that the cluster's segments get vertices at the same distances from it; kNone:
  /// midpoints and shells.
  std::uint32_t grid_origin = kNone;
  /// The endpoint is an input vertex shared with another segment: splits of the
  /// subsegment at that end use concentric shells (notes §3.8, Figure 3.33).
  bool shell_a = false, shell_b = false;
  /// Two facets through the segment meet at a dihedral angle below 90 degrees.
  bool small_angle = false;
};
static_assert(sizeof(SegmentData) == 56);

/// Two facets through a segment meeting below 90 degrees, with the sine of their angle
/// (small_angles.h, rule (c)).
struct SegmentWedge {
  std::uint32_t segment, f1, f2;
  double sine;
};

inline std::uint64_t edge_key(std::uint32_t a, std::uint32_t b) {
  if (a > b) std::swap(a, b);
  return (static_cast<std::uint64_t>(a) << 32) | b;
}

/// A face key from three distinct vertex ids (face_key, inlined for the hot paths).
inline FaceKey sorted_face_key(std::uint32_t a, std::uint32_t b, std::uint32_t c) {
  if (a > b) std::swap(a, b);
  if (b > c) std::swap(b, c);
  if (a > b) std::swap(a, b);
  return {a, b, c};
}

/// A subsegment to check (and split if missing or encroached).
struct SubsegmentTask {
  std::uint32_t a, b;
};
/// A subfacet to check or split.
struct SubfaceTask {
  FaceKey face;
};

/// The subsegments and subfacets among the edges and faces of the prepared cavity, each
/// once, in the order of first occurrence over cavity.tets (edges and faces of a tet in
/// kEdgeVertex / kFaceVertex order). Computed once per prepared cavity and shared by the
/// encroachment tests and the queueing of commit_insertion (boundary_split.cpp).
struct CavityElements {
  std::uint64_t serial = 0;  ///< RefineState::cavity_serial it describes (0: nothing)
  std::uint64_t segment_version = 0, face_version = 0;
  std::size_t tet_count = 0;
  std::uint32_t first_tet = kNone;
  std::vector<SubsegmentTask> subsegments;  ///< oriented as met in the cavity tets
  std::vector<FaceKey> subfaces;
  std::vector<std::uint32_t> subface_facets;  ///< facet of each of subfaces
  /// For each of subfaces: the face (4*t + j) of the tet outside the cavity glued to it,
  /// or kNone when the face lies inside the cavity (the insertion deletes it).
  std::vector<std::uint32_t> subface_outside;
  /// Hash set of the cavity tets the current scan has passed (scratch sized to the
  /// cavity rather than one mark per tet slot), slots valid when stamped with `epoch`.
  std::vector<std::uint32_t> scanned_tets = std::vector<std::uint32_t>(64, 0);
  std::vector<std::uint32_t> scanned_epochs = std::vector<std::uint32_t>(64, 0);
  std::uint32_t epoch = 0;
  /// Hash map of the edge keys in `subsegments` to their index there, slots valid when
  /// stamped with `epoch`.
  std::vector<std::uint64_t> found_keys = std::vector<std::uint64_t>(64, 0);
  std::vector<std::uint32_t> found_epochs = std::vector<std::uint32_t>(64, 0);
  std::vector<std::uint32_t> found_index = std::vector<std::uint32_t>(64, 0);
  /// The point cavity_encroached_subsegments / cavity_encroached_subfaces last tested
  /// against these elements, and per subsegment / subfacet the answer (kUntested for one
  /// skipped or not asked about): commit_insertion of that point reuses them.
  static constexpr std::uint8_t kUntested = 2;
  Vec3 tested_segments_point = Vec3::Zero(), tested_faces_point = Vec3::Zero();
  std::vector<std::uint8_t> subsegment_encroached, subface_encroached;
  /// Scratch of commit_insertion: per subsegment, the first cavity boundary face holding
  /// it (index into cavity.boundary, kNone when none does) and the positions of its two
  /// vertices in that face.
  std::vector<std::uint32_t> boundary_face;
  std::vector<std::array<std::uint8_t, 2>> boundary_position;
};

class ProgressReporter;

struct StageCounters {
  std::size_t steiner = 0;
};

struct RefineState {
  RefineState(const Plc& plc_in, const MeshOptions& options_in) : plc(plc_in), options(options_in) {}

  const Plc& plc;
  const MeshOptions& options;

  TetMesh mesh;
  /// The cavity of the last prepare_insertion (boundary_split.h), its serial number, and
  /// the boundary elements found in it (a cache: filled on first use).
  Cavity cavity;
  std::uint64_t cavity_serial = 0;
  mutable CavityElements cavity_elements;
  /// Indexed by tet mesh vertex id. Per-vertex and per-tet-slot arrays are MappedArrays
  /// (toolkit/core/mapped_array.h): they grow by remapping, leaving no outgrown buffer
  /// behind in the heap, which matters because the peak memory is at the end.
  MappedArray<VertexInfo> vertices;

  std::vector<SegmentData> segments;
  SubsegmentTable subsegments;  ///< edge key -> segment
  /// Every wedge of every segment, in segment order (small_angles.h).
  std::vector<SegmentWedge> segment_wedges;
  /// Per segment that has any: the segments of a facet of it that share no vertex with
  /// it and come closer than its length; the floors of its vertices follow the gap
  /// (narrow_facet_floor.h).
  std::unordered_map<std::uint32_t, std::vector<std::uint32_t>> narrow_partners;

  /// The OpenMesh mesh of every facet triangulation, reading the coordinates of `mesh`.
  std::unique_ptr<FacetMeshPool> facet_pool = std::make_unique<FacetMeshPool>(mesh.point_array());
  /// The facet records, in one array (reserved for every input facet before the first is
  /// built: nothing holds a pointer to a record across its growth).
  std::vector<FacetTriangulation> facets;
  std::vector<int> facet_markers;
  SubfaceTable subfaces;  ///< face key -> facet

  /// Region per tet slot (kRegionUnknown until the domain is marked).
  MappedArray<int> tet_region;
  /// Volume bound per region id (absent: none).
  std::unordered_map<int, double> region_max_volume;
  bool domain_marked = false;

  std::vector<SubsegmentTask> subsegment_queue;
  std::vector<SubfaceTask> subface_queue;
  /// Tets created by insertions since the quality stage last looked (for its queue).
  std::vector<std::uint32_t> new_tets;
  bool collect_new_tets = false;

  /// Progress of the run (progress_report.h); polled at every insertion when set.
  ProgressReporter* progress = nullptr;
  /// The sink options.log points to when mesh_plc runs with a log: a trial operation
  /// holds the lines its steps write until it is kept (deferred_split.h). Null: no log,
  /// or lines go straight out.
  HoldingLogSink* log_hold = nullptr;
  /// Entries in the quality stage's tet queue (for progress reports).
  std::size_t tet_queue_size = 0;

  /// Sliver splits quality refinement may still make (sliver_improvement.h).
  std::size_t sliver_splits_left = 0;

  /// Steiner points inserted by the current stage.
  std::size_t stage_steiner = 0;
  /// Subsegment splits of the current stage, by cause (split_subsegment counts the total
  /// into for_rejected_points and shell; restore_conformity moves its own splits to
  /// missing / encroached_by_*).
  SegmentSplitStats stage_segment_splits;
  /// Hard cap on vertices (memory guard); insertions fail beyond it.
  std::size_t vertex_cap = 0;
  /// Refinement on a conforming CDT (notes §2.1.7, §4.2.1 last paragraph): set for the
  /// quality stage after CCDT facet recovery. Cavities are constrained (they cross no
  /// subfacet except those of the facet or segment being split: prepare_insertion's
  /// InsertionSite) and shrunk until star-shaped from the new vertex; only vertices of
  /// tets in the domain encroach subsegments and subfacets (exterior tets are kept but
  /// never refined and never encroach, notes Figure 3.23).
  bool constrained = false;
  /// Constrained insertions whose cavity was shrunk to make it star-shaped, and
  /// candidates dropped because no star-shaped cavity around the tet holding them exists.
  std::size_t cavity_shrinks = 0;
  std::size_t cavity_rejections = 0;
  /// Missing subfacets restore_conformity met on the CCDT (RefineState::constrained),
  /// counted with SegmentRecovery::StronglyDelaunay only (boundary_recovery.h).
  std::size_t constrained_missing_subfaces = 0;
  /// Vertex count at which restore_conformity stops with an error (recovery_limit.h);
  /// set for the recovery stages only.
  std::size_t recovery_limit = std::numeric_limits<std::size_t>::max();

  // scratch
  std::vector<std::uint32_t> scratch_tets;
  std::vector<std::uint32_t> scratch_ring;
  std::vector<int> scratch_regions;
};

/// The segment of subsegment (a, b), or nullptr when (a, b) is not a subsegment (either
/// id may be the infinite vertex).
inline const std::uint32_t* subsegment_of(const RefineState& state, std::uint32_t a, std::uint32_t b) {
  if (!state.subsegments.may_hold(a) || !state.subsegments.may_hold(b)) return nullptr;
  return state.subsegments.lookup(edge_key(a, b));
}

/// The facet of subfacet (a, b, c), or nullptr when (a, b, c) is not a subfacet (any id
/// may be the infinite vertex).
inline const std::uint32_t* subface_of(const RefineState& state, std::uint32_t a, std::uint32_t b, std::uint32_t c) {
  if (!state.subfaces.may_hold(a) || !state.subfaces.may_hold(b) || !state.subfaces.may_hold(c)) return nullptr;
  return state.subfaces.lookup(sorted_face_key(a, b, c));
}

}  // namespace delmesh::tet3d
