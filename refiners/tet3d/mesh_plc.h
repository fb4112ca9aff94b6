// 3D Delaunay refinement of a piecewise linear complex: the library entry point behind
// `delmesh mesh` (notes ch. 4). Stages: Delaunay tetrahedralization of the PLC vertices,
// segment recovery by stitching, facet recovery by encroachment with per-facet 2D
// triangulations (toolkit/facet), removal of exterior and hole tets with region
// assignment, then quality refinement (radius-edge bound, max volume, sizing) with the
// rejection rules and priorities of §4.2.1 and termination protection for small input
// angles (§4.2.3). The result is always a valid mesh; bounds that cannot be met are
// reported through MeshStatus::Partial and the counters in MeshStats.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "toolkit/core/error.h"
#include "toolkit/core/log.h"
#include "toolkit/core/mesh_status.h"
#include "toolkit/geometry/vec3.h"
#include "toolkit/mesh3d/tetra_mesh.h"
#include "toolkit/plc/plc.h"

namespace delmesh {

/// Which radius-edge bound each tet is held to (notes §4.3; refiners/tet3d/interior_strategy.h).
enum class InteriorStrategy : std::uint8_t {
  /// max_radius_edge for every tet.
  Uniform,
  /// B = 1 for tets touching no segment or facet interior, √2 for tets with a vertex in a
  /// facet interior, 2 for tets with a vertex in a segment interior; each capped by
  /// max_radius_edge.
  Graded,
};

/// A snapshot of a running mesh_plc, for progress displays (MeshOptions::progress).
struct MeshProgress {
  /// "delaunay", "segments", "facets", "domain", "quality", "slivers" (with a dihedral
  /// target, or the default improvement), "polish" (the radius-edge polish after
  /// "slivers", with quality on)
  const char* stage = "";
  double seconds = 0.0;    ///< since mesh_plc started
  std::size_t vertices = 0;
  std::size_t tets = 0;  ///< live tets of the tetrahedralization (exterior ones included)
  std::size_t steiner_points = 0;
  std::size_t subsegment_queue = 0;
  std::size_t subfacet_queue = 0;
  std::size_t tet_queue = 0;  ///< tets waiting for quality refinement (stale entries included)
};

/// How facets are recovered once the segments are (refiners/tet3d/ccdt_facet_recovery.h).
enum class FacetRecovery : std::uint8_t {
  /// Ccdt when no refinement stage follows (no quality, volume or dihedral target),
  /// else Conforming; when the conforming facet recovery stops at its Steiner-point bound
  /// (recovery_limit.h), the run starts again with Ccdt (CcdtStats::after_conforming).
  Auto,
  /// Split missing and encroached subfacets (boundary_recovery.h): a Delaunay mesh.
  Conforming,
  /// Recover the subfacets without Steiner points as a conforming CDT; facets where that
  /// fails fall back to splitting. A refinement stage that follows inserts its vertices
  /// with constrained cavities (RefineState::constrained; notes §2.1.7, §4.2.1).
  Ccdt,
};

/// Which subsegments segment recovery splits (refiners/tet3d/boundary_recovery.h).
enum class SegmentRecovery : std::uint8_t {
  /// Every subsegment missing or encroached (a vertex inside or on its closed diametral
  /// sphere: notes §4.2.1), and in refinement every subsegment a vertex encroaches.
  Diametral,
  /// Only subsegments missing from the Delaunay tetrahedralization or present but not
  /// strongly Delaunay (strong_segments.h; notes §2.1.4: then a CDT exists), then facets
  /// recovered as a CCDT (FacetRecovery::Ccdt; Conforming is an error) and refinement on
  /// it that splits a subsegment or subfacet only for a rejected point (a circumcenter or
  /// subfacet circumcenter that encroaches it) or when it is missing, never because an
  /// existing vertex encroaches it.
  /// Refinement on the CCDT can fail where the conforming path does not (docs/MESHING.md "Quality
  /// refinement on the CCDT"): such a run (an Unsupported error) is started again with
  /// Diametral, with a warning (MeshStats::strong_segments_fell_back).
  StronglyDelaunay,
};

struct MeshOptions {
  /// Refine for quality: split tets whose circumradius-to-shortest-edge ratio exceeds
  /// max_radius_edge (TetGen -q). Without it only boundary recovery and the volume bounds
  /// apply.
  bool quality = true;
  double max_radius_edge = 2.0;
  /// Per-tet bounds of notes §4.3 (see InteriorStrategy). Uniform by default: Graded gives
  /// 1.7 to 12.6 times the tets on corpus inputs without better dihedral angles (docs/MESHING.md).
  InteriorStrategy interior_strategy = InteriorStrategy::Uniform;
  /// Dihedral-angle targets in degrees (sliver removal, notes §4.4); 0 / 180: none.
  double min_dihedral_deg = 0.0;
  double max_dihedral_deg = 180.0;
  /// Without a dihedral target: after refinement, improve the tets with a dihedral angle
  /// below 10 degrees by flips, smoothing, vertex insertion and deletion, never making a
  /// tet that breaks the radius-edge or volume bounds (refiners/tet3d/
  /// default_improvement.h). CLI --no-improve, TetGen -O0: off.
  bool improve = true;
  /// Split tets outside the dihedral window at Chew's random off-centers instead of their
  /// circumcenters (notes §4.4): random points of the inner half of the circumsphere,
  /// rejected when they fall in a cavity face's disallowed region (they would make, with
  /// that face, a tet outside the window whose radius-edge ratio meets the bound); the
  /// circumcenter after 8 rejected candidates. Draws from `seed`. Skinny and too-big tets
  /// keep their circumcenters.
  bool sliver_off_centers = false;
  /// Global maximum tet volume (TetGen -a#); <= 0: none.
  double max_volume = -1.0;
  /// Apply the per-region max volumes of the PLC (TetGen -a without a number).
  bool region_max_volume = true;
  /// Sizing callback: the largest volume wanted for a tet whose circumcenter is p;
  /// <= 0 means no bound there.
  std::function<double(const Vec3& p)> max_volume_at;
  FacetRecovery facet_recovery = FacetRecovery::Auto;
  SegmentRecovery segment_recovery = SegmentRecovery::Diametral;
  /// Keep the tets of the convex hull outside the domain, as region -1 (TetGen -c).
  bool keep_convex_hull = false;
  /// Last-resort budget on Steiner points; negative: unlimited. When it runs out the
  /// result is a valid mesh flagged Partial.
  long long max_steiner_points = -1;
  /// Seed of every randomized choice (insertion order, off-centers); same seed, same mesh.
  std::uint64_t seed = 1;
  /// Log sink for progress lines and warnings; null discards. Progress-level messages
  /// carry the snapshot of `progress` as text.
  LogSink* log = nullptr;
  /// Called at the start of each stage and then about four times a second while a stage
  /// runs (from the calling thread); empty: none.
  std::function<void(const MeshProgress&)> progress;
};

/// Subsegment splits of one pipeline stage by the rule that fired (notes §4.2.1).
struct SegmentSplitStats {
  std::size_t missing = 0;  ///< the subsegment was not an edge of the tetrahedralization
  /// Present but encroached, by the kind of the first vertex found inside or on its
  /// diametral sphere: an input vertex, a vertex on a segment, on a facet, in a volume.
  std::size_t encroached_by_input = 0;
  std::size_t encroached_by_segment_vertex = 0;
  std::size_t encroached_by_facet_vertex = 0;
  std::size_t encroached_by_interior_vertex = 0;
  /// Split because a subfacet or tet circumcenter (or a vertex projecting outside its
  /// facet) would encroach it.
  std::size_t for_rejected_points = 0;
  /// Of all the splits above, those on a concentric shell rather than at the midpoint.
  std::size_t shell = 0;
  std::size_t total() const {
    return missing + encroached_by_input + encroached_by_segment_vertex + encroached_by_facet_vertex +
           encroached_by_interior_vertex + for_rejected_points;
  }
};

/// Time and Steiner points of one pipeline stage.
struct MeshStageStats {
  /// "delaunay", "segments", "facets", "domain", "quality", "slivers", "polish" (the
  /// radius-edge polish: refiners/tet3d/radius_edge_polish.h)
  std::string name;
  double seconds = 0.0;
  std::size_t steiner_points = 0;
  /// The subsegment splits among the Steiner points.
  SegmentSplitStats segment_splits = {};
};

/// What the CCDT facet recovery did (all zero when facets were recovered by splitting).
struct CcdtStats {
  bool used = false;                  ///< facets were recovered as a CCDT
  std::size_t regions = 0;            ///< connected regions of missing subfacets met
  std::size_t recovered_regions = 0;  ///< recovered by cavity retriangulation
  std::size_t failed_regions = 0;     ///< left to the conforming fallback
  std::size_t fallback_facets = 0;    ///< facets recovered by splitting instead
  std::size_t enlargements = 0;       ///< cavity enlargements by one tet
  std::size_t cocircular_flips = 0;   ///< facet triangulation flips to match (Figure 4.8)
  /// Auto chose conforming recovery, which stopped at its bound: this run is the rerun
  /// with Ccdt.
  bool after_conforming = false;
  /// Refinement on the CCDT: insertions whose constrained cavity was shrunk to a star of
  /// the new vertex, and candidates dropped because none existed (RefineState).
  std::size_t cavity_shrinks = 0;
  std::size_t cavity_rejections = 0;
};

struct MeshStats {
  std::size_t input_vertices = 0;
  std::size_t input_segments = 0;
  std::size_t input_facets = 0;
  std::vector<MeshStageStats> stages;
  CcdtStats ccdt;
  /// Tets of the result that miss a bound asked for: radius-edge ratio above
  /// max_radius_edge (quality on), a dihedral angle outside [min_dihedral_deg,
  /// max_dihedral_deg], or a volume above a volume bound; left because a small input
  /// angle or a termination floor forbids fixing them, or because the Steiner budget ran
  /// out. Measured on the result mesh as tet_quality_report measures it.
  std::size_t unmet_tets = 0;
  /// Of those, the ones that touch a small input angle (MeshResult::tet_at_small_angle).
  std::size_t unmet_tets_at_small_angles = 0;
  /// Tets of the result that touch a small input angle: a vertex at an input vertex where
  /// PLC features meet below the angles of notes §4.2.3, or on a segment whose facets
  /// meet below 90 degrees (refiners/tet3d/small_angles.h; docs/MESHING.md "Small input angles").
  std::size_t tets_at_small_angles = 0;
  /// Tets with a dihedral angle outside [min_dihedral_deg, max_dihedral_deg] (0 without
  /// a dihedral target), touching a small input angle and elsewhere.
  std::size_t outside_dihedral_at_small_angles = 0;
  std::size_t outside_dihedral_elsewhere = 0;
  /// A Steiner budget ran out: max_steiner_points, or the automatic bound on the quality
  /// stage (then quality_bound_reached too).
  bool budget_exhausted = false;
  /// The quality stage stopped at its automatic bound (refiners/tet3d/quality_bound.h):
  /// a number of Steiner points proportional to the recovered mesh and the demand of the
  /// volume bounds. The mesh is valid and Partial.
  bool quality_bound_reached = false;
  /// SegmentRecovery::StronglyDelaunay was asked for and the run on the CCDT ended with
  /// an error (Unsupported: a recovery bound, subfacets left missing, an invalid result);
  /// this result is the rerun with SegmentRecovery::Diametral.
  bool strong_segments_fell_back = false;
};

struct MeshResult {
  TetraMesh mesh;
  /// For each boundary face of `mesh`, the index of the PLC facet it lies in.
  std::vector<std::uint32_t> boundary_face_facets;
  /// For each tet of `mesh`: nonzero when it touches a small input angle (MeshStats::
  /// tets_at_small_angles; refiners/tet3d/small_angles.h): 1 by a vertex at the angle,
  /// 2 by lying in a sharp wedge's floor zone or beside a narrow corner (rules (c), (e)),
  /// else 0. tet_quality_report(mesh, tet_at_small_angle, ...)
  /// gives the dihedral histograms of either group.
  std::vector<std::uint8_t> tet_at_small_angle;
  MeshStatus status = MeshStatus::Complete;
  MeshStats stats;
  /// The mesh is a constrained Delaunay tetrahedralization: false once the improvement
  /// pass (dihedral target or MeshOptions::improve) has flipped, moved, inserted or
  /// deleted anything, so check_mesh's Delaunay test no longer applies.
  bool constrained_delaunay = true;
};

/// Meshes `plc`. Errors: PLCs that fail validation (self-intersections, open boundary
/// around a region, ...), with the offending entity ids; PLCs whose segment recovery (or,
/// with FacetRecovery::Conforming, facet recovery) reaches its Steiner-point bound or the
/// resolution of double precision (features nearly touching or meeting at tiny angles:
/// refiners/tet3d/recovery_limit.h), naming the features. With FacetRecovery::Auto a
/// facet recovery that stops so is rerun as a CCDT (a warning on the log).
Expected<MeshResult> mesh_plc(const Plc& plc, const MeshOptions& options);

}  // namespace delmesh
