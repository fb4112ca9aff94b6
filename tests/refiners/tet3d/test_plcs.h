// Programmatic PLCs for the 3D refinement tests, with their exact volumes, and the
// mesh checks they share.
#pragma once

#include <array>
#include <chrono>
#include <cstdlib>
#include <cmath>
#include <map>
#include <numbers>
#include <set>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "refiners/tet3d/mesh_plc.h"
#include "toolkit/plc/plc.h"
#include "toolkit/predicates/predicates.h"
#include "toolkit/quality/tet_quality.h"

namespace delmesh::test {

struct TestPlc {
  std::string name;
  Plc plc;
  double volume = 0.0;                  ///< volume of the domain
  std::map<int, double> region_volume;  ///< expected volume per region id (if any)
  bool small_angles = false;
};

/// Adds the 8 corners and 6 quad facets of an axis-aligned box; markers base..base+5.
inline void add_box(Plc& plc, const Vec3& lo, const Vec3& hi, int marker_base) {
  const auto base = static_cast<std::uint32_t>(plc.points.size());
  for (int i = 0; i < 8; ++i)
    plc.points.emplace_back((i & 1) ? hi.x() : lo.x(), (i & 2) ? hi.y() : lo.y(), (i & 4) ? hi.z() : lo.z());
  const std::uint32_t quads[6][4] = {{0, 2, 6, 4}, {1, 5, 7, 3}, {0, 4, 5, 1}, {2, 3, 7, 6}, {0, 1, 3, 2}, {4, 6, 7, 5}};
  for (int f = 0; f < 6; ++f) {
    Plc::Facet facet;
    facet.polygons.push_back({base + quads[f][0], base + quads[f][1], base + quads[f][2], base + quads[f][3]});
    facet.marker = marker_base + f;
    plc.facets.push_back(facet);
  }
}

inline TestPlc unit_cube() {
  TestPlc t{"unit_cube", {}, 1.0, {}, false};
  add_box(t.plc, Vec3(0, 0, 0), Vec3(1, 1, 1), 1);
  return t;
}

inline TestPlc box_with_hole() {
  TestPlc t{"box_with_hole", {}, 64.0 - 1.0, {}, false};
  add_box(t.plc, Vec3(0, 0, 0), Vec3(4, 4, 4), 1);
  add_box(t.plc, Vec3(1.5, 1.5, 1.5), Vec3(2.5, 2.5, 2.5), 11);
  t.plc.holes.emplace_back(2.0, 2.0, 2.0);
  return t;
}

/// Two unit boxes side by side sharing the facet x = 1: regions 1 and 2.
inline TestPlc two_boxes() {
  TestPlc t{"two_boxes", {}, 2.0, {{1, 1.0}, {2, 1.0}}, false};
  Plc& plc = t.plc;
  for (int i = 0; i < 12; ++i) plc.points.emplace_back(i % 3, (i / 3) % 2, i / 6);
  auto id = [](int x, int y, int z) { return static_cast<std::uint32_t>(x + 3 * y + 6 * z); };
  auto facet = [&](std::vector<std::uint32_t> poly, int marker) {
    Plc::Facet f;
    f.polygons.push_back(std::move(poly));
    f.marker = marker;
    plc.facets.push_back(f);
  };
  facet({id(0, 0, 0), id(0, 1, 0), id(0, 1, 1), id(0, 0, 1)}, 1);
  facet({id(2, 0, 0), id(2, 1, 0), id(2, 1, 1), id(2, 0, 1)}, 2);
  facet({id(1, 0, 0), id(1, 1, 0), id(1, 1, 1), id(1, 0, 1)}, 3);  // internal
  for (int x = 0; x < 2; ++x) {
    facet({id(x, 0, 0), id(x + 1, 0, 0), id(x + 1, 0, 1), id(x, 0, 1)}, 4);
    facet({id(x, 1, 0), id(x + 1, 1, 0), id(x + 1, 1, 1), id(x, 1, 1)}, 5);
    facet({id(x, 0, 0), id(x + 1, 0, 0), id(x + 1, 1, 0), id(x, 1, 0)}, 6);
    facet({id(x, 0, 1), id(x + 1, 0, 1), id(x + 1, 1, 1), id(x, 1, 1)}, 7);
  }
  plc.regions.push_back({Vec3(0.5, 0.5, 0.5), 1, -1.0});
  plc.regions.push_back({Vec3(1.5, 0.5, 0.5), 2, -1.0});
  return t;
}

/// A prism over a polygon in the xy plane, from z = 0 to z = h.
inline void add_prism(Plc& plc, const std::vector<std::array<double, 2>>& polygon, double h) {
  const auto n = static_cast<std::uint32_t>(polygon.size());
  const auto base = static_cast<std::uint32_t>(plc.points.size());
  for (const auto& p : polygon) plc.points.emplace_back(p[0], p[1], 0.0);
  for (const auto& p : polygon) plc.points.emplace_back(p[0], p[1], h);
  Plc::Facet bottom, top;
  bottom.polygons.emplace_back();
  top.polygons.emplace_back();
  for (std::uint32_t i = 0; i < n; ++i) {
    bottom.polygons[0].push_back(base + i);
    top.polygons[0].push_back(base + n + i);
  }
  bottom.marker = 1;
  top.marker = 2;
  plc.facets.push_back(bottom);
  plc.facets.push_back(top);
  for (std::uint32_t i = 0; i < n; ++i) {
    Plc::Facet side;
    const std::uint32_t j = (i + 1) % n;
    side.polygons.push_back({base + i, base + j, base + n + j, base + n + i});
    side.marker = 3 + static_cast<int>(i);
    plc.facets.push_back(side);
  }
}

inline TestPlc l_prism() {
  TestPlc t{"l_prism", {}, 3.0, {}, false};
  add_prism(t.plc, {{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}}, 1.0);
  return t;
}

inline TestPlc thin_slab() {
  TestPlc t{"thin_slab", {}, 0.05, {}, false};
  add_box(t.plc, Vec3(0, 0, 0), Vec3(1, 1, 0.05), 1);
  return t;
}

/// A wedge prism whose triangular section has a 5 degree angle (two facets meeting at a
/// 5 degree dihedral angle), plus a fan of two segments meeting at 3 degrees on its top.
inline TestPlc sharp_wedge() {
  const double a = 5.0 * std::numbers::pi / 180.0;
  TestPlc t{"sharp_wedge", {}, 0.0, {}, true};
  add_prism(t.plc, {{0, 0}, {1, 0}, {std::cos(a), std::sin(a)}}, 1.0);
  t.volume = 0.5 * std::sin(a);
  // Two segments in the top facet from vertex 3 (0,0,1) at 3 degrees to each other.
  const double b = 1.0 * std::numbers::pi / 180.0;
  const auto p = static_cast<std::uint32_t>(t.plc.points.size());
  t.plc.points.emplace_back(0.7 * std::cos(b), 0.7 * std::sin(b), 1.0);
  t.plc.points.emplace_back(0.5 * std::cos(4 * b), 0.5 * std::sin(4 * b), 1.0);
  t.plc.facets[1].polygons.push_back({3, p});
  t.plc.facets[1].polygons.push_back({3, p + 1});
  return t;
}

/// A unit cube holding two free segments of length 0.6 from the interior vertex
/// (0.2, 0.5, 0.5) along +x, `degrees` apart: a needle-thin small input angle.
inline TestPlc cube_with_needle(double degrees) {
  TestPlc t = unit_cube();
  t.name = "needle " + std::to_string(degrees);
  t.small_angles = true;
  const double half = degrees * std::numbers::pi / 360.0;
  const auto apex = static_cast<std::uint32_t>(t.plc.points.size());
  const Vec3 p(0.2, 0.5, 0.5);
  t.plc.points.push_back(p);
  t.plc.points.push_back(p + 0.6 * Vec3(std::cos(half), std::sin(half), 0.0));
  t.plc.points.push_back(p + 0.6 * Vec3(std::cos(half), -std::sin(half), 0.0));
  t.plc.segments.push_back({apex, apex + 1, 0});
  t.plc.segments.push_back({apex, apex + 2, 0});
  return t;
}

inline std::vector<TestPlc> all_test_plcs() {
  return {unit_cube(), box_with_hole(), two_boxes(), l_prism(), thin_slab(), sharp_wedge()};
}

inline double tet_volume(const TetraMesh& m, std::size_t t) {
  const auto& v = m.tets[t];
  return signed_volume(m.points[v[0]], m.points[v[1]], m.points[v[2]], m.points[v[3]]);
}

/// Validity checks on a result: positive tets, boundary faces are tet faces with the
/// right neighbours, volume.
inline void expect_valid_mesh(const TestPlc& input, const MeshResult& r) {
  const TetraMesh& m = r.mesh;
  ASSERT_FALSE(m.tets.empty()) << input.name;
  std::map<FaceKey, int> face_count;
  double volume = 0.0;
  std::map<int, double> region_volume;
  for (std::size_t t = 0; t < m.tets.size(); ++t) {
    const auto& v = m.tets[t];
    ASSERT_EQ(predicates::orient3d(m.points[v[0]].data(), m.points[v[1]].data(), m.points[v[2]].data(),
                                   m.points[v[3]].data()),
              Sign::Positive)
        << input.name << " tet " << t;
    const double vol = tet_volume(m, t);
    volume += vol;
    region_volume[m.region_of(t)] += vol;
    for (int i = 0; i < 4; ++i) ++face_count[face_key(v[(i + 1) % 4], v[(i + 2) % 4], v[(i + 3) % 4])];
  }
  EXPECT_NEAR(volume, input.volume, 1e-9 * input.volume) << input.name;
  for (const auto& [id, vol] : input.region_volume) EXPECT_NEAR(region_volume[id], vol, 1e-9 * vol) << input.name;
  ASSERT_EQ(m.boundary_faces.size(), m.boundary_markers.size());
  ASSERT_EQ(m.boundary_faces.size(), r.boundary_face_facets.size());
  std::set<FaceKey> boundary;
  for (const auto& f : m.boundary_faces) {
    const FaceKey key = face_key(f[0], f[1], f[2]);
    EXPECT_TRUE(boundary.insert(key).second) << input.name << ": boundary face listed twice";
    EXPECT_GE(face_count[key], 1) << input.name << ": boundary face is no tet face";
  }
  // Every tet face seen once is on the boundary of the domain: it must be a subfacet.
  for (const auto& [key, count] : face_count) {
    EXPECT_LE(count, 2) << input.name;
    if (count == 1) {
      EXPECT_TRUE(boundary.count(key)) << input.name << ": domain boundary face not a subfacet";
    }
  }
}

}  // namespace delmesh::test
