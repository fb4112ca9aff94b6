// The queueing of commit_insertion (refiners/tet3d/boundary_split.h, notes §4.2.1):
// after every insertion, the subsegment and subfacet queues receive exactly the
// elements of the cavity that are now missing or encroached, in the order of first
// occurrence over the cavity tets. commit_insertion finds them through the cavity's
// element index (CavityElements, with its per-subsegment boundary-face lookup, and the
// new vertex's encroachment answers when they were asked before the commit); here
// they are recomputed by brute force (every edge and face of every cavity tet, the
// status from a fresh walk of the mesh) on random insertions near and away from the
// boundary of each test PLC. With strongly Delaunay segment recovery on the CCDT
// (RefineState::constrained), where only missing elements are split, they receive
// exactly the elements the insertion deleted.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <random>
#include <set>
#include <utility>
#include <vector>

#include "refiners/tet3d/boundary_split.h"
#include "refiners/tet3d/plc_preparation.h"
#include "test_plcs.h"
#include "toolkit/tetmesh/tet_check.h"

namespace delmesh::test {
namespace {

using namespace delmesh::tet3d;

constexpr int kEdges[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};

struct CavityBoundaryElements {
  std::vector<std::pair<std::uint32_t, std::uint32_t>> subsegments;  ///< as met in the cavity tets
  std::vector<FaceKey> subfaces;
};

/// Every subsegment and subfacet among the edges and faces of the prepared cavity, each
/// once, in the order of first occurrence (edges and faces of a tet in local order).
CavityBoundaryElements brute_force_elements(const RefineState& state) {
  CavityBoundaryElements out;
  std::set<std::uint64_t> seen_edges;
  std::set<FaceKey> seen_faces;
  for (const std::uint32_t t : state.cavity.tets) {
    const auto& v = state.mesh.tet(t).v;
    for (const auto& e : kEdges) {
      const std::uint32_t a = v[e[0]], b = v[e[1]];
      if (a == kInfiniteVertex || b == kInfiniteVertex) continue;
      if (!state.subsegments.count(edge_key(a, b)) || !seen_edges.insert(edge_key(a, b)).second) continue;
      out.subsegments.push_back({a, b});
    }
    for (int f = 0; f < 4; ++f) {
      const auto& o = kFaceVertex[f];
      if (v[o[0]] == kInfiniteVertex || v[o[1]] == kInfiniteVertex || v[o[2]] == kInfiniteVertex) continue;
      const FaceKey key = face_key(v[o[0]], v[o[1]], v[o[2]]);
      if (!state.subfaces.count(key) || !seen_faces.insert(key).second) continue;
      out.subfaces.push_back(key);
    }
  }
  return out;
}

/// Subsegments and subfacets met in cavities, and those queued.
struct Counts {
  std::size_t subsegments_met = 0, subsegments_queued = 0, subfaces_met = 0, subfaces_queued = 0;
};

/// Inserts `count` random interior vertices into the prepared PLC (a third of them
/// close to an input vertex, so that cavities often hold several subsegments) and
/// checks each insertion's queueing against the brute-force recomputation, adding to
/// `counts`.
/// `strong_on_ccdt`: with strongly Delaunay segment recovery, each insertion committed
/// as on the CCDT (the cavity found unconstrained, so that it deletes subsegments and
/// subfacets, then committed with RefineState::constrained set); the queues must then
/// hold exactly the cavity's elements that are missing.
void check_random_insertions(const TestPlc& input, int count, std::uint64_t seed, Counts& counts,
                             bool strong_on_ccdt = false) {
  MeshOptions options;
  if (strong_on_ccdt) options.segment_recovery = SegmentRecovery::StronglyDelaunay;
  RefineState state(input.plc, options);
  EXPECT_TRUE(prepare_plc(state).has_value()) << input.name;
  Vec3 lo = input.plc.points.front(), hi = lo;
  for (const Vec3& p : input.plc.points) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const Vec3 extent = hi - lo;
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int k = 0; k < count; ++k) {
    Vec3 p;
    if (k % 3 == 0) {
      const Vec3& near = input.plc.points[rng() % input.plc.points.size()];
      p = near + 0.05 * Vec3(unit(rng) - 0.5, unit(rng) - 0.5, unit(rng) - 0.5).cwiseProduct(extent);
    } else {
      p = lo + Vec3(unit(rng), unit(rng), unit(rng)).cwiseProduct(extent);
    }
    if (!prepare_insertion(state, p, kNone)) continue;
    const CavityBoundaryElements expected = brute_force_elements(state);
    counts.subsegments_met += expected.subsegments.size();
    counts.subfaces_met += expected.subfaces.size();
    if (k % 2 == 1) {
      // As quality refinement does before committing: the encroachment answers of p,
      // which commit_insertion then reuses for the new vertex.
      std::vector<std::uint64_t> segments;
      std::vector<FaceKey> faces;
      cavity_encroached_subsegments(state, p, ~std::uint64_t{0}, segments);
      cavity_encroached_subfaces(state, p, kNone, kNone, faces);
    }
    state.subsegment_queue.clear();
    state.subface_queue.clear();
    VertexInfo info;
    info.kind = VertexKind::Interior;
    state.constrained = strong_on_ccdt;
    commit_insertion(state, p, info);
    state.constrained = false;
    // Present and unencroached elements are never queued; on the CCDT with strongly
    // Delaunay recovery, encroached ones neither.
    const auto queued = [&](SubfaceStatus status) {
      return strong_on_ccdt ? status == SubfaceStatus::Missing : status != SubfaceStatus::Present;
    };

    std::vector<std::pair<std::uint32_t, std::uint32_t>> want_segments;
    for (const auto& [a, b] : expected.subsegments) {
      std::uint32_t by = kNone;
      if (queued(subsegment_status(state, a, b, by))) want_segments.push_back({a, b});
    }
    std::vector<std::pair<std::uint32_t, std::uint32_t>> got_segments;
    for (const SubsegmentTask& s : state.subsegment_queue) got_segments.push_back({s.a, s.b});
    EXPECT_EQ(got_segments, want_segments) << input.name << " insertion " << k;
    counts.subsegments_queued += want_segments.size();

    std::vector<FaceKey> want_faces;
    for (const FaceKey& f : expected.subfaces) {
      std::uint32_t by = kNone;
      if (queued(subface_status(state, f, by))) want_faces.push_back(f);
    }
    std::vector<FaceKey> got_faces;
    for (const SubfaceTask& s : state.subface_queue) got_faces.push_back(s.face);
    EXPECT_EQ(got_faces, want_faces) << input.name << " insertion " << k;
    counts.subfaces_queued += want_faces.size();
  }
  EXPECT_TRUE(check_topology(state.mesh).empty()) << input.name;
}

TEST(Tet3dCommitQueue, QueuesExactlyTheMissingOrEncroachedCavityElements) {
  Counts counts;
  std::uint64_t seed = 7;
  for (const TestPlc& input : all_test_plcs()) check_random_insertions(input, 300, seed++, counts);
  // The insertions reached the boundary, and both answers occurred: many cavity
  // subsegments and subfacets were left present and unencroached, many were not.
  EXPECT_GT(counts.subsegments_queued, 50u);
  EXPECT_GT(counts.subsegments_met - counts.subsegments_queued, 50u);
  EXPECT_GT(counts.subfaces_queued, 20u);
  EXPECT_GT(counts.subfaces_met - counts.subfaces_queued, 20u);
}

TEST(Tet3dCommitQueue, StronglyDelaunayOnTheCcdtQueuesExactlyTheDeletedCavityElements) {
  Counts counts;
  std::uint64_t seed = 7;
  for (const TestPlc& input : all_test_plcs()) check_random_insertions(input, 300, seed++, counts, true);
  // Both answers occurred: cavity subsegments and subfacets deleted, and others left
  // in place (present, encroached or not).
  EXPECT_GT(counts.subsegments_queued, 50u);
  EXPECT_GT(counts.subsegments_met - counts.subsegments_queued, 50u);
  EXPECT_GT(counts.subfaces_queued, 10u);
  EXPECT_GT(counts.subfaces_met - counts.subfaces_queued, 20u);
}

}  // namespace
}  // namespace delmesh::test
