// Which tets touch a small input angle (refiners/tet3d/small_angles.h, notes §4.2.3), and
// the end-of-run counters (unmet_tets.h) against a recount on the output mesh:
//   * a box has no small angle: no tet is marked;
//   * a free segment leaning on a facet from a vertex inside the facet is a small angle
//     below arccos(1 / (2 sqrt 2)) ~ 69.3 degrees and not above: the tets at that vertex
//     are marked (the segment-facet rule the classification once lacked), and besides
//     them only tets with a vertex on the segment (rule (d));
//   * two free segments 2 degrees apart mark the tets on either arm along its whole
//     length (rule (d): the needle is narrower than the floors), and every tet left above
//     the bound is among them; at 50 degrees only tets near the apex are marked;
//   * two free segments 59.999 degrees apart make their vertex an apex, 60.001 not;
//   * a wall with a 1 degree corner between a step's two tops marks, besides the tets on
//     the arms, the tets with a vertex on the facets beside the arms within its floor of
//     both (rule (e)), some of them above the bounds, and none away from the arms; at 50
//     degrees only near the apex;
//   * a 5 degree wedge marks every tet with a vertex on its sharp segment, and the tets
//     with a vertex on its two facets in the floor zone of the segment (rule (c));
//   * on a 38 degree wedge, tets are marked that no vertex rule marks (each of their
//     vertices also lies in an unmarked tet), all of them reaching across a sharp wedge
//     (rule (f)): 4885 of 13116 tets marked, 3246 without the rule;
//   * on every programmatic PLC, under several option sets, MeshStats equals the
//     recount: unmet tets (radius-edge as tet_quality_report measures it, dihedral
//     window, volume bound), those touching small angles, the tets touching small
//     angles and the tets outside the window in either group.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>

#include "test_plcs.h"

