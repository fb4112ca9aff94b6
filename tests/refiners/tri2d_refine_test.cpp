// 2D Delaunay refinement through delmesh::triangulate: angle and area bounds met,
// input segments kept as chains of edges, area conserved, termination with tiny input
// angles (Partial), regions, sizing callback, Chew's algorithm, determinism.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <set>

#include "refiners/tri2d/triangulate.h"
#include "toolkit/predicates/predicates.h"

namespace delmesh {
namespace {

constexpr double kPi = 3.14159265358979323846;

double tri_area(const TriangleMesh& m, std::size_t t) {
  const auto& a = m.points[m.triangles[t][0]];
  const auto& b = m.points[m.triangles[t][1]];
  const auto& c = m.points[m.triangles[t][2]];
  return 0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]));
}

double tri_min_angle(const TriangleMesh& m, const std::array<std::uint32_t, 3>& t) {
  double best = 180;
  for (int i = 0; i < 3; ++i) {
    const auto& a = m.points[t[i]];
    const auto& b = m.points[t[(i + 1) % 3]];
    const auto& c = m.points[t[(i + 2) % 3]];
    const double ux = b[0] - a[0], uy = b[1] - a[1], wx = c[0] - a[0], wy = c[1] - a[1];
    best = std::min(best, std::atan2(std::abs(ux * wy - uy * wx), ux * wx + uy * wy) * 180 / kPi);
  }
  return best;
}

double min_angle(const TriangleMesh& m) {
  double best = 180;
  for (const auto& t : m.triangles) best = std::min(best, tri_min_angle(m, t));
  return best;
}

double total_area(const TriangleMesh& m) {
  double s = 0;
  for (std::size_t t = 0; t < m.triangles.size(); ++t) s += tri_area(m, t);
  return s;
}

// Valid mesh: counterclockwise triangles, every edge in at most two triangles, every
// edge in one triangle lies on a subsegment.
void expect_valid_mesh(const TriangleMesh& m) {
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> edges;
  for (const auto& t : m.triangles) {
    ASSERT_EQ(predicates::orient2d(m.points[t[0]].data(), m.points[t[1]].data(),
                                   m.points[t[2]].data()),
              Sign::Positive);
    for (int i = 0; i < 3; ++i) {
      const auto key = std::make_pair(t[i], t[(i + 1) % 3]);
      ASSERT_EQ(edges.count(key), 0u) << "directed edge used twice";
      edges[key] = 1;
    }
  }
  std::set<std::pair<std::uint32_t, std::uint32_t>> segs;
  for (const auto& s : m.segments) segs.insert({std::min(s[0], s[1]), std::max(s[0], s[1])});
  for (const auto& [e, one] : edges) {
    if (edges.count({e.second, e.first})) continue;
    EXPECT_TRUE(segs.count({std::min(e.first, e.second), std::max(e.first, e.second)}))
        << "boundary edge is not a subsegment";
  }
}

// Every input segment is a chain of output subsegments from one end to the other.
void expect_segments_kept(const Pslg& in, const TriangleMesh& m) {
  std::multimap<std::uint32_t, std::uint32_t> adj;
  for (const auto& s : m.segments) {
    adj.insert({s[0], s[1]});
    adj.insert({s[1], s[0]});
  }
  for (const auto& s : in.segments) {
    const auto& a = in.points[s[0]];
    const auto& b = in.points[s[1]];
    const double len2 = (b[0] - a[0]) * (b[0] - a[0]) + (b[1] - a[1]) * (b[1] - a[1]);
    std::uint32_t cur = s[0];
    double along = 0;
    bool reached = false;
    for (std::size_t steps = 0; steps < m.segments.size() + 1 && !reached; ++steps) {
      bool moved = false;
      for (auto [it, end] = adj.equal_range(cur); it != end; ++it) {
        const auto& p = m.points[it->second];
        const double t = ((p[0] - a[0]) * (b[0] - a[0]) + (p[1] - a[1]) * (b[1] - a[1])) / len2;
        const double off = std::abs((p[0] - a[0]) * (b[1] - a[1]) - (p[1] - a[1]) * (b[0] - a[0])) / len2;
        if (t > along && off < 1e-12) {
          cur = it->second;
          along = t;
          moved = true;
          break;
        }
      }
      if (cur == s[1]) reached = true;
      if (!moved) break;
    }
    EXPECT_TRUE(reached) << "segment " << s[0] << "-" << s[1] << " is not a chain of subsegments";
  }
}

