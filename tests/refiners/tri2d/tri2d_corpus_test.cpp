// Corpus regression for 2D refinement: every PSLG and point set of the public corpus
// (corpus_dir()/poly2d) is triangulated with a 30 degree minimum-angle bound, and the
// result is checked against the input independently of the refiner's own bookkeeping:
//   * the run terminates with a valid mesh (indices in range, every triangle strictly
//     counterclockwise by the exact orient2d, no edge shared by more than two triangles);
//   * the domain area is conserved: the triangle areas sum to the area of the plain
//     constrained Delaunay triangulation of the same input (relative 1e-9);
//   * every input segment that borders the domain survives as a chain of subsegments that
//     are mesh edges, from one endpoint to the other, through vertices that lie on it and
//     advance along it (segments with holes on both sides vanish with the holes);
//   * where the input has no angle under 60 degrees between segments sharing a vertex,
//     every triangle meets 30 degrees and the status is Complete; elsewhere the triangles
//     below 30 degrees are counted and reported, and the status is Partial exactly when
//     such triangles exist (their number agreeing with the refiner's unmet count).
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <iostream>
#include <numbers>
#include <set>
#include <string>
#include <unordered_map>
#include <vector>

#include "refiners/tri2d/triangulate.h"
#include "tests/support/corpus_inputs.h"
#include "tests/support/test_paths.h"
#include "toolkit/mesh2d/triangle_angles.h"
#include "toolkit/mesh2d/triangle_format_reader.h"
#include "toolkit/mesh2d/triangle_mesh_edges.h"
#include "toolkit/predicates/predicates.h"

