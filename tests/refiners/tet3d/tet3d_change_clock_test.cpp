// Change tracking of the improvement pass (refiners/tet3d/change_clock.h): after random
// 2-3 flips, edge removals, vertex contractions and vertex moves on Delaunay meshes of
// integer points, each marked as the improvement pass marks them, every vertex the clock
// reports unchanged still has exactly the star it had (the same tets, the same vertices
// at the same coordinates), while vertices whose stars did change are reported changed.
// FailureRecords answers per id from the clock.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <random>
#include <vector>

#include "refiners/tet3d/change_clock.h"
#include "refiners/tet3d/vertex_deletion.h"
#include "tests/support/tetmesh_fixtures.h"
#include "toolkit/predicates/predicates.h"
#include "toolkit/tetmesh/delaunay.h"
#include "toolkit/tetmesh/tet_check.h"
#include "toolkit/tetmesh/tet_flips.h"

namespace delmesh::tet3d {
namespace {

using test::describe;
using test::interior;

/// The star of v as data: each tet's vertices in sorted order with their coordinates,
/// the tets sorted.
using StarSnapshot = std::vector<std::array<double, 16>>;

StarSnapshot snapshot(TetMesh& mesh, std::uint32_t v) {
  std::vector<std::uint32_t> star;
  mesh.star(v, star);
  StarSnapshot out;
  for (const std::uint32_t t : star) {
    std::array<std::uint32_t, 4> q = mesh.tet(t).v;
    std::sort(q.begin(), q.end());
    std::array<double, 16> row{};
    for (int i = 0; i < 4; ++i) {
      row[4 * i] = q[i];
      const Vec3& p = mesh.point(q[i]);
      for (int c = 0; c < 3; ++c) row[4 * i + 1 + c] = p[c];
    }
    out.push_back(row);
  }
  std::sort(out.begin(), out.end());
  return out;
}

/// Moves interior vertex v by a random step if its star stays positively oriented
/// (exact orient3d); true if it moved.
bool try_move(TetMesh& mesh, std::uint32_t v, const std::vector<std::uint32_t>& star, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> step(-0.5, 0.5);
  const Vec3 old = mesh.point(v);
  mesh.move_point(v, old + Vec3(step(rng), step(rng), step(rng)));
  for (const std::uint32_t t : star) {
    const auto& q = mesh.tet(t).v;
    if (predicates::orient3d(mesh.coords(q[0]), mesh.coords(q[1]), mesh.coords(q[2]), mesh.coords(q[3])) !=
        Sign::Positive) {
      mesh.move_point(v, old);
      return false;
    }
  }
  return true;
}

TEST(Tet3dChangeClock, UnchangedVerticesKeepTheirStars) {
  std::size_t unchanged_total = 0, changed_total = 0, operations = 0;
  for (unsigned seed = 1; seed <= 3; ++seed) {
    auto dt = delaunay_tetrahedralize(test::random_integer_points(300, seed, 40));
    ASSERT_TRUE(dt.has_value());
    TetMesh mesh = std::move(dt->mesh);
    ChangeClock clock(mesh.num_vertices());
    std::mt19937_64 rng(seed);
    std::vector<StarSnapshot> before(mesh.num_vertices());
    for (std::uint32_t v = 1; v < mesh.num_vertices(); ++v) before[v] = snapshot(mesh, v);
    const std::uint64_t since = clock.now();
    std::vector<std::uint32_t> created, star, neighbors;
    for (int k = 0; k < 60; ++k) {
      std::uniform_int_distribution<std::uint32_t> pick_tet(0, mesh.tet_slots() - 1);
      std::uniform_int_distribution<std::uint32_t> pick_vertex(1, mesh.num_vertices() - 1);
      const std::uint32_t t = pick_tet(rng);
      if (mesh.is_dead(t) || mesh.is_infinite(t)) continue;
      const auto& v = mesh.tet(t).v;
      switch (k % 4) {
        case 0:
          if (flip23(mesh, {t, static_cast<std::uint8_t>(rng() % 4)}, &created)) {
            clock.made(mesh, created);
            ++operations;
          }
          break;
        case 1: {
          const std::size_t i = rng() % 4, j = (i + 1 + rng() % 3) % 4;
          if (remove_edge(mesh, v[i], v[j], -1.0, &created, tet_shape_quality)) {
            clock.made(mesh, created);
            ++operations;
          }
          break;
        }
        case 2: {
          const std::uint32_t x = pick_vertex(rng);
          if (!interior(mesh, x, star)) break;
          mesh.vertex_neighbors(x, neighbors);
          for (const std::uint32_t u : neighbors) {
            Contraction plan;
            if (!plan_contraction(mesh, star, x, u, plan)) continue;
            commit_contraction(mesh, plan, created);
            clock.made(mesh, created);
            clock.mark(std::span<const std::uint32_t>(&x, 1));  // x has no star now
            ++operations;
            break;
          }
          break;
        }
        default: {
          const std::uint32_t x = pick_vertex(rng);
          if (!interior(mesh, x, star)) break;
          if (try_move(mesh, x, star, rng)) {
            clock.moved(mesh, star);
            ++operations;
          }
        }
      }
    }
    const auto issues = check_topology(mesh);
    ASSERT_TRUE(issues.empty()) << describe(issues);
    for (std::uint32_t v = 1; v < mesh.num_vertices(); ++v) {
      const StarSnapshot now = snapshot(mesh, v);
      const bool reported_unchanged = clock.unchanged_since(std::span<const std::uint32_t>(&v, 1), since);
      if (reported_unchanged) {
        ++unchanged_total;
        EXPECT_EQ(now, before[v]) << "seed " << seed << " vertex " << v << ": star changed, clock says not";
      } else {
        ++changed_total;
      }
      if (now != before[v]) {
        EXPECT_FALSE(reported_unchanged) << "seed " << seed << " vertex " << v;
      }
    }
  }
  std::printf("operations %zu, vertices reported unchanged %zu, changed %zu\n", operations, unchanged_total,
              changed_total);
  EXPECT_GT(operations, 60u);
  EXPECT_GT(unchanged_total, 100u);
  EXPECT_GT(changed_total, 100u);
}

TEST(Tet3dChangeClock, FailureRecordsFollowTheClock) {
  ChangeClock clock(10);
  FailureRecords failed;
  const std::array<std::uint32_t, 2> pair{3, 4};
  EXPECT_FALSE(failed.still_fails(7, pair, clock));  // nothing recorded
  failed.record(7, clock);
  EXPECT_TRUE(failed.still_fails(7, pair, clock));
  EXPECT_FALSE(failed.still_fails(8, pair, clock));
  const std::array<std::uint32_t, 2> other{5, 6};
  clock.mark(other);
  EXPECT_TRUE(failed.still_fails(7, pair, clock));  // 5 and 6 are not 3 and 4
  const std::array<std::uint32_t, 1> four{4};
  clock.mark(four);
  EXPECT_FALSE(failed.still_fails(7, pair, clock));
  failed.record(7, clock);  // a new failure after the change
  EXPECT_TRUE(failed.still_fails(7, pair, clock));
  // A vertex beyond the ones the clock was made for (a vertex just inserted) is unknown
  // until marked, then tracked like the others.
  const std::array<std::uint32_t, 1> fresh{12};
  EXPECT_FALSE(clock.unchanged_since(fresh, clock.now()));
  clock.mark(fresh);
  EXPECT_TRUE(clock.unchanged_since(fresh, clock.now()));
  EXPECT_FALSE(clock.unchanged_since(fresh, clock.now() - 1));
}

}  // namespace
}  // namespace delmesh::tet3d