Pslg polygon(const std::vector<Point2>& pts) {
  Pslg p;
  p.points = pts;
  for (std::uint32_t i = 0; i < pts.size(); ++i)
    p.segments.push_back({i, static_cast<std::uint32_t>((i + 1) % pts.size())});
  return p;
}

double shoelace(const std::vector<Point2>& pts) {
  double s = 0;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const auto& a = pts[i];
    const auto& b = pts[(i + 1) % pts.size()];
    s += a[0] * b[1] - a[1] * b[0];
  }
  return 0.5 * s;
}

// A polygon with a hole and no angle below 60 degrees (a regular 9-gon with a hexagonal
// hole and a notch of 90 degrees).
Pslg annulus(std::vector<Point2>& outer, std::vector<Point2>& inner) {
  outer.clear();
  inner.clear();
  for (int k = 0; k < 9; ++k)
    outer.push_back({3 * std::cos(2 * kPi * k / 9), 3 * std::sin(2 * kPi * k / 9)});
  for (int k = 0; k < 6; ++k)
    inner.push_back({std::cos(2 * kPi * k / 6 + 0.3), std::sin(2 * kPi * k / 6 + 0.3)});
  Pslg p = polygon(outer);
  const auto base = static_cast<std::uint32_t>(outer.size());
  for (std::uint32_t i = 0; i < inner.size(); ++i) {
    p.points.push_back(inner[i]);
    p.segments.push_back({base + i, base + (i + 1) % 6});
  }
  p.holes.push_back({0, 0});
  return p;
}

TEST(Tri2dRefine, MinAngleMetAndAreaConserved) {
  std::vector<Point2> outer, inner;
  const Pslg in = annulus(outer, inner);
  const double area = shoelace(outer) - shoelace(inner);
  for (double angle : {20.0, 30.0, 33.0}) {
    TriangulateOptions opt;
    opt.quality = true;
    opt.min_angle_deg = angle;
    auto r = triangulate(in, opt);
    ASSERT_TRUE(r.has_value()) << r.error().describe();
    EXPECT_EQ(r->status, MeshStatus::Complete) << angle;
    EXPECT_GE(min_angle(r->mesh), angle) << angle;
    EXPECT_NEAR(total_area(r->mesh), area, 1e-12 * area);
    expect_valid_mesh(r->mesh);
    expect_segments_kept(in, r->mesh);
  }
}

TEST(Tri2dRefine, MaxAreaRespected) {
  std::vector<Point2> outer, inner;
  const Pslg in = annulus(outer, inner);
  TriangulateOptions opt;
  opt.quality = true;
  opt.min_angle_deg = 25;
  opt.max_area = 0.01;
  auto r = triangulate(in, opt);
  ASSERT_TRUE(r.has_value());
  EXPECT_EQ(r->status, MeshStatus::Complete);
  for (std::size_t t = 0; t < r->mesh.triangles.size(); ++t) ASSERT_LE(tri_area(r->mesh, t), 0.01);
  EXPECT_GT(r->mesh.triangles.size(), std::size_t((shoelace(outer) - shoelace(inner)) / 0.01));
  expect_segments_kept(in, r->mesh);
}