namespace delmesh {
namespace {

constexpr double kMinAngle = 30.0;

/// The corpus files (MANIFEST.md, poly2d/); CorpusListIsComplete checks nothing is missed.
const std::vector<std::string>& corpus_files() {
  static const std::vector<std::string> files = {
      "cgal-clusters.poly",          "cgal-fish-and-rectangle.poly",
      "cgal-fish.poly",              "cgal-square-deforme.poly",
      "drufat-a.poly",               "drufat-box.poly",
      "drufat-dots.node",            "drufat-double-hex2.poly",
      "drufat-double-hex3.poly",     "drufat-face.poly",
      "drufat-square-circle-hole.poly", "p2t-debug2.poly",
      "p2t-dude.poly",               "p2t-nazca-heron.poly",
      "p2t-nazca-monkey.poly",
  };
  return files;
}

double twice_signed_area(const Point2& a, const Point2& b, const Point2& c) {
  return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
}

/// Sum of triangle areas, accumulated in long double.
long double mesh_area(const TriangleMesh& mesh) {
  long double sum = 0;
  for (const auto& t : mesh.triangles) {
    sum += twice_signed_area(mesh.points[t[0]], mesh.points[t[1]], mesh.points[t[2]]) / 2.0L;
  }
  return sum;
}

/// Smallest angle (degrees) between two input segments that share an endpoint; 180 when
/// no vertex has two segments.
double smallest_input_angle(const Pslg& pslg) {
  std::vector<std::vector<double>> directions(pslg.points.size());
  for (const auto& s : pslg.segments) {
    const Point2& a = pslg.points[s[0]];
    const Point2& b = pslg.points[s[1]];
    if (a == b) continue;
    directions[s[0]].push_back(std::atan2(b[1] - a[1], b[0] - a[0]));
    directions[s[1]].push_back(std::atan2(a[1] - b[1], a[0] - b[0]));
  }
  double smallest = 180.0;
  for (auto& d : directions) {
    if (d.size() < 2) continue;
    std::sort(d.begin(), d.end());
    for (std::size_t i = 0; i < d.size(); ++i) {
      double gap = (i + 1 < d.size() ? d[i + 1] : d[0] + 2 * std::numbers::pi) - d[i];
      smallest = std::min(smallest, gap * 180.0 / std::numbers::pi);
    }
  }
  return smallest;
}

struct PointHash {
  std::size_t operator()(const Point2& p) const {
    std::uint64_t x = 0, y = 0;
    std::memcpy(&x, &p[0], sizeof x);
    std::memcpy(&y, &p[1], sizeof y);
    return std::hash<std::uint64_t>()(x * 0x9E3779B97F4A7C15ULL ^ y);
  }
};

/// Checks that the mesh is a valid triangulation.
void expect_valid_mesh(const TriangleMesh& mesh, const std::string& file) {
  const std::size_t n = mesh.points.size();
  std::size_t bad_orientation = 0;
  for (const auto& t : mesh.triangles) {
    ASSERT_TRUE(t[0] < n && t[1] < n && t[2] < n) << file;
    if (predicates::orient2d(mesh.points[t[0]].data(), mesh.points[t[1]].data(), mesh.points[t[2]].data()) !=
        Sign::Positive) {
      ++bad_orientation;
    }
  }
  EXPECT_EQ(bad_orientation, 0u) << file << ": triangles not strictly counterclockwise";
  std::vector<std::uint64_t> keys;
  keys.reserve(3 * mesh.triangles.size());
  for (const auto& t : mesh.triangles) {
    for (int k = 0; k < 3; ++k) {
      std::uint32_t u = t[static_cast<std::size_t>(k)], v = t[static_cast<std::size_t>((k + 1) % 3)];
      keys.push_back((static_cast<std::uint64_t>(std::min(u, v)) << 32) | std::max(u, v));
    }
  }
  std::sort(keys.begin(), keys.end());
  std::size_t overshared = 0;
  for (std::size_t i = 0; i + 2 < keys.size(); ++i) overshared += keys[i] == keys[i + 2];
  EXPECT_EQ(overshared, 0u) << file << ": edges shared by more than two triangles";
}

/// For each input segment: is it a chain of mesh edges from one endpoint to the other,
/// through vertices that lie on it and advance along it? With `subsegments_only`, the
/// chain must consist of edges the mesh lists as subsegments (and that are triangle
/// edges); otherwise any triangle edge counts.
std::vector<bool> segment_chains(const Pslg& input, const TriangleMesh& mesh, bool subsegments_only) {
  std::unordered_map<Point2, std::uint32_t, PointHash> vertex_at;
  for (std::uint32_t i = 0; i < mesh.points.size(); ++i) vertex_at.emplace(mesh.points[i], i);
  std::set<std::uint64_t> edges;
  std::vector<std::vector<std::uint32_t>> next_to(mesh.points.size());
  for (const auto& e : mesh_edges(mesh)) {
    edges.insert((static_cast<std::uint64_t>(e.a) << 32) | e.b);
    if (!subsegments_only) {
      next_to[e.a].push_back(e.b);
      next_to[e.b].push_back(e.a);
    }
  }
  if (subsegments_only) {
    for (const auto& s : mesh.segments) {
      next_to[s[0]].push_back(s[1]);
      next_to[s[1]].push_back(s[0]);
    }
  }
  std::vector<bool> kept(input.segments.size(), false);
  for (std::size_t si = 0; si < input.segments.size(); ++si) {
    const Point2& a = input.points[input.segments[si][0]];
    const Point2& b = input.points[input.segments[si][1]];
    const auto ia = vertex_at.find(a);
    const auto ib = vertex_at.find(b);
    if (ia == vertex_at.end() || ib == vertex_at.end() || a == b) continue;
    const double dx = b[0] - a[0], dy = b[1] - a[1];
    const double length = std::sqrt(dx * dx + dy * dy);
    const double scale = std::max({std::abs(a[0]), std::abs(a[1]), std::abs(b[0]), std::abs(b[1])});
    const double tolerance = 1e-9 * length + 1e-12 * scale;
    auto along = [&](const Point2& p) { return ((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / (length * length); };
    auto off_line = [&](const Point2& p) { return std::abs((p[0] - a[0]) * dy - (p[1] - a[1]) * dx) / length; };
    std::uint32_t current = ia->second;
    double t = 0;
    bool ok = true;
    while (ok && current != ib->second) {
      std::uint32_t next = current;
      double next_t = 2;
      for (const std::uint32_t w : next_to[current]) {
        const double tw = along(mesh.points[w]);
        if (tw > t && tw < next_t && off_line(mesh.points[w]) <= tolerance) {
          next = w;
          next_t = tw;
        }
      }
      const std::uint64_t key =
          (static_cast<std::uint64_t>(std::min(current, next)) << 32) | std::max(current, next);
      ok = next != current && edges.count(key) > 0;
      current = next;
      t = next_t;
    }
    kept[si] = ok;
  }
  return kept;
}

class Tri2dCorpus : public ::testing::TestWithParam<std::string> {};

TEST_P(Tri2dCorpus, RefinesTo30DegreesKeepingSegmentsAndArea) {
  const std::string file = GetParam();
  auto input = read_triangle_input(test::corpus_dir() / "poly2d" / file);
  ASSERT_TRUE(input) << input.error().describe();
  const Pslg& pslg = input->pslg;

  // The domain: the plain constrained Delaunay triangulation with holes and concavities
  // removed. Where that leaves nothing (segments that enclose no region, like the one-sided
  // outer box of drufat-box.poly), the convex hull is kept, as Triangle's -c would.
  TriangulateOptions plain;
  plain.pslg = input->has_segment_section;
  auto reference = triangulate(pslg, plain);
  ASSERT_TRUE(reference) << file << ": " << reference.error().describe();
  if (reference->mesh.triangles.empty()) {
    plain.keep_convex_hull = true;
    reference = triangulate(pslg, plain);
    ASSERT_TRUE(reference) << file << ": " << reference.error().describe();
    std::cout << "[corpus] " << file << ": segments enclose no region; convex hull kept (-c)\n";
  }
  const long double domain_area = mesh_area(reference->mesh);
  ASSERT_GT(domain_area, 0.0L) << file;
  // Segments inside removed regions (both sides in holes) disappear with them.
  const std::vector<bool> in_domain = segment_chains(pslg, reference->mesh, false);

  TriangulateOptions quality = plain;
  quality.quality = true;
  quality.min_angle_deg = kMinAngle;
  const auto start = std::chrono::steady_clock::now();
  auto refined = triangulate(pslg, quality);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  ASSERT_TRUE(refined) << file << ": " << refined.error().describe();
  const TriangleMesh& mesh = refined->mesh;

  expect_valid_mesh(mesh, file);
  const long double area = mesh_area(mesh);
  EXPECT_GT(area, 0.0L) << file;
  EXPECT_LE(std::abs(area - domain_area), 1e-9L * std::abs(domain_area))
      << file << ": refined area " << static_cast<double>(area) << " vs domain "
      << static_cast<double>(domain_area);
  const std::vector<bool> chains = segment_chains(pslg, mesh, true);
  std::size_t broken = 0, removed = 0;
  for (std::size_t si = 0; si < chains.size(); ++si) {
    removed += !in_domain[si];
    if (in_domain[si] && !chains[si]) {
      if (++broken <= 3) ADD_FAILURE() << file << ": input segment " << si << " is not a chain of mesh edges";
    }
  }
  EXPECT_EQ(broken, 0u) << file;

  std::size_t below = 0, below_loose = 0;
  double min_angle = 180;
  for (const auto& t : mesh.triangles) {
    const double angle = triangle_min_angle_deg(mesh.points[t[0]], mesh.points[t[1]], mesh.points[t[2]]);
    min_angle = std::min(min_angle, angle);
    below += angle < kMinAngle - 1e-7;
    below_loose += angle < kMinAngle + 1e-7;
  }
  const double input_angle = smallest_input_angle(pslg);
  const bool partial = refined->status == MeshStatus::Partial;
  std::cout << "[corpus] " << file << ": input min angle " << input_angle << " deg, "
            << pslg.segments.size() - removed << "/" << pslg.segments.size() << " segments in the domain, "
            << mesh.points.size() << " vertices, " << mesh.triangles.size() << " triangles, min angle "
            << min_angle << " deg, " << below << " below 30 deg, status " << (partial ? "Partial" : "Complete")
            << " (unmet " << refined->stats.unmet_triangles << "), " << seconds << " s\n";
  RecordProperty("triangles", static_cast<int>(mesh.triangles.size()));
  RecordProperty("below_30", static_cast<int>(below));

  if (input_angle >= 60.0) {
    EXPECT_EQ(below, 0u) << file << ": triangles below 30 degrees although no input angle is under 60";
    EXPECT_FALSE(partial) << file;
    EXPECT_GE(min_angle, kMinAngle - 1e-7) << file;
  }
  // Partial exactly when triangles are left below the bound.
  if (below > 0) {
    EXPECT_TRUE(partial) << file << ": " << below << " triangles below 30 degrees";
  }
  if (below_loose == 0) {
    EXPECT_FALSE(partial) << file << ": Partial with every triangle at 30 degrees";
  }
  if (partial) {
    EXPECT_GE(refined->stats.unmet_triangles, below) << file;
    EXPECT_LE(refined->stats.unmet_triangles, below_loose) << file;
  }
}

INSTANTIATE_TEST_SUITE_P(Poly2d, Tri2dCorpus, ::testing::ValuesIn(corpus_files()),
                         [](const ::testing::TestParamInfo<std::string>& param) { return test::parameter_name(param.param); });

TEST(Tri2dCorpusList, CorpusListIsComplete) {
  const auto dir = test::corpus_dir() / "poly2d";
  ASSERT_TRUE(std::filesystem::is_directory(dir)) << dir;
  std::set<std::string> listed(corpus_files().begin(), corpus_files().end());
  std::size_t found = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    const std::string ext = entry.path().extension().string();
    if (ext != ".poly" && ext != ".node") continue;
    ++found;
    EXPECT_TRUE(listed.count(entry.path().filename().string())) << "not in the corpus test: " << entry.path();
  }
  EXPECT_EQ(found, listed.size());
}

TEST(Tri2dCorpusAngles, SmallestInputAngleMeasuresSegmentPairs) {
  Pslg pslg;
  pslg.points = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  pslg.segments = {{0, 1}, {1, 2}, {2, 3}, {3, 0}};
  EXPECT_NEAR(smallest_input_angle(pslg), 90.0, 1e-12);
  pslg.points = {{0, 0}, {1, 0}, {1, 0.1}};
  pslg.segments = {{0, 1}, {0, 2}};
  EXPECT_NEAR(smallest_input_angle(pslg), std::atan(0.1) * 180 / std::numbers::pi, 1e-9);
  pslg.segments = {{0, 1}};
  EXPECT_EQ(smallest_input_angle(pslg), 180.0);
}

}  // namespace
}  // namespace delmesh
