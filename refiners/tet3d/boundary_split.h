// Vertex insertion for 3D Delaunay refinement and the splits of subsegments and
// subfacets (notes §4.2.1, Figure 4.5): the encroachment tests (diametral sphere
// "inside or on", equatorial sphere "inside or on" for non-coplanar vertices), midpoint,
// concentric-shell (§3.8, Figure 3.33) and narrow-corner grid split points, subfacet splits at
// circumcenters inserted independently into the tetrahedralization and the facet
// triangulation, and the bookkeeping every insertion does (queue the subsegments and
// subfacets its cavity touches, give the new tets a region).
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "refiners/tet3d/refine_state.h"

namespace delmesh::tet3d {

/// What an insertion splits, for constrained cavities (RefineState::constrained): the
/// subfacets of `facet` (a subfacet split) or of the facets holding `segment` (a
/// subsegment split) may be crossed; every other subfacet blocks the cavity search.
struct InsertionSite {
  std::uint32_t facet = kNone;
  std::uint32_t segment = kNone;
};

/// Computes, without changing anything, the Bowyer–Watson cavity of p in state.cavity
/// (constrained by `site` and shrunk to a star of p when state.constrained). False when p
/// coincides with an existing vertex (or the vertex budget is spent), or, constrained,
/// when no star-shaped cavity holds the tet containing p.
bool prepare_insertion(RefineState& state, const Vec3& p, std::uint32_t hint, InsertionSite site = {});

/// For a point ruled out before its cavity is prepared: advances the location walk's
/// random state (state.cavity.rng) as prepare_insertion(state, p, hint) would, without
/// computing the cavity, so that the walks that follow, and with them the mesh (which of
/// two tets sharing the face a point lies on starts its cavity), stay as they were.
void pass_over_insertion(RefineState& state, const Vec3& p, std::uint32_t hint);

/// Inserts p with the cavity of the last prepare_insertion; returns its vertex id. info.floor
/// is the floor of the element p is created for (vertex_floor); the vertex keeps it as its
/// recovery floor outside the quality stage and gets its field floor from
/// new_vertex_floor (termination_floor.h).
std::uint32_t commit_insertion(RefineState& state, const Vec3& p, const VertexInfo& info);

/// Subsegments (edge keys) among the edges of the prepared cavity whose diametral sphere
/// holds p (inside or on), except `skip`.
void cavity_encroached_subsegments(const RefineState& state, const Vec3& p, std::uint64_t skip,
                                   std::vector<std::uint64_t>& out);
/// Subfacets among the faces of the prepared cavity whose equatorial sphere holds p
/// (inside or on; p not coplanar), except those of facet `skip_facet` and of the facets
/// of segment `skip_segment` (kNone: none).
void cavity_encroached_subfaces(const RefineState& state, const Vec3& p, std::uint32_t skip_facet,
                                std::uint32_t skip_segment, std::vector<FaceKey>& out);

/// Is a subfacet among the prepared cavity's faces a face between two of its tets (the
/// insertion deletes it)? When none is, the cavity's tets are joined across faces that
/// are not subfacets, and so lie in one region.
bool cavity_deletes_subface(const RefineState& state);

enum class SubfaceStatus : std::uint8_t { Present, Missing, Encroached };

/// Is the subsegment (a, b) present and unencroached (Present), missing from the
/// tetrahedralization, or encroached (`by`: a vertex inside or on its diametral sphere)?
SubfaceStatus subsegment_status(RefineState& state, std::uint32_t a, std::uint32_t b, std::uint32_t& by);

/// Is the subfacet present and unencroached? For Encroached, `by` names a vertex inside or
/// on its equatorial sphere.
SubfaceStatus subface_status(RefineState& state, const FaceKey& face, std::uint32_t& by);

/// Where an encroached subsegment (a, b) is split: at a power-of-two distance from a
/// shared input endpoint (concentric shells), else at its midpoint. A segment with a grid
/// origin (SegmentData::grid_origin: its narrow-corner cluster's apex) is split on the
/// shell around the origin when the subsegment touches it, else at the distance from the
/// origin m 2^k, 2^k the largest power of two with a multiple in the middle third of the
/// subsegment's distance range (unique, so segments of the cluster with vertices at the
/// same distances get them again).
Vec3 subsegment_split_point(const RefineState& state, std::uint32_t a, std::uint32_t b);

/// Shortest subsegment delmesh makes, relative to the largest coordinate magnitude of its
/// ends: 2^-30. A split point of a shorter one lies off the segment by up to a few units
/// in the last place of its coordinates, more than a millionth of the piece's length, so
/// "on the segment" no longer holds in any useful sense; recovery that needs such pieces
/// has run away at features that nearly touch (recovery_limit.h) and stops with an error.
inline constexpr double kSplitResolution = 0x1p-30;

/// Would splitting subsegment (a, b) at p make a piece shorter than kSplitResolution
/// times the magnitude of its coordinates?
bool below_split_resolution(const RefineState& state, std::uint32_t a, std::uint32_t b, const Vec3& p);

/// Insertion radius of split point p of subsegment (a, b): its distance to the nearer end.
double subsegment_split_radius(const RefineState& state, std::uint32_t a, std::uint32_t b, const Vec3& p);

/// Splits the subsegment (a, b) at `split_point` (from subsegment_split_point), updating
/// the facets holding it. `floor`: termination floor of the new vertex. Returns the new
/// vertex or kNone when the point coincides with a vertex or a new piece would be below
/// the resolution of double precision (below_split_resolution). On the CCDT
/// (RefineState::constrained), when the split point's cavity is refused or keeps (a, b)
/// as an edge (the point would lie on an edge of a kept tet), the points 3/8, 5/8, 1/4
/// and 3/4 of the way from a to b are tried in turn, and when each is refused or keeps
/// (a, b) the split point is taken with its cavity as prepared (docs/MESHING.md, "Why
/// refinement on the CCDT falls back on CAD parts"). `delaunay`
/// false: the facets split their subfacets without their own Lawson flips (the caller
/// makes the flips it checked) and the split is made at `split_point` or not at all.
std::uint32_t split_subsegment(RefineState& state, std::uint32_t a, std::uint32_t b, const Vec3& split_point,
                               double floor, bool delaunay = true);

/// Inserts p, a point of facet `facet` (a subfacet circumcenter), into the facet
/// triangulation and the tetrahedralization. The cavity must be prepared for p. Returns
/// the new vertex, or kNone if p projects outside the facet. `near`: a facet vertex close
/// to p (a vertex of the subfacet split), where the facet's point location starts.
/// `delaunay` false: the facet splits the subfacet without its own Lawson flips (the caller
/// makes the flips it checked, FacetTriangulation::insert_vertex).
std::uint32_t insert_facet_point(RefineState& state, std::uint32_t facet, const Vec3& p, double floor,
                                 std::uint32_t near, bool delaunay = true);

/// Applies a facet triangulation change to the subfacet lookup and queues new subfacets.
void apply_subface_change(RefineState& state, std::uint32_t facet, const SubfaceChange& change);

/// The subfacet of `facet` whose prism holds vertex v (Projection Lemma), if any.
std::optional<FaceKey> subface_below(const RefineState& state, std::uint32_t facet, std::uint32_t near,
                                     const Vec3& v);

/// TetMesh::find_face (the same search, the same face returned) without a heap
/// allocation per call: the state's scratch queue holds the search.
std::optional<FaceRef> find_face_ref(RefineState& state, std::uint32_t a, std::uint32_t b, std::uint32_t c);

/// Distance from p to the nearest vertex of the prepared cavity (its insertion radius);
/// constrained, to the nearest vertex of its tets in the domain (all of them when none is).
double cavity_insertion_radius(const RefineState& state, const Vec3& p);

/// Termination floor of a vertex (0 for vertices without one): VertexInfo::field_floor in
/// the quality stage, VertexInfo::floor before it (termination_floor.h).
inline double vertex_floor(const RefineState& state, std::uint32_t v) {
  return state.collect_new_tets ? state.vertices[v].field_floor : state.vertices[v].floor;
}

}  // namespace delmesh::tet3d