TEST(Tri2dRefine, SizingCallbackAndRegions) {
  // Two squares side by side; the right one has a region max area.
  Pslg in;
  in.points = {{0, 0}, {1, 0}, {2, 0}, {2, 1}, {1, 1}, {0, 1}};
  in.segments = {{0, 1}, {1, 2}, {2, 3}, {3, 4}, {4, 5}, {5, 0}, {1, 4}};
  in.regions.resize(2);
  in.regions[0] = {{0.5, 0.5}, 7.0, -1.0};
  in.regions[1] = {{1.5, 0.5}, 9.0, 0.002};
  TriangulateOptions opt;
  opt.region_attributes = true;
  opt.region_max_area = true;
  opt.max_area_at = [](double x, double y) { return x < 1 && y < 0.5 ? 0.001 : -1.0; };
  auto r = triangulate(in, opt);
  ASSERT_TRUE(r.has_value());
  const auto& m = r->mesh;
  ASSERT_EQ(m.triangle_attributes.size(), m.triangles.size());
  for (std::size_t t = 0; t < m.triangles.size(); ++t) {
    double cx = 0, cy = 0;
    for (auto v : m.triangles[t]) cx += m.points[v][0] / 3, cy += m.points[v][1] / 3;
    EXPECT_EQ(m.triangle_attributes[t], cx < 1 ? 7.0 : 9.0);
    if (cx > 1) {
      EXPECT_LE(tri_area(m, t), 0.002);
    }
    if (cx < 1 && cy < 0.5) {
      EXPECT_LE(tri_area(m, t), 0.001);
    }
  }
  EXPECT_NEAR(total_area(m), 2.0, 1e-12);
}

// A fan of segments from the origin separated by tiny angles, inside a square.
Pslg fan(double step_deg, int count) {
  Pslg p;
  p.points = {{-1, -1}, {3, -1}, {3, 3}, {-1, 3}, {0, 0}};
  p.segments = {{0, 1}, {1, 2}, {2, 3}, {3, 0}};
  for (int k = 0; k < count; ++k) {
    const double a = (10.0 + k * step_deg) * kPi / 180.0;
    p.points.push_back({2 * std::cos(a), 2 * std::sin(a)});
    p.segments.push_back({4, static_cast<std::uint32_t>(p.points.size() - 1)});
  }
  return p;
}

TEST(Tri2dRefine, TinyInputAnglesTerminateWithPartial) {
  for (double step : {1.0, 0.1}) {
    for (double angle : {30.0, 40.0}) {
      const Pslg in = fan(step, 4);
      TriangulateOptions opt;
      opt.quality = true;
      opt.min_angle_deg = angle;
      auto r = triangulate(in, opt);
      ASSERT_TRUE(r.has_value());
      EXPECT_EQ(r->status, MeshStatus::Partial) << step << " " << angle;
      EXPECT_GT(r->stats.unmet_triangles, 0u);
      EXPECT_LT(r->mesh.triangles.size(), 200000u);
      EXPECT_NEAR(total_area(r->mesh), 16.0, 16e-12);
      expect_valid_mesh(r->mesh);
      expect_segments_kept(in, r->mesh);
    }
  }
}

TEST(Tri2dRefine, HighAngleBoundsTerminate) {
  std::vector<Point2> outer, inner;
  const Pslg in = annulus(outer, inner);
  for (double angle : {40.0, 45.0}) {
    TriangulateOptions opt;
    opt.quality = true;
    opt.min_angle_deg = angle;
    auto r = triangulate(in, opt);
    ASSERT_TRUE(r.has_value());
    EXPECT_LT(r->mesh.triangles.size(), 200000u);
    EXPECT_GE(r->stats.min_angle_deg, 20.0);
    expect_valid_mesh(r->mesh);
    if (r->status == MeshStatus::Complete) {
      EXPECT_GE(min_angle(r->mesh), angle);
    } else {
      EXPECT_GT(r->stats.unmet_triangles, 0u);
    }
  }
}

TEST(Tri2dRefine, ChewFirstAlgorithm) {
  std::vector<Point2> outer, inner;
  const Pslg in = annulus(outer, inner);
  TriangulateOptions opt;
  opt.quality = true;
  opt.chew = true;
  auto r = triangulate(in, opt);
  ASSERT_TRUE(r.has_value());
  EXPECT_EQ(r->status, MeshStatus::Complete);
  EXPECT_GE(min_angle(r->mesh), 28.0);
  expect_valid_mesh(r->mesh);
  expect_segments_kept(in, r->mesh);
  EXPECT_NEAR(total_area(r->mesh), shoelace(outer) - shoelace(inner), 1e-11);
}

