// Boundary recovery by encroachment (see boundary_recovery.h; notes §4.2.1).
#include "refiners/tet3d/boundary_recovery.h"

#include <algorithm>
#include <string>

#include "refiners/tet3d/boundary_split.h"
#include "refiners/tet3d/recovery_limit.h"
#include "refiners/tet3d/strong_segments.h"
#include "toolkit/geometry/circumcenter.h"
#include "toolkit/predicates/predicates.h"

namespace delmesh::tet3d {

namespace {

Error cap_error(const RefineState& state) {
  return make_error(ErrorCode::Unsupported, "boundary recovery stopped at the vertex cap (" +
                                                std::to_string(state.vertex_cap) + " vertices)");
}

/// Strongly Delaunay recovery on the CCDT: at most this many missing subfacets, plus one
/// per 64 subfacets, are split the conforming way before the run is given up (mesh_plc
/// then reruns it with diametral recovery). A constrained split that leaves subfacets
/// missing can cascade (each conforming split of one leaving others missing) until the
/// recovery bound, slowly where the cavities are large (gmsh-t106-blade: over 300 s).
/// Measured at B = 1.414: 2-63 on the runs that finish (cgal-fandisk 16-31, cgal-bear
/// 2-3, pocc-io1 32-63), over 32768 on gmsh-part.step before its recovery bound.
constexpr std::size_t kStrongMissingSubfaces = 256;

double face_floor(const RefineState& state, const FaceKey& f) {
  return std::min({vertex_floor(state, f[0]), vertex_floor(state, f[1]), vertex_floor(state, f[2])});
}

/// The smallest field floor (VertexInfo::field_floor, termination_floor.h) among the
/// vertices of subfacet f. Recovery's own floors (VertexInfo::floor) are the element's
/// smallest, so the floor of a pair of nearly coincident input vertices spreads along
/// chains of splits over whole facets; the field grows with the distance from them. An
/// encroached (present) subfacet is split in recovery only when the new vertex respects
/// both: on cgal-step.off two facets meeting at 15.8 degrees (0-1-2 and 0-2-6) took the
/// floor 8e-5 of input vertices 1 and 5, 6.7e-4 apart, and split each other's subfacets
/// to the recovery bound; with the field they stop.
double face_field_floor(const RefineState& state, const FaceKey& f) {
  return std::min({state.vertices[f[0]].field_floor, state.vertices[f[1]].field_floor,
                   state.vertices[f[2]].field_floor});
}

}  // namespace

bool match_cocircular(RefineState& state, std::uint32_t facet, const FaceKey& key) {
  FacetTriangulation& tri = state.facets[facet];
  // The subfacet in the facet's counterclockwise order.
  std::array<std::uint32_t, 3> f = key;
  if (tri.third_vertex(f[0], f[1]) != f[2]) std::swap(f[1], f[2]);
  for (int e = 0; e < 3; ++e) {
    const std::uint32_t x = f[e], y = f[(e + 1) % 3], c = f[(e + 2) % 3];
    if (tri.is_segment(x, y)) continue;
    const std::uint32_t d = tri.third_vertex(y, x);
    if (d == ~0u) continue;
    if (!state.mesh.find_face(c, d, x) || !state.mesh.find_face(c, d, y)) continue;
    auto change = tri.flip_edge(x, y);
    if (!change) continue;
    apply_subface_change(state, facet, change.value());
    return true;
  }
  return false;
}

namespace {

/// Splits subsegment `e` at its split point when `mandatory` or when the new vertex respects
/// `floor`; false if it was not split.
Expected<bool> split_subsegment_above(RefineState& state, std::uint64_t e, double floor, bool mandatory) {
  const std::uint32_t a = static_cast<std::uint32_t>(e >> 32), b = static_cast<std::uint32_t>(e);
  if (!state.subsegments.count(e)) return false;
  const Vec3 q = subsegment_split_point(state, a, b);
  if (!mandatory && subsegment_split_radius(state, a, b, q) < floor) return false;
  if (split_subsegment(state, a, b, q, floor) == kNone) {
    if (state.mesh.num_vertices() >= state.vertex_cap) return cap_error(state);
    // Constrained (refinement on a CCDT): the split's cavity could not be made a star of
    // the split point; the subsegment stays as it is.
    if (state.constrained) return false;
    return split_point_error(state, a, b);
  }
  return true;
}

/// Moves the split just made by split_subsegment (counted as for a rejected point) to
/// the rule that fired: missing, or encroached by a vertex of the kind of `by`.
void count_split_cause(RefineState& state, SubfaceStatus status, std::uint32_t by) {
  SegmentSplitStats& counts = state.stage_segment_splits;
  --counts.for_rejected_points;
  if (status == SubfaceStatus::Missing) {
    ++counts.missing;
    return;
  }
  switch (state.vertices[by].kind) {
    case VertexKind::OnSegment: ++counts.encroached_by_segment_vertex; break;
    case VertexKind::OnFacet: ++counts.encroached_by_facet_vertex; break;
    case VertexKind::Interior: ++counts.encroached_by_interior_vertex; break;
    case VertexKind::Input:
    case VertexKind::Unused: ++counts.encroached_by_input; break;
  }
}

}  // namespace

std::optional<std::uint64_t> subsegment_toward(const RefineState& state, std::uint32_t facet, const FaceKey& from,
                                               const Vec3& p) {
  const FacetTriangulation& tri = state.facets[facet];
  const Axis axis = tri.axis();
  std::array<std::uint32_t, 3> t = from;
  if (tri.third_vertex(t[0], t[1]) != t[2]) std::swap(t[1], t[2]);
  if (tri.third_vertex(t[0], t[1]) != t[2]) return std::nullopt;
  const Vec3 g = (state.mesh.point(t[0]) + state.mesh.point(t[1]) + state.mesh.point(t[2])) / 3.0;
  const double* q = p.data();
  auto at = [&](std::uint32_t v) { return state.mesh.coords(v); };
  // Straight walk from g to q: leave each triangle through the edge (u, v) that has q
  // strictly beyond it and u, v on the right and left of the line g -> q (or on it).
  std::uint64_t entered = ~std::uint64_t{0};
  const std::size_t limit = 4 * tri.subface_count() + 16;
  for (std::size_t step = 0; step < limit; ++step) {
    int exit = -1;
    for (int e = 0; e < 3 && exit < 0; ++e) {
      const std::uint32_t u = t[e], v = t[(e + 1) % 3];
      if (edge_key(u, v) == entered) continue;
      if (predicates::orient2d_projected(at(u), at(v), q, axis) != Sign::Negative) continue;
      if (predicates::orient2d_projected(g.data(), q, at(u), axis) == Sign::Positive) continue;
      if (predicates::orient2d_projected(g.data(), q, at(v), axis) == Sign::Negative) continue;
      exit = e;
    }
    if (exit < 0) return std::nullopt;
    const std::uint32_t u = t[exit], v = t[(exit + 1) % 3];
    if (tri.is_segment(u, v)) return edge_key(u, v);
    const std::uint32_t w = tri.third_vertex(v, u);
    if (w == ~0u) return std::nullopt;
    t = {v, u, w};
    entered = edge_key(u, v);
  }
  return std::nullopt;
}

Expected<void> restore_conformity(RefineState& state, bool segments_only) {
  std::vector<std::uint64_t> encroached;
  std::size_t cocircular_fixes = 0;
  const std::size_t fix_limit = 16 * state.subfaces.size() + 1024;
  const bool strong = state.options.segment_recovery == SegmentRecovery::StronglyDelaunay;
  std::vector<std::uint32_t> ring_tets, ring;
  while (true) {
    if (state.mesh.num_vertices() >= state.recovery_limit) return recovery_limit_error(state);
    if (!state.subsegment_queue.empty()) {
      const SubsegmentTask task = state.subsegment_queue.back();
      state.subsegment_queue.pop_back();
      const auto it = state.subsegments.find(edge_key(task.a, task.b));
      if (it == state.subsegments.end()) continue;
      std::uint32_t by = kNone;
      const SubfaceStatus status = subsegment_status(state, task.a, task.b, by);
      if (status == SubfaceStatus::Present) continue;
      if (status == SubfaceStatus::Encroached && strong) {
        // Strongly Delaunay recovery: on the Delaunay tetrahedralization only a subsegment
        // that is not strongly Delaunay is split; on the CCDT an encroached one stays.
        if (state.constrained || strongly_delaunay_edge(state.mesh, task.a, task.b, ring_tets, ring)) continue;
      }
      const Vec3 p = subsegment_split_point(state, task.a, task.b);
      double floor = std::min(vertex_floor(state, task.a), vertex_floor(state, task.b));
      if (status == SubfaceStatus::Encroached) {
        // Present but encroached: split only above the floor (quality_refinement.h).
        floor = std::min(floor, vertex_floor(state, by));
        if (subsegment_split_radius(state, task.a, task.b, p) < floor) continue;
      }
      if (split_subsegment(state, task.a, task.b, p, floor) == kNone) {
        if (state.mesh.num_vertices() >= state.vertex_cap) return cap_error(state);
        if (state.constrained) continue;  // as in split_subsegment_above
        return split_point_error(state, task.a, task.b);
      }
      count_split_cause(state, status, by);
      continue;
    }
    if (segments_only || state.subface_queue.empty()) break;
    const FaceKey key = state.subface_queue.back().face;
    state.subface_queue.pop_back();
    const auto it = state.subfaces.find(key);
    if (it == state.subfaces.end()) continue;
    const std::uint32_t facet = it->second;
    std::uint32_t by = kNone;
    const SubfaceStatus status = subface_status(state, key, by);
    if (status == SubfaceStatus::Present) continue;
    // Strongly Delaunay recovery, on the CCDT: an encroached (present) subfacet stays.
    if (status == SubfaceStatus::Encroached && strong && state.constrained) continue;
    const bool mandatory = status == SubfaceStatus::Missing;
    if (mandatory && strong && state.constrained &&
        ++state.constrained_missing_subfaces > kStrongMissingSubfaces + state.subfaces.size() / 64)
      return make_error(ErrorCode::Unsupported, "refinement on the CCDT met " +
                                                    std::to_string(state.constrained_missing_subfaces) +
                                                    " missing subfacets (splits cascading)");
    if (mandatory && cocircular_fixes < fix_limit && match_cocircular(state, facet, key)) {
      ++cocircular_fixes;
      continue;
    }
    double floor = face_floor(state, key);
    // Projection Lemma order: split the subfacet whose prism holds the encroaching vertex.
    FaceKey target = key;
    if (!mandatory) {
      floor = std::min(floor, vertex_floor(state, by));
      // Boundary recovery: at least the field floor (termination_floor.h).
      if (!state.collect_new_tets)
        floor = std::max(floor, std::min(face_field_floor(state, key), state.vertices[by].field_floor));
      const Vec3& pb = state.mesh.point(by);
      const auto below = subface_below(state, facet, key[0], pb);
      if (!below) {
        // `by` projects outside the facet: no subfacet is split for it (notes §4.2.3,
        // Projection Lemma); the subsegment between, which it encroaches, is split
        // instead if the floor allows. Otherwise the subfacet stays, present.
        const auto seg = subsegment_toward(state, facet, key, pb);
        if (!seg) continue;
        const std::uint32_t a = static_cast<std::uint32_t>(*seg >> 32), b = static_cast<std::uint32_t>(*seg);
        if (predicates::dot3d(state.mesh.coords(a), state.mesh.coords(b), pb.data()) == Sign::Positive) continue;
        auto split = split_subsegment_above(state, *seg, floor, false);
        if (!split) return split.error();
        if (*split) state.subface_queue.push_back({key});
        continue;
      }
      if (*below != key && state.subfaces.count(*below)) target = *below;
    }
    const auto center =
        triangle_circumcenter(state.mesh.point(target[0]), state.mesh.point(target[1]), state.mesh.point(target[2]));
    DELMESH_CHECK(center.has_value(), "degenerate subfacet");
    Vec3 p = *center;
    if (!prepare_insertion(state, p, state.mesh.any_tet_of(target[0]), {facet, kNone})) {
      if (state.mesh.num_vertices() >= state.vertex_cap) return cap_error(state);
      p = (state.mesh.point(target[0]) + state.mesh.point(target[1]) + state.mesh.point(target[2])) / 3.0;
      if (!prepare_insertion(state, p, state.mesh.any_tet_of(target[0]), {facet, kNone})) {
        DELMESH_CHECK(!mandatory || state.constrained, "a missing subfacet cannot be split");
        continue;
      }
    }
    cavity_encroached_subsegments(state, p, ~std::uint64_t{0}, encroached);
    if (!encroached.empty()) {
      // The circumcenter is rejected; the subsegments it encroaches are split instead.
      if (!mandatory) {
        bool allowed = true;
        for (const std::uint64_t e : encroached) {
          const std::uint32_t a = static_cast<std::uint32_t>(e >> 32), b = static_cast<std::uint32_t>(e);
          if (subsegment_split_radius(state, a, b, subsegment_split_point(state, a, b)) < floor) allowed = false;
        }
        if (!allowed) continue;
      }
      const std::size_t requeued = state.subface_queue.size();
      state.subface_queue.push_back({target});
      if (target != key) state.subface_queue.push_back({key});
      bool split_any = false;
      for (const std::uint64_t e : encroached) {
        const std::uint32_t a = static_cast<std::uint32_t>(e >> 32), b = static_cast<std::uint32_t>(e);
        if (!state.subsegments.count(edge_key(a, b))) continue;
        const Vec3 q = subsegment_split_point(state, a, b);
        if (split_subsegment(state, a, b, q, floor) == kNone) {
          if (state.mesh.num_vertices() >= state.vertex_cap) return cap_error(state);
          if (state.constrained) continue;  // as in split_subsegment_above
          return split_point_error(state, a, b);
        }
        split_any = true;
      }
      // Constrained, with every split refused: nothing changed, so the subfacet is not
      // tried again (a failed split queues nothing, so the two entries are on top).
      if (state.constrained && !split_any) state.subface_queue.resize(requeued);
      continue;
    }
    if (!mandatory && cavity_insertion_radius(state, p) < floor) continue;
    if (insert_facet_point(state, facet, p, floor, target[0]) != kNone) {
      if (target != key) state.subface_queue.push_back({key});
      continue;
    }
    // The circumcenter lies outside the facet: a vertex of the subfacet encroaches the
    // subsegment between (Lemma 17), which is split instead (above the floor unless the
    // subfacet is missing).
    if (const auto seg = subsegment_toward(state, facet, target, p)) {
      auto split = split_subsegment_above(state, *seg, floor, mandatory);
      if (!split) return split.error();
      if (*split) {
        state.subface_queue.push_back({key});
        if (target != key) state.subface_queue.push_back({target});
      }
      continue;
    }
    // Outside by roundoff only: split at the centroid.
    state.subface_queue.push_back({target});
    const Vec3 g = (state.mesh.point(target[0]) + state.mesh.point(target[1]) + state.mesh.point(target[2])) / 3.0;
    if (!prepare_insertion(state, g, state.mesh.any_tet_of(target[0]), {facet, kNone}) ||
        insert_facet_point(state, facet, g, floor, target[0]) == kNone) {
      DELMESH_CHECK(!mandatory || state.constrained, "a missing subfacet cannot be split");
      state.subface_queue.pop_back();
    }
  }
  return {};
}

}  // namespace delmesh::tet3d
