// Vertex deletion by edge contraction (refiners/tet3d/vertex_deletion.h): on Delaunay
// meshes of integer points (volumes exact in double), every contraction the planner
// accepts leaves a valid mesh (check_topology: adjacency, exact orientation, connected
// stars) of exactly the same volume without the vertex, and the planner refuses
// contractions that would fold a tet, hull vertices and non-neighbours. In the
// improvement pass (sliver_improvement.h) on gmsh-part, whose thin curved face leaves
// bad tets for every step to work on, deletions happen and the mesh stays valid,
// conforming and of the same volume.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <string>
#include <string_view>
#include <vector>

#include "importers/import.h"
#include "refiners/tet3d/mesh_plc.h"
#include "tests/support/test_paths.h"
#include "toolkit/check/check_mesh.h"
#include "toolkit/core/log.h"

#include "refiners/tet3d/vertex_deletion.h"
#include "tests/support/tetmesh_fixtures.h"
#include "toolkit/tetmesh/delaunay.h"
#include "toolkit/tetmesh/tet_check.h"

namespace delmesh::tet3d {
namespace {

using test::describe;
using test::interior;

/// Delaunay mesh of n points with integer coordinates in [0, 40]^3 (duplicates dropped).
TetMesh integer_mesh(std::size_t n, unsigned seed) {
  auto r = delaunay_tetrahedralize(test::random_integer_points(n, seed, 40));
  EXPECT_TRUE(r.has_value());
  return std::move(r->mesh);
}

/// Six times the total volume of the finite tets: an integer, exact in double here.
double six_volume(const TetMesh& mesh) {
  double sum = 0.0;
  for (std::uint32_t t = 0; t < mesh.tet_slots(); ++t) {
    if (mesh.is_dead(t) || mesh.is_infinite(t)) continue;
    const auto& v = mesh.tet(t).v;
    const Vec3 &a = mesh.point(v[0]), &b = mesh.point(v[1]), &c = mesh.point(v[2]), &d = mesh.point(v[3]);
    sum += (b - a).dot((c - a).cross(d - a));
  }
  return sum;
}

TEST(Tet3dVertexDeletion, AcceptedContractionsKeepAValidMeshOfTheSameVolume) {
  std::size_t accepted = 0, refused = 0;
  for (unsigned seed = 1; seed <= 3; ++seed) {
    const TetMesh original = integer_mesh(150, seed);
    const double volume = six_volume(original);
    ASSERT_GT(volume, 0.0);
    TetMesh scan = original;
    std::vector<std::uint32_t> star, neighbors, created;
    for (std::uint32_t v = 1; v < scan.num_vertices(); ++v) {
      if (!interior(scan, v, star)) continue;
      scan.vertex_neighbors(v, neighbors);
      for (const std::uint32_t u : neighbors) {
        Contraction plan;
        if (!plan_contraction(scan, star, v, u, plan)) {
          ++refused;
          continue;
        }
        ++accepted;
        TetMesh mesh = original;
        commit_contraction(mesh, plan, created);
        ASSERT_EQ(created.size(), plan.tets.size());
        const auto issues = check_topology(mesh);
        ASSERT_TRUE(issues.empty()) << "seed " << seed << " v " << v << " u " << u << ": " << describe(issues);
        EXPECT_EQ(six_volume(mesh), volume) << "seed " << seed << " v " << v << " u " << u;
        EXPECT_EQ(mesh.num_live_tets(), original.num_live_tets() - star.size() + plan.tets.size());
        std::vector<std::uint32_t> after;
        mesh.star(v, after);
        EXPECT_TRUE(after.empty()) << "v " << v << " still has tets";
        // u's star now fills the old star of v too.
        mesh.star(u, after);
        EXPECT_GE(after.size(), plan.tets.size());
      }
    }
  }
  std::printf("contractions accepted %zu, refused %zu\n", accepted, refused);
  EXPECT_GT(accepted, 100u);
  EXPECT_GT(refused, 100u);  // random stars are rarely convex: many cones would fold
}

TEST(Tet3dVertexDeletion, RefusedContractionsWouldFoldATet) {
  // Independent of the planner's own test: a refused plan between interior neighbours
  // has, among the tets of v's star without u, one whose copy with u for v is not
  // positively oriented (computed here in exact integer arithmetic).
  TetMesh mesh = integer_mesh(150, 7);
  std::vector<std::uint32_t> star, neighbors;
  std::size_t checked = 0;
  for (std::uint32_t v = 1; v < mesh.num_vertices(); ++v) {
    if (!interior(mesh, v, star)) continue;
    mesh.vertex_neighbors(v, neighbors);
    for (const std::uint32_t u : neighbors) {
      Contraction plan;
      if (plan_contraction(mesh, star, v, u, plan)) continue;
      bool folds = false;
      for (const std::uint32_t t : star) {
        auto q = mesh.tet(t).v;
        if (mesh.local_index(t, u) >= 0) continue;
        q[mesh.local_index(t, v)] = u;
        const Vec3 &a = mesh.point(q[0]), &b = mesh.point(q[1]), &c = mesh.point(q[2]), &d = mesh.point(q[3]);
        const auto ix = [](double x) { return static_cast<long long>(x); };
        const long long bx = ix(b[0] - a[0]), by = ix(b[1] - a[1]), bz = ix(b[2] - a[2]);
        const long long cx = ix(c[0] - a[0]), cy = ix(c[1] - a[1]), cz = ix(c[2] - a[2]);
        const long long dx = ix(d[0] - a[0]), dy = ix(d[1] - a[1]), dz = ix(d[2] - a[2]);
        const long long det = bx * (cy * dz - cz * dy) - by * (cx * dz - cz * dx) + bz * (cx * dy - cy * dx);
        folds = folds || det <= 0;
      }
      EXPECT_TRUE(folds) << "v " << v << " u " << u << " refused without a folded tet";
      ++checked;
    }
  }
  EXPECT_GT(checked, 10u);
}

TEST(Tet3dVertexDeletion, RefusesHullVerticesAndNonNeighbours) {
  TetMesh mesh = integer_mesh(80, 11);
  std::vector<std::uint32_t> star, neighbors;
  std::size_t hull = 0, strangers = 0;
  for (std::uint32_t v = 1; v < mesh.num_vertices(); ++v) {
    mesh.star(v, star);
    if (star.empty()) continue;
    mesh.vertex_neighbors(v, neighbors);
    bool on_hull = false;
    for (const std::uint32_t t : star) on_hull = on_hull || mesh.is_infinite(t);
    for (std::uint32_t u = 1; u < mesh.num_vertices(); ++u) {
      if (u == v) continue;
      const bool neighbor = std::find(neighbors.begin(), neighbors.end(), u) != neighbors.end();
      Contraction plan;
      if (on_hull && neighbor) {
        EXPECT_FALSE(plan_contraction(mesh, star, v, u, plan)) << "hull vertex " << v;
        ++hull;
      } else if (!neighbor) {
        EXPECT_FALSE(plan_contraction(mesh, star, v, u, plan)) << "v " << v << " u " << u;
        ++strangers;
      }
    }
  }
  EXPECT_GT(hull, 0u);
  EXPECT_GT(strangers, 0u);
}

/// Keeps the improvement pass's summary line.
class SliverLog : public LogSink {
 public:
  void write(LogLevel, std::string_view message) override {
    if (message.find("vertex deletions") != std::string_view::npos) lines.emplace_back(message);
  }
  /// One summary line per run of the pass (improvement_rounds.h).
  std::vector<std::string> lines;
};

/// The number written before `what` in `line` (0 if absent).
std::size_t count_before(const std::string& line, const std::string& what) {
  const std::size_t at = line.find(" " + what);
  if (at == std::string::npos) return 0;
  std::size_t start = at;
  while (start > 0 && std::isdigit(static_cast<unsigned char>(line[start - 1]))) --start;
  return start < at ? std::stoul(line.substr(start, at - start)) : 0;
}

double total_volume(const TetraMesh& mesh) {
  double sum = 0.0;
  for (const auto& v : mesh.tets) {
    const Vec3 &a = mesh.points[v[0]], &b = mesh.points[v[1]], &c = mesh.points[v[2]], &d = mesh.points[v[3]];
    sum += (b - a).dot((c - a).cross(d - a)) / 6.0;
  }
  return sum;
}

TEST(Tet3dVertexDeletion, ImprovementPassDeletesVerticesAndKeepsTheMeshValid) {
  auto plc = import_file(test::corpus_dir() / "step" / "gmsh-part.step", ImportOptions{});
  ASSERT_TRUE(plc.has_value()) << plc.error().message;
  auto plain = mesh_plc(*plc, MeshOptions{});
  MeshOptions options;
  options.min_dihedral_deg = 20.0;
  options.max_dihedral_deg = 150.0;
  SliverLog log;
  options.log = &log;
  auto r = mesh_plc(*plc, options);
  ASSERT_TRUE(plain.has_value() && r.has_value());
  std::size_t deletions = 0;
  for (const std::string& line : log.lines) {
    deletions += count_before(line, "vertex deletions");
    std::printf("gmsh-part: %s\n", line.c_str());
  }
  EXPECT_GT(deletions, 0u);
  CheckMeshOptions check;
  check.check_delaunay = false;
  const auto issues = check_mesh(r->mesh, *plc, r->boundary_face_facets, check);
  EXPECT_TRUE(issues.empty()) << (issues.empty() ? "" : issues.front().message);
  const double volume = total_volume(plain->mesh);
  EXPECT_NEAR(total_volume(r->mesh), volume, 1e-9 * volume);
  // Every output vertex is used by a tet: deleted vertices are gone.
  std::vector<char> used(r->mesh.points.size(), 0);
  for (const auto& v : r->mesh.tets)
    for (const std::uint32_t x : v) used[x] = 1;
  EXPECT_EQ(std::count(used.begin(), used.end(), 0), 0);
}

}  // namespace
}  // namespace delmesh::tet3d