TEST(Tri2dRefine, AttributesInterpolatedLinearly) {
  // A linear field is reproduced exactly (up to rounding) at every Steiner vertex.
  std::vector<Point2> outer, inner;
  Pslg in = annulus(outer, inner);
  const auto field = [](const Point2& p) { return 2.0 * p[0] - 3.0 * p[1] + 1.0; };
  in.num_point_attributes = 2;
  for (const auto& p : in.points) {
    in.point_attributes.push_back(field(p));
    in.point_attributes.push_back(5.0);
  }
  TriangulateOptions opt;
  opt.quality = true;
  opt.min_angle_deg = 30;
  opt.max_area = 0.05;
  auto r = triangulate(in, opt);
  ASSERT_TRUE(r.has_value());
  const auto& m = r->mesh;
  ASSERT_EQ(m.num_point_attributes, 2);
  ASSERT_EQ(m.point_attributes.size(), 2 * m.points.size());
  ASSERT_GT(m.points.size(), in.points.size() + 100);
  for (std::size_t v = 0; v < m.points.size(); ++v) {
    EXPECT_NEAR(m.point_attributes[2 * v], field(m.points[v]), 1e-9) << v;
    EXPECT_NEAR(m.point_attributes[2 * v + 1], 5.0, 1e-12) << v;
  }
}

TEST(Tri2dRefine, OffCentersKeepQualityWithFewerTriangles) {
  std::vector<Point2> outer, inner;
  const Pslg in = annulus(outer, inner);
  std::size_t counts[2] = {0, 0};
  for (int off = 0; off < 2; ++off) {
    TriangulateOptions opt;
    opt.quality = true;
    opt.min_angle_deg = 33;
    opt.off_centers = off == 1;
    auto r = triangulate(in, opt);
    ASSERT_TRUE(r.has_value());
    EXPECT_EQ(r->status, MeshStatus::Complete);
    EXPECT_GE(min_angle(r->mesh), 33.0);
    counts[off] = r->mesh.triangles.size();
  }
  EXPECT_LE(counts[1], counts[0]);
}

TEST(Tri2dRefine, RelaxedBoundaryStrategy) {
  std::vector<Point2> outer, inner;
  const Pslg in = annulus(outer, inner);
  TriangulateOptions opt;
  opt.quality = true;
  opt.min_angle_deg = 34;
  opt.max_area = 0.02;
  opt.relaxed_boundary = true;
  auto r = triangulate(in, opt);
  ASSERT_TRUE(r.has_value());
  EXPECT_EQ(r->status, MeshStatus::Complete);
  const auto& m = r->mesh;
  // Steiner vertices on segments carry the boundary marker 1.
  std::size_t relaxed = 0;
  for (const auto& t : m.triangles) {
    const double a = tri_min_angle(m, t);
    EXPECT_GE(a, 20.7);
    bool on_segment = false;
    for (auto v : t) on_segment |= v >= in.points.size() && m.point_markers[v] != 0;
    if (on_segment) {
      relaxed += a < 34.0;
    } else {
      EXPECT_GE(a, 34.0);
    }
  }
  EXPECT_GT(relaxed, 0u);
  expect_segments_kept(in, m);
}

