// Refinement at the kernel level: after tri2d::refine the triangulation is still a valid
// constrained Delaunay triangulation (check_topology, check_delaunay), subsegment owners
// stay consistent, and the Steiner budget is honoured.
#include <gtest/gtest.h>

#include <cmath>

#include "refiners/tri2d/refine.h"
#include "toolkit/mesh2d/cdt.h"
#include "toolkit/mesh2d/validate.h"

namespace delmesh::tri2d {
namespace {

using mesh2d::SubsegmentOwners;
using mesh2d::Triangulation;

struct KernelCase {
  Triangulation tri;
  SubsegmentOwners owners;
  std::vector<std::uint8_t> kind;
};

// A square with an inner slit, a hole and a vertex close to a segment (small local
// feature size), plus an interior point cloud on an integer grid (cocircular points).
void make(KernelCase& s) {
  std::vector<Point2> pts = {{0, 0}, {8, 0}, {8, 8}, {0, 8}, {2, 2}, {5, 3},
                             {6, 6}, {7, 6}, {7, 7}, {6, 7}, {4, 0.01}};
  for (int i = 1; i < 8; i += 2)
    for (int j = 4; j < 6; ++j) pts.push_back({double(i), double(j)});
  ASSERT_TRUE(s.tri.build_delaunay(pts).has_value());
  mesh2d::CdtStats stats;
  ASSERT_TRUE(mesh2d::insert_segments(s.tri,
                                      {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {4, 5}, {6, 7}, {7, 8},
                                       {8, 9}, {9, 6}},
                                      s.owners, stats)
                  .has_value());
  auto dom = mesh2d::classify_domain(s.tri, {{6.5, 6.5}}, {}, mesh2d::DomainOptions{});
  ASSERT_TRUE(dom.has_value());
  s.kind.assign(s.tri.points.size(), kInputVertex);
  classify_input_vertices(s.tri, s.kind);
}

double area(const Triangulation& tri) {
  double a = 0;
  for (std::uint32_t t = 0; t < tri.num_slots(); ++t) {
    if (!tri.in_domain(t)) continue;
    const auto& p = tri.points[tri.tv[3 * t]];
    const auto& q = tri.points[tri.tv[3 * t + 1]];
    const auto& r = tri.points[tri.tv[3 * t + 2]];
    a += 0.5 * ((q[0] - p[0]) * (r[1] - p[1]) - (q[1] - p[1]) * (r[0] - p[0]));
  }
  return a;
}

TEST(Tri2dRefineKernel, StaysConstrainedDelaunay) {
  for (double angle : {25.0, 33.0, 42.0}) {
    KernelCase s;
    make(s);
    RefineParams p;
    p.quality = true;
    p.min_angle_deg = angle;
    p.max_area = 0.5;
    const RefineOutcome out = refine(s.tri, s.owners, s.kind, p);
    EXPECT_GT(out.steiner_points, 50u);
    const auto topo = mesh2d::check_topology(s.tri);
    ASSERT_TRUE(topo.empty()) << topo.front();
    const auto del = mesh2d::check_delaunay(s.tri);
    ASSERT_TRUE(del.empty()) << del.front();
    EXPECT_NEAR(area(s.tri), 64.0 - 1.0, 1e-12 * 64);
    EXPECT_EQ(s.kind.size(), s.tri.points.size());
    // Every marked edge has an owner, and every owner entry is a marked edge.
    std::size_t marked = 0;
    for (std::uint32_t t = 0; t < s.tri.num_slots(); ++t) {
      if (!s.tri.alive(t)) continue;
      for (std::uint32_t i = 0; i < 3; ++i) {
        if (!s.tri.subseg(t, i)) continue;
        ++marked;
        EXPECT_NE(s.owners.get(s.tri.org(t, i), s.tri.dest(t, i)), mesh2d::kNone);
      }
    }
    EXPECT_EQ(marked, 2 * s.owners.size());
  }
}

TEST(Tri2dRefineKernel, SteinerBudget) {
  KernelCase s;
  make(s);
  RefineParams p;
  p.quality = true;
  p.min_angle_deg = 30;
  p.max_area = 0.01;
  p.max_steiner_points = 40;
  const RefineOutcome out = refine(s.tri, s.owners, s.kind, p);
  EXPECT_TRUE(out.budget_exhausted);
  EXPECT_EQ(out.steiner_points, 40u);
  EXPECT_GT(out.unmet_triangles, 0u);
  EXPECT_TRUE(mesh2d::check_topology(s.tri).empty());
}

TEST(Tri2dRefineKernel, InputVertexClassification) {
  KernelCase s;
  make(s);
  // Corner of the outer square (90 degrees): corner, no small angle.
  EXPECT_TRUE(s.kind[0] & kCornerVertex);
  EXPECT_FALSE(s.kind[0] & kSmallAngleVertex);
  // Slit end: one segment, not a corner.
  EXPECT_FALSE(s.kind[4] & kCornerVertex);
  // Interior grid point: no segment.
  EXPECT_EQ(s.kind[11], kInputVertex);
}

}  // namespace
}  // namespace delmesh::tri2d