namespace delmesh::test {
namespace {

/// A unit cube whose bottom facet holds the isolated vertex (0.5, 0.5, 0), with a free
/// segment from it into the cube at `degrees` to the bottom facet.
Plc cube_with_leaning_segment(double degrees) {
  Plc plc = unit_cube().plc;
  const double a = degrees * std::numbers::pi / 180.0;
  const auto foot = static_cast<std::uint32_t>(plc.points.size());
  plc.points.emplace_back(0.5, 0.5, 0.0);
  plc.points.emplace_back(0.5 + 0.4 * std::cos(a), 0.5, 0.4 * std::sin(a));
  // Facet 4 of add_box is the bottom (z = 0).
  plc.facets[4].polygons.push_back({foot});
  plc.segments.push_back({foot, foot + 1, 0});
  return plc;
}

bool has_point(const TetraMesh& mesh, std::size_t t, const Vec3& p) {
  for (const std::uint32_t v : mesh.tets[t])
    if (mesh.points[v] == p) return true;
  return false;
}

/// Distance from p to the segment (a, b).
double distance_to_segment(const Vec3& p, const Vec3& a, const Vec3& b) {
  const double t = std::clamp((p - a).dot(b - a) / (b - a).squaredNorm(), 0.0, 1.0);
  return (p - (a + t * (b - a))).norm();
}

TEST(Tet3dSmallAngles, BoxHasNone) {
  MeshOptions options;
  options.max_volume = 0.005;
  auto r = mesh_plc(unit_cube().plc, options);
  ASSERT_TRUE(r.has_value());
  ASSERT_EQ(r->tet_at_small_angle.size(), r->mesh.tets.size());
  EXPECT_EQ(r->stats.tets_at_small_angles, 0u);
  for (const std::uint8_t flag : r->tet_at_small_angle) EXPECT_EQ(flag, 0);
}

TEST(Tet3dSmallAngles, SegmentLeaningOnAFacet) {
  const Vec3 foot(0.5, 0.5, 0.0);
  for (const double degrees : {30.0, 60.0, 75.0, 90.0}) {
    MeshOptions options;
    options.max_volume = 0.01;
    auto r = mesh_plc(cube_with_leaning_segment(degrees), options);
    ASSERT_TRUE(r.has_value()) << degrees << ": " << r.error().message;
    const TetraMesh& mesh = r->mesh;
    ASSERT_EQ(r->tet_at_small_angle.size(), mesh.tets.size());
    const bool small = degrees < 69.3;
    const Vec3& top = cube_with_leaning_segment(degrees).points.back();
    std::size_t at_foot = 0, marked = 0;
    for (std::size_t t = 0; t < mesh.tets.size(); ++t) {
      const bool touches_foot = has_point(mesh, t, foot);
      bool on_segment = false;
      for (const std::uint32_t v : mesh.tets[t]) on_segment = on_segment || distance_to_segment(mesh.points[v], foot, top) <= 1e-12;
      at_foot += touches_foot;
      const bool flagged = r->tet_at_small_angle[t] != 0;
      marked += flagged;
      if (touches_foot) {
        EXPECT_EQ(flagged, small) << degrees << " degrees, tet " << t;
      }
      // Away from the foot only rule (d) marks: a vertex on the segment near the foot.
      if (flagged) {
        EXPECT_TRUE(touches_foot || on_segment) << degrees << " degrees, tet " << t;
      }
    }
    EXPECT_GT(at_foot, 0u) << degrees;
    EXPECT_EQ(r->stats.tets_at_small_angles, marked) << degrees;
    if (!small) {
      EXPECT_EQ(marked, 0u) << degrees;
    }
  }
}

/// A unit cube with two free segments from its centre, `degrees` apart.
Plc cube_with_corner(double degrees) {
  Plc plc = unit_cube().plc;
  const double half = degrees * std::numbers::pi / 360.0;
  const auto apex = static_cast<std::uint32_t>(plc.points.size());
  plc.points.emplace_back(0.5, 0.5, 0.5);
  for (const double side : {-1.0, 1.0})
    plc.points.emplace_back(0.5 + 0.3 * std::sin(side * half), 0.5 + 0.3 * std::cos(half), 0.5);
  plc.segments.push_back({apex, apex + 1, 0});
  plc.segments.push_back({apex, apex + 2, 0});
  return plc;
}

TEST(Tet3dSmallAngles, NarrowCornerAtSixtyDegrees) {
  // Two segments just below 60 degrees make their common vertex an apex (rule (a)), just
  // above they do not: the angle is measured where the cosine is near 1/2, not skipped.
  const Vec3 apex(0.5, 0.5, 0.5);
  for (const double degrees : {59.999, 60.001}) {
    MeshOptions options;
    options.max_volume = 0.01;
    auto r = mesh_plc(cube_with_corner(degrees), options);
    ASSERT_TRUE(r.has_value()) << degrees << ": " << r.error().message;
    std::size_t at_apex = 0, marked_at_apex = 0;
    for (std::size_t t = 0; t < r->mesh.tets.size(); ++t) {
      if (!has_point(r->mesh, t, apex)) continue;
      ++at_apex;
      marked_at_apex += r->tet_at_small_angle[t] == 1;
    }
    EXPECT_GT(at_apex, 0u) << degrees;
    EXPECT_EQ(marked_at_apex, degrees < 60.0 ? at_apex : 0u) << degrees;
  }
}

TEST(Tet3dSmallAngles, SharpSegmentOfAWedge) {
  const TestPlc wedge = sharp_wedge();
  auto r = mesh_plc(wedge.plc, MeshOptions{});
  ASSERT_TRUE(r.has_value()) << r.error().message;
  const TetraMesh& mesh = r->mesh;
  // The 5 degree dihedral angle is at the segment x = y = 0, 0 <= z <= 1.
  std::size_t on_edge = 0;
  for (std::size_t t = 0; t < mesh.tets.size(); ++t) {
    bool touches = false;
    for (const std::uint32_t v : mesh.tets[t]) touches = touches || (mesh.points[v].x() == 0.0 && mesh.points[v].y() == 0.0);
    if (!touches) continue;
    ++on_edge;
    EXPECT_NE(r->tet_at_small_angle[t], 0) << "tet " << t << " has a vertex on the sharp segment";
  }
  EXPECT_GT(on_edge, 0u);
  EXPECT_GE(r->stats.tets_at_small_angles, on_edge);
}

// Rule (c): a tet with no vertex on the sharp segment of the 5 degree wedge is marked 2
// only when one of its vertices lies on one of the wedge's two facets near the segment,
// in the floor zone where the wedge is thinner than the termination floor: every marked
// tet has a facet vertex within half the facets' reach of the segment, tets with a vertex
// on the facets farther out are left unmarked (the zone does not cover the wedge), and
// tets with no vertex on the facets are never marked 2.
TEST(Tet3dSmallAngles, FloorZoneOfAWedge) {
  const TestPlc wedge = sharp_wedge();
  MeshOptions options;
  options.min_dihedral_deg = 20.0;
  options.max_dihedral_deg = 150.0;
  auto r = mesh_plc(wedge.plc, options);
  ASSERT_TRUE(r.has_value()) << r.error().message;
  const TetraMesh& mesh = r->mesh;
  ASSERT_EQ(r->tet_at_small_angle.size(), mesh.tets.size());
  const double a = 5.0 * std::numbers::pi / 180.0;
  const Vec3 normal_low(0.0, 1.0, 0.0), normal_high(-std::sin(a), std::cos(a), 0.0);
  std::size_t zone = 0, zone_outside = 0, unmarked_on_facets = 0;
  double zone_reach = 0.0;
  for (std::size_t t = 0; t < mesh.tets.size(); ++t) {
    const std::uint8_t flag = r->tet_at_small_angle[t];
    bool on_segment = false;
    double nearest_on_facet = std::numeric_limits<double>::infinity();
    for (const std::uint32_t v : mesh.tets[t]) {
      const Vec3& p = mesh.points[v];
      on_segment = on_segment || (p.x() == 0.0 && p.y() == 0.0);
      if (std::abs(p.dot(normal_low)) <= 1e-12 || std::abs(p.dot(normal_high)) <= 1e-12)
        nearest_on_facet = std::min(nearest_on_facet, std::hypot(p.x(), p.y()));
    }
    if (on_segment) {
      EXPECT_EQ(flag, 1) << "tet " << t << " has a vertex on the sharp segment";
      continue;
    }
    if (flag == 1) continue;  // marked by rules (a), (b), (d): the segments in the top facet
    if (flag == 0) {
      if (std::isfinite(nearest_on_facet)) ++unmarked_on_facets;
      continue;
    }
    ++zone;
    ASSERT_TRUE(std::isfinite(nearest_on_facet)) << "tet " << t << " has no vertex on the wedge's facets";
    zone_reach = std::max(zone_reach, nearest_on_facet);
    bool outside = false;
    for (const double angle : dihedral_angles_deg(mesh.points[mesh.tets[t][0]], mesh.points[mesh.tets[t][1]],
                                                  mesh.points[mesh.tets[t][2]], mesh.points[mesh.tets[t][3]]))
      outside = outside || !(angle >= 20.0 && angle <= 150.0);
    zone_outside += outside;
  }
  EXPECT_GT(zone, 0u);
  EXPECT_GT(zone_outside, 0u);
  EXPECT_GT(unmarked_on_facets, 0u);
  EXPECT_LT(zone_reach, 0.5) << "the floor zone should hug the segment (the facets reach 1 from it)";
  EXPECT_GE(r->stats.outside_dihedral_at_small_angles, zone_outside);
}

// Rule (d): the tets at a vertex on a segment, where a small angle that segment makes at
// its end is narrower than the vertex's termination floor. Two free segments 0.2 degrees
// apart (their far ends 0.0021 apart) open more slowly than the floor field grows away
// from those ends (kFloorSlope, 1/128, against sin 0.2 degrees = 0.0035), so the zone
// reaches far from the apex: tets there with a vertex on either arm are marked, only
// those, and every tet left above the radius-edge bound is marked. At 50 degrees the zone
// ends near the apex, so no tet whose vertices all lie far from it is marked.
TEST(Tet3dSmallAngles, FloorZoneOfANeedle) {
  for (const double degrees : {0.2, 50.0}) {
    MeshOptions options;
    options.max_radius_edge = 1.414;
    const Plc plc = cube_with_needle(degrees).plc;
    auto r = mesh_plc(plc, options);
    ASSERT_TRUE(r.has_value()) << degrees << ": " << r.error().message;
    const TetraMesh& mesh = r->mesh;
    ASSERT_EQ(r->tet_at_small_angle.size(), mesh.tets.size());
    const std::size_t a = plc.points.size() - 3;
    const Vec3& apex = plc.points[a];
    std::size_t far_marked = 0, far_on_arm = 0;
    for (std::size_t t = 0; t < mesh.tets.size(); ++t) {
      bool far = true, on_arm = false;
      for (const std::uint32_t v : mesh.tets[t]) {
        const Vec3& p = mesh.points[v];
        far = far && (p - apex).norm() > 0.2;
        on_arm = on_arm || distance_to_segment(p, apex, plc.points[a + 1]) <= 1e-12 ||
                 distance_to_segment(p, apex, plc.points[a + 2]) <= 1e-12;
      }
      if (!far) continue;
      far_on_arm += on_arm;
      far_marked += r->tet_at_small_angle[t] != 0;
      if (r->tet_at_small_angle[t] != 0) {
        EXPECT_TRUE(on_arm) << degrees << " degrees, tet " << t;
      }
    }
    if (degrees < 10.0) {
      EXPECT_GT(far_marked, 0u);
      EXPECT_GT(r->stats.unmet_tets, 0u);
      EXPECT_EQ(r->stats.unmet_tets_at_small_angles, r->stats.unmet_tets);
    } else {
      EXPECT_GT(far_on_arm, 0u);
      EXPECT_EQ(far_marked, 0u);
    }
  }
}

/// A unit cube with a step in its top: the top is z = 1 for y > 0.5 and for x < 0.2, and
/// sinks at `degrees` along +x from the line x = 0.2 for y < 0.5, so the wall y = 0.5
/// between the two tops is a triangle with a `degrees` corner at its apex (0.2, 0.5, 1):
/// the arms are the wall's edges with the two tops (gmsh-part.step's 1.05 degree corners
/// between its faces 13 and 23, 12 and 23, in small).
Plc cube_with_stepped_top(double degrees) {
  const double drop = 0.8 * std::tan(degrees * std::numbers::pi / 180.0);
  Plc plc;
  plc.points = {{0, 0, 0},   {1, 0, 0},        {1, 1, 0},   {0, 1, 0},   {0, 0, 1}, {0.2, 0, 1}, {1, 0, 1 - drop},
                {1, 0.5, 1 - drop}, {1, 0.5, 1}, {1, 1, 1}, {0, 1, 1}, {0.2, 0.5, 1}};
  // 0-3 bottom corners; 4 A, 5 B, 6 C, 7 D, 8 E, 9 F, 10 G, 11 the apex P.
  const std::vector<std::vector<std::uint32_t>> polygons = {
      {0, 3, 2, 1},          // bottom
      {4, 5, 11, 8, 9, 10},  // top, z = 1
      {5, 6, 7, 11},         // sunken top
      {11, 7, 8},            // wall y = 0.5
      {0, 4, 10, 3},         // x = 0
      {1, 2, 9, 8, 7, 6},    // x = 1
      {0, 1, 6, 5, 4},       // y = 0
      {3, 10, 9, 2},         // y = 1
  };
  int marker = 1;
  for (const auto& polygon : polygons) {
    Plc::Facet facet;
    facet.polygons.push_back(polygon);
    facet.marker = marker++;
    plc.facets.push_back(facet);
  }
  return plc;
}

// Rule (e): a tet with no vertex on the arms of a narrow corner is marked 2 when one of its
// vertices lies on a facet beside an arm within its floor of both arms. A step in a cube's
// top whose wall has a 1 degree corner, meshed with the dihedral window [20, 150]: the
// vertices that refinement puts on the facets beside the wall's edges (their subsegments,
// as short as the gap between the arms, encroached) make tets marked 2 (56 of 2036
// tets), some of them above the radius-edge bound (2); every tet marked 2 has a
// vertex off the arms near both of them; tets whose vertices all lie away from the arms
// are not marked (the zone does not cover the facets). At 50 degrees the zone keeps to
// the apex.
TEST(Tet3dSmallAngles, FloorZoneBesideANarrowCorner) {
  for (const double degrees : {1.0, 50.0}) {
    MeshOptions options;
    options.min_dihedral_deg = 20.0;
    options.max_dihedral_deg = 150.0;
    const Plc plc = cube_with_stepped_top(degrees);
    auto r = mesh_plc(plc, options);
    ASSERT_TRUE(r.has_value()) << degrees << ": " << r.error().message;
    const TetraMesh& mesh = r->mesh;
    ASSERT_EQ(r->tet_at_small_angle.size(), mesh.tets.size());
    const Vec3 &apex = plc.points[11], &end1 = plc.points[8], &end2 = plc.points[7];
    std::size_t zone = 0, zone_unmet = 0, far_marked = 0, far = 0;
    double reach = 0.0;
    for (std::size_t t = 0; t < mesh.tets.size(); ++t) {
      const std::uint8_t flag = r->tet_at_small_angle[t];
      bool on_arm = false, all_far = true;
      double nearest = std::numeric_limits<double>::infinity();  // facet vertex off the arms, from the farther arm
      for (const std::uint32_t v : mesh.tets[t]) {
        const Vec3& p = mesh.points[v];
        const double d1 = distance_to_segment(p, apex, end1), d2 = distance_to_segment(p, apex, end2);
        on_arm = on_arm || d1 <= 1e-12 || d2 <= 1e-12;
        all_far = all_far && std::min(d1, d2) > 0.1;
        if (d1 > 1e-12 && d2 > 1e-12) nearest = std::min(nearest, std::max(d1, d2));
      }
      far += all_far;
      if (all_far && flag != 0) ++far_marked;
      if (on_arm || flag != 2) continue;  // tets on the arms: rule (d)'s
      ++zone;
      ASSERT_TRUE(std::isfinite(nearest)) << degrees << " degrees, tet " << t << " has no vertex beside the arms";
      reach = std::max(reach, nearest);
      const auto& v = mesh.tets[t];
      const Vec3 &p0 = mesh.points[v[0]], &p1 = mesh.points[v[1]], &p2 = mesh.points[v[2]], &p3 = mesh.points[v[3]];
      bool unmet = !(radius_edge_ratio(p0, p1, p2, p3) <= options.max_radius_edge);
      for (const double angle : dihedral_angles_deg(p0, p1, p2, p3))
        unmet = unmet || !(angle >= options.min_dihedral_deg && angle <= options.max_dihedral_deg);
      zone_unmet += unmet;
    }
    EXPECT_GT(far, 0u) << degrees;
    EXPECT_EQ(far_marked, 0u) << degrees;
    EXPECT_LT(reach, 0.05) << degrees << " degrees: the zone should hug the arms";
    if (degrees < 10.0) {
      EXPECT_GT(zone, 0u);
      EXPECT_GT(zone_unmet, 0u);
    }
    std::printf("%g degrees: %zu tets, %zu marked by rule (e), %zu of them unmet, reach %g\n", degrees,
                mesh.tets.size(), zone, zone_unmet, reach);
  }
}

struct Recount {
  std::size_t unmet = 0, unmet_small = 0, touching = 0, outside_small = 0, outside_elsewhere = 0;
};

Recount recount(const MeshResult& r, const MeshOptions& o) {
  Recount c;
  const TetraMesh& m = r.mesh;
  const bool window = o.min_dihedral_deg > 0.0 || o.max_dihedral_deg < 180.0;
  for (std::size_t t = 0; t < m.tets.size(); ++t) {
    const auto& v = m.tets[t];
    const Vec3 &a = m.points[v[0]], &b = m.points[v[1]], &cc = m.points[v[2]], &d = m.points[v[3]];
    bool outside = false;
    if (window)
      for (const double angle : dihedral_angles_deg(a, b, cc, d))
        outside = outside || !(angle >= o.min_dihedral_deg && angle <= o.max_dihedral_deg);
    const bool skinny = o.quality && !(radius_edge_ratio(a, b, cc, d) <= o.max_radius_edge);
    const bool big = o.max_volume > 0.0 && signed_volume(a, b, cc, d) > o.max_volume;
    const bool small = r.tet_at_small_angle[t] != 0;
    c.touching += small;
    if (outside) ++(small ? c.outside_small : c.outside_elsewhere);
    if (outside || skinny || big) {
      ++c.unmet;
      c.unmet_small += small;
    }
  }
  return c;
}

/// A prism 8 long over the wedge {(0, 0), (1, 0), (cos a, sin a)} of `degrees`, with its
/// edge on the x axis split 0.02 before its end (a short side facet there, so the recovery
/// floors along the wedge's facets are small): its sharp segment x = y = 0 runs along z.
Plc long_wedge(double degrees) {
  Plc plc;
  const double a = degrees * std::numbers::pi / 180.0;
  add_prism(plc, {{0, 0}, {0.98, 0}, {1, 0}, {std::cos(a), std::sin(a)}}, 8.0);
  return plc;
}

// Rule (f): a tet reaching across a sharp wedge (a vertex on each of its two facets) where
// the wedge is narrower than two floors. Rules (a)-(e) mark vertices, so a tet they mark has
// a vertex all of whose tets are marked; rule (f) marks tets, so on a 38 degree wedge (as
// gmsh-netgen-hinge.stl's 38.3 degree one) there are marked tets each of whose vertices
// also lies in an unmarked tet, and every such tet reaches across a wedge: it has vertices
// on two of the three side planes, which meet pairwise at sharp segments (38 degrees at
// x = y = 0, 71 degrees at the two other vertical edges).
TEST(Tet3dSmallAngles, TetsAcrossAWedge) {
  const double degrees = 38.0;
  MeshOptions options;
  options.max_radius_edge = 1.414;
  auto r = mesh_plc(long_wedge(degrees), options);
  ASSERT_TRUE(r.has_value()) << r.error().message;
  const TetraMesh& mesh = r->mesh;
  ASSERT_EQ(r->tet_at_small_angle.size(), mesh.tets.size());
  std::vector<bool> in_unmarked(mesh.points.size(), false);
  for (std::size_t t = 0; t < mesh.tets.size(); ++t)
    if (r->tet_at_small_angle[t] == 0)
      for (const std::uint32_t v : mesh.tets[t]) in_unmarked[v] = true;
  const double a = degrees * std::numbers::pi / 180.0;
  const Vec3 corner(std::cos(a), std::sin(a), 0.0);
  // The side planes, as (point, unit normal): y = 0, the 38 degree one, the far one.
  const Vec3 far_normal = Vec3(corner.y(), 1.0 - corner.x(), 0.0).normalized();
  const std::array<std::pair<Vec3, Vec3>, 3> planes{{{Vec3::Zero(), Vec3(0.0, 1.0, 0.0)},
                                                     {Vec3::Zero(), Vec3(-std::sin(a), std::cos(a), 0.0)},
                                                     {Vec3(1.0, 0.0, 0.0), far_normal}}};
  std::size_t by_tet = 0;
  for (std::size_t t = 0; t < mesh.tets.size(); ++t) {
    if (r->tet_at_small_angle[t] == 0) continue;
    bool vertex_marked = false;
    std::array<bool, 3> on{};
    for (const std::uint32_t v : mesh.tets[t]) {
      vertex_marked = vertex_marked || !in_unmarked[v];
      for (std::size_t k = 0; k < planes.size(); ++k)
        on[k] = on[k] || std::abs((mesh.points[v] - planes[k].first).dot(planes[k].second)) <= 1e-12;
    }
    if (vertex_marked) continue;
    ++by_tet;
    EXPECT_EQ(r->tet_at_small_angle[t], 2) << "tet " << t;
    EXPECT_GE(int(on[0]) + int(on[1]) + int(on[2]), 2)
        << "tet " << t << " is marked by no vertex rule and does not reach across a wedge";
  }
  std::printf("%zu tets, %zu marked, %zu of them by the tet rule (f) alone\n", mesh.tets.size(),
              static_cast<std::size_t>(r->stats.tets_at_small_angles), by_tet);
  EXPECT_GT(by_tet, 0u);
}

TEST(Tet3dSmallAngles, CountersEqualARecountOnTheOutput) {
  std::vector<MeshOptions> option_sets(5);
  option_sets[1].max_radius_edge = 1.2;
  option_sets[2].min_dihedral_deg = 20.0;
  option_sets[2].max_dihedral_deg = 150.0;
  option_sets[3].quality = false;
  option_sets[3].min_dihedral_deg = 25.0;
  option_sets[4].max_volume = 0.02;
  option_sets[4].max_dihedral_deg = 140.0;
  std::vector<TestPlc> inputs = all_test_plcs();
  inputs.push_back({"leaning_segment", cube_with_leaning_segment(30.0), 1.0, {}, true});
  for (const TestPlc& input : inputs) {
    for (std::size_t k = 0; k < option_sets.size(); ++k) {
      const MeshOptions& options = option_sets[k];
      auto r = mesh_plc(input.plc, options);
      ASSERT_TRUE(r.has_value()) << input.name << " options " << k << ": " << r.error().message;
      ASSERT_EQ(r->tet_at_small_angle.size(), r->mesh.tets.size());
      const Recount c = recount(*r, options);
      const MeshStats& s = r->stats;
      EXPECT_EQ(s.unmet_tets, c.unmet) << input.name << " options " << k;
      EXPECT_EQ(s.unmet_tets_at_small_angles, c.unmet_small) << input.name << " options " << k;
      EXPECT_EQ(s.tets_at_small_angles, c.touching) << input.name << " options " << k;
      EXPECT_EQ(s.outside_dihedral_at_small_angles, c.outside_small) << input.name << " options " << k;
      EXPECT_EQ(s.outside_dihedral_elsewhere, c.outside_elsewhere) << input.name << " options " << k;
      EXPECT_EQ(r->status == MeshStatus::Partial, c.unmet > 0 || s.budget_exhausted) << input.name << " options " << k;
      // The split reports of toolkit/quality add up to the whole.
      const TetQualityReport all = tet_quality_report(r->mesh, options.max_radius_edge, options.min_dihedral_deg,
                                                      options.max_dihedral_deg);
      const TetQualityReport at = tet_quality_report(r->mesh, r->tet_at_small_angle, true, options.max_radius_edge,
                                                     options.min_dihedral_deg, options.max_dihedral_deg);
      const TetQualityReport away = tet_quality_report(r->mesh, r->tet_at_small_angle, false, options.max_radius_edge,
                                                       options.min_dihedral_deg, options.max_dihedral_deg);
      EXPECT_EQ(at.tets + away.tets, all.tets);
      EXPECT_EQ(at.tets, c.touching);
      EXPECT_EQ(at.outside_dihedral_window, c.outside_small);
      EXPECT_EQ(away.outside_dihedral_window, c.outside_elsewhere);
      for (std::size_t bin = 0; bin < all.min_dihedral_counts.size(); ++bin)
        EXPECT_EQ(at.min_dihedral_counts[bin] + away.min_dihedral_counts[bin], all.min_dihedral_counts[bin]);
      for (std::size_t bin = 0; bin < all.max_dihedral_counts.size(); ++bin)
        EXPECT_EQ(at.max_dihedral_counts[bin] + away.max_dihedral_counts[bin], all.max_dihedral_counts[bin]);
    }
  }
}

}  // namespace
}  // namespace delmesh::test