// Degenerate PSLGs that once produced parallel constraint chains around a rounded
// intersection vertex (and endless encroachment between them): a duplicated segment
// crossed by another, and segments overlapping a segment that carries a crossing.
TEST(Tri2dRefine, DuplicateAndOverlappingSegmentsThroughCrossings) {
  Pslg dup;
  dup.points = {{0, 0}, {8, 0}, {8, 8}, {0, 8}, {7, 4}, {1, 1}, {6, 7}};
  dup.segments = {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {3, 4}, {5, 6}, {3, 4}};
  Pslg overlap;
  overlap.points = {{0, 0}, {8, 0}, {8, 8}, {0, 8}, {7, 1}, {8, 4}, {6, 4}, {0, 0}, {1, 0}};
  overlap.segments = {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {4, 1}, {1, 2}, {7, 5},
                      {6, 8}, {5, 5}, {3, 7}, {3, 4}, {6, 1}, {1, 3}};
  Pslg diagonal;  // (0,0)-(2,2) and (1,1)-(8,8) overlap where a third segment crosses
  diagonal.points = {{0, 0}, {8, 0}, {8, 8}, {0, 8}, {2, 2}, {1, 1}, {0, 3.3}, {3.1, 0}};
  diagonal.segments = {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {0, 4}, {6, 7}, {5, 2}};
  for (const Pslg* in : {&dup, &overlap, &diagonal}) {
    for (double angle : {0.0, 20.0, 33.0}) {
      TriangulateOptions opt;
      opt.quality = angle > 0;
      opt.min_angle_deg = angle;
      opt.max_area = 0.5;
      auto r = triangulate(*in, opt);
      ASSERT_TRUE(r.has_value()) << r.error().describe();
      EXPECT_LT(r->mesh.triangles.size(), 5000u) << angle;
      EXPECT_GT(r->stats.segment_crossings, 0u);
      EXPECT_NEAR(total_area(r->mesh), 64.0, 64e-12);
      expect_valid_mesh(r->mesh);
    }
  }
}

TEST(Tri2dRefine, Deterministic) {
  const Pslg in = fan(3.0, 6);
  TriangulateOptions opt;
  opt.quality = true;
  opt.min_angle_deg = 30;
  opt.max_area = 0.05;
  auto a = triangulate(in, opt);
  auto b = triangulate(in, opt);
  ASSERT_TRUE(a.has_value() && b.has_value());
  EXPECT_EQ(a->mesh.points, b->mesh.points);
  EXPECT_EQ(a->mesh.triangles, b->mesh.triangles);
  EXPECT_EQ(a->mesh.segments, b->mesh.segments);
}

TEST(Tri2dTriangulate, BadInputErrors) {
  Pslg in = polygon({{0, 0}, {1, 0}, {0, 1}});
  in.segments.push_back({0, 7});
  auto r = triangulate(in, TriangulateOptions{});
  ASSERT_FALSE(r.has_value());
  EXPECT_NE(r.error().message.find("segment 3"), std::string::npos);

  Pslg nan = polygon({{0, 0}, {1, 0}, {0, std::nan("")}});
  EXPECT_FALSE(triangulate(nan, TriangulateOptions{}).has_value());

  Pslg hole = polygon({{0, 0}, {1, 0}, {0, 1}});
  hole.holes.push_back({2, 2});
  auto rh = triangulate(hole, TriangulateOptions{});
  ASSERT_FALSE(rh.has_value());
  EXPECT_NE(rh.error().message.find("hole 0"), std::string::npos);

  Pslg line = polygon({{0, 0}, {1, 1}, {2, 2}});
  auto rl = triangulate(line, TriangulateOptions{});
  ASSERT_FALSE(rl.has_value());
  EXPECT_EQ(rl.error().code, ErrorCode::DegenerateInput);
}

TEST(Tri2dTriangulate, PointsOnlyAndMarkers) {
  Pslg in;
  in.points = {{0, 0}, {2, 0}, {2, 2}, {0, 2}, {1, 1}, {1, 1}};
  TriangulateOptions opt;
  opt.pslg = false;
  auto r = triangulate(in, opt);
  ASSERT_TRUE(r.has_value());
  EXPECT_EQ(r->mesh.triangles.size(), 4u);
  EXPECT_EQ(r->mesh.segments.size(), 4u);  // hull edges, marker 1
  for (int m : r->mesh.segment_markers) EXPECT_EQ(m, 1);
  EXPECT_EQ(r->mesh.point_markers[4], 0);
  EXPECT_EQ(r->mesh.point_markers[0], 1);
  EXPECT_EQ(r->stats.duplicate_points, 1u);
}

}  // namespace
}  // namespace delmesh
