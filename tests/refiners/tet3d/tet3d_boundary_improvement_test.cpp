// Improvement steps at the boundary, on refined states of the programmatic PLCs.
// Removal of an edge inside a facet (refiners/tet3d/facet_edge_flip.h), the facet vertices
// first moved within the facets as smoothing moves them: the flips it plans and makes
// keep a valid tetrahedralization of the same domain whose faces include every subfacet,
// the facets' triangulations counterclockwise, the regions on both sides (a boundary
// facet, an internal facet between two regions, a hole's facet, the convex hull); it
// refuses subsegments, edges on no facet, flips that do not beat the worst tet around the
// edge, and flips that would lower the facet triangulation's smallest angle.
// Smoothing of hull vertices (sliver_improvement.h): vertices of the convex hull with a
// hull face that is not a subfacet move, and the hull stays convex.
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <random>
#include <set>

#include "refiners/tet3d/facet_edge_flip.h"
#include "refiners/tet3d/sliver_improvement.h"
#include "refined_test_state.h"
#include "toolkit/tetmesh/tet_check.h"

namespace delmesh::test {
namespace {

using namespace delmesh::tet3d;

constexpr double kInf = std::numeric_limits<double>::infinity();

/// Moves the facet Steiner vertices within their facets' planes (the boxes' facets are
/// axis-aligned) by up to a third of their shortest edge, as smoothing would, where every
/// tet around stays positively oriented and every subfacet counterclockwise: the facets
/// are no longer Delaunay, so flips that raise their smallest angle exist.
void move_facet_vertices(RefineState& state) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  TetMesh& mesh = state.mesh;
  std::vector<std::uint32_t> star;
  for (std::uint32_t v = 0; v < mesh.num_vertices(); ++v) {
    if (state.vertices[v].kind != VertexKind::OnFacet) continue;
    const FacetTriangulation& facet = state.facets[state.vertices[v].owner];
    mesh.star(v, star);
    double shortest = kInf;
    for (const std::uint32_t t : star)
      for (const std::uint32_t w : mesh.tet(t).v)
        if (w != v && w != kInfiniteVertex) shortest = std::min(shortest, (mesh.point(w) - mesh.point(v)).norm());
    Vec3 step(u(rng), u(rng), u(rng));
    for (int c = 0; c < 3; ++c)
      if (facet.normal()[c] != 0.0) step[c] = 0.0;
    const Vec3 old = mesh.point(v), moved = old + (shortest / 3.0) * step;
    if (!facet.can_move_vertex(v, moved)) continue;
    mesh.move_point(v, moved);
    bool valid = true;
    for (const std::uint32_t t : star) {
      const auto& w = mesh.tet(t).v;
      if (mesh.is_infinite(t)) continue;
      valid = valid && predicates::orient3d(mesh.coords(w[0]), mesh.coords(w[1]), mesh.coords(w[2]),
                                            mesh.coords(w[3])) == Sign::Positive;
    }
    if (!valid) mesh.move_point(v, old);
  }
}

/// A refined state of `input` (refine_for_improvement) whose facet vertices have been
/// moved off their Delaunay positions.
void refine(RefineState& state, const TestPlc& input) {
  ASSERT_NO_FATAL_FAILURE(refine_for_improvement(state, input));
  move_facet_vertices(state);
}

const RegionTetQuality kMinSine = [](int, const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  return min_dihedral_sine(a, b, c, d);
};

/// The edges of the subfacets that are not subsegments, sorted.
std::vector<std::array<std::uint32_t, 2>> facet_edges(const RefineState& state) {
  std::set<std::array<std::uint32_t, 2>> edges;
  for (const auto& [key, facet] : state.subfaces) {
    for (int i = 0; i < 3; ++i) {
      std::uint32_t a = key[i], b = key[(i + 1) % 3];
      if (a > b) std::swap(a, b);
      if (!subsegment_of(state, a, b)) edges.insert({a, b});
    }
  }
  return {edges.begin(), edges.end()};
}

/// Every live finite tet positively oriented (exact), the topology consistent, every
/// subfacet a face of the mesh and of its facet's triangulation with a counterclockwise
/// star around each vertex, the faces between regions all subfacets, and the volume of
/// each region as given.
void expect_valid_state(RefineState& state, double domain_volume, const std::map<int, double>& region_volume,
                        const std::string& name) {
  TetMesh& mesh = state.mesh;
  EXPECT_TRUE(check_topology(mesh).empty()) << name;
  std::map<int, double> volume;
  for (std::uint32_t t = 0; t < mesh.tet_slots(); ++t) {
    if (mesh.is_dead(t) || mesh.is_infinite(t)) continue;
    const auto& v = mesh.tet(t).v;
    EXPECT_EQ(predicates::orient3d(mesh.coords(v[0]), mesh.coords(v[1]), mesh.coords(v[2]), mesh.coords(v[3])),
              Sign::Positive)
        << name << ": tet " << t;
    const int region = state.tet_region[t];
    if (in_domain(region))
      volume[region] += signed_volume(mesh.point(v[0]), mesh.point(v[1]), mesh.point(v[2]), mesh.point(v[3]));
    for (int f = 0; f < 4; ++f) {
      const std::uint32_t u = mesh.neighbor(t, f);
      const int other = mesh.is_infinite(u) ? kRegionExterior : state.tet_region[u];
      if (other == region) continue;
      const auto& o = kFaceVertex[f];
      EXPECT_NE(subface_of(state, v[o[0]], v[o[1]], v[o[2]]), nullptr) << name << ": region change off the facets";
    }
  }
  double total = 0.0;
  for (const auto& [region, v] : volume) total += v;
  EXPECT_NEAR(total, domain_volume, 1e-12 * domain_volume) << name;
  for (const auto& [region, expected] : region_volume)
    EXPECT_NEAR(volume[region], expected, 1e-12 * expected) << name << ": region " << region;
  std::size_t listed = 0;
  for (std::size_t f = 0; f < state.facets.size(); ++f) {
    const FacetTriangulation& facet = state.facets[f];
    for (const Subface& s : facet.subfaces()) {
      ++listed;
      const std::uint32_t* owner = subface_of(state, s[0], s[1], s[2]);
      ASSERT_NE(owner, nullptr) << name;
      EXPECT_EQ(*owner, f) << name;
      EXPECT_TRUE(mesh.find_face(s[0], s[1], s[2]).has_value()) << name << ": subfacet not a face";
      for (const std::uint32_t v : s)  // counterclockwise around v: it may stay where it is
        EXPECT_TRUE(facet.can_move_vertex(v, mesh.point(v))) << name;
    }
  }
  EXPECT_EQ(listed, state.subfaces.size()) << name;
}

TEST(Tet3dBoundaryImprovement, FlipsKeepAValidMeshOnBothSidesOfTheFacets) {
  // Every flip the plan allows (any valid one: no gain asked), made in turn on a boundary
  // facet, a hole's facets and the internal facet of two regions.
  for (TestPlc input : {unit_cube(), box_with_hole(), two_boxes()}) {
    MeshOptions options;
    options.max_volume = input.volume / 2000.0;
    RefineState state(input.plc, options);
    refine(state, input);
    const std::map<int, double> region_volume = input.region_volume;
    std::size_t flips = 0, internal = 0;
    FacetEdgeFlip plan;
    std::vector<std::uint32_t> created;
    for (const auto& [x, y] : facet_edges(state)) {
      if (!plan_facet_edge_flip(state, x, y, -kInf, kMinSine, plan)) continue;
      const std::size_t subfaces = state.subfaces.size();
      const std::size_t facet_faces = state.facets[plan.facet].subface_count();
      if (!commit_facet_edge_flip(state, plan, created)) continue;
      ++flips;
      EXPECT_EQ(created.size(), plan.tets.size());
      EXPECT_EQ(created.size(), 2 * (plan.old_tets.size() - 2));
      EXPECT_EQ(state.subfaces.size(), subfaces);
      EXPECT_EQ(state.facets[plan.facet].subface_count(), facet_faces);
      EXPECT_EQ(subface_of(state, x, y, plan.c), nullptr);
      ASSERT_NE(subface_of(state, plan.c, plan.d, x), nullptr);
      EXPECT_EQ(*subface_of(state, plan.c, plan.d, y), plan.facet);
      EXPECT_FALSE(state.mesh.find_edge(x, y).has_value());
      std::set<int> sides(plan.regions.begin(), plan.regions.end());
      internal += sides.size() == 2 && in_domain(*sides.begin()) && in_domain(*sides.rbegin());
    }
    std::printf("%-14s %zu facet edge flips, %zu across an internal facet\n", input.name.c_str(), flips, internal);
    EXPECT_GT(flips, 0u) << input.name;
    if (input.name == "two_boxes") {
      EXPECT_GT(internal, 0u);
    }
    expect_valid_state(state, input.volume, region_volume, input.name);
  }
}

TEST(Tet3dBoundaryImprovement, RefusesSegmentsEdgesOffTheFacetsAndFlipsWithoutGain) {
  const TestPlc input = unit_cube();
  MeshOptions options;
  options.max_volume = input.volume / 300.0;
  RefineState state(input.plc, options);
  refine(state, input);
  FacetEdgeFlip plan;
  // A subsegment: a cube edge, split or not.
  std::size_t segments = 0;
  for (const auto& [key, segment] : state.subsegments) {
    const auto a = static_cast<std::uint32_t>(key >> 32), b = static_cast<std::uint32_t>(key);
    EXPECT_FALSE(plan_facet_edge_flip(state, a, b, -kInf, kMinSine, plan));
    ++segments;
  }
  EXPECT_GT(segments, 0u);
  // Edges with an interior vertex: on no facet.
  std::size_t interior = 0;
  for (std::uint32_t t = 0; t < state.mesh.tet_slots() && interior < 50; ++t) {
    if (state.mesh.is_dead(t) || state.mesh.is_infinite(t)) continue;
    const auto& v = state.mesh.tet(t).v;
    for (int i = 0; i < 4; ++i) {
      if (state.vertices[v[i]].kind != VertexKind::Interior) continue;
      EXPECT_FALSE(plan_facet_edge_flip(state, v[i], v[(i + 1) % 4], -kInf, kMinSine, plan));
      ++interior;
    }
  }
  EXPECT_GT(interior, 0u);
  // No flip beats the tets around its edge by more than 2 (sines are at most 1), and the
  // refusals change nothing.
  const std::size_t live = state.mesh.num_live_tets();
  std::size_t allowed = 0;
  for (const auto& [x, y] : facet_edges(state)) {
    EXPECT_FALSE(plan_facet_edge_flip(state, x, y, 2.0, kMinSine, plan));
    allowed += plan_facet_edge_flip(state, x, y, -kInf, kMinSine, plan);
  }
  EXPECT_GT(allowed, 0u);
  EXPECT_EQ(state.mesh.num_live_tets(), live);
  expect_valid_state(state, input.volume, {}, input.name);
}

double smallest_angle(const Vec3& a, const Vec3& b, const Vec3& c) {
  auto angle = [](const Vec3& o, const Vec3& p, const Vec3& q) {
    return std::acos(std::clamp((p - o).normalized().dot((q - o).normalized()), -1.0, 1.0));
  };
  return std::min({angle(a, b, c), angle(b, a, c), angle(c, a, b)});
}

TEST(Tet3dBoundaryImprovement, KeepsTheFacetsSmallestAngle) {
  // Refinement leaves the facets constrained Delaunay, so most flips would lower the
  // smallest angle of their two subfacets: each of those is refused, even with no gain
  // asked; the flips allowed keep it.
  const TestPlc input = l_prism();
  MeshOptions options;
  options.max_volume = input.volume / 300.0;
  RefineState state(input.plc, options);
  refine(state, input);
  FacetEdgeFlip plan;
  std::size_t lowering = 0, allowed = 0;
  for (const auto& [x, y] : facet_edges(state)) {
    const std::uint32_t* facet = nullptr;
    std::vector<std::uint32_t> apexes;
    for (const auto& [key, f] : state.subfaces) {
      const bool has_x = std::find(key.begin(), key.end(), x) != key.end();
      const bool has_y = std::find(key.begin(), key.end(), y) != key.end();
      if (!has_x || !has_y) continue;
      for (const std::uint32_t v : key)
        if (v != x && v != y) apexes.push_back(v);
      facet = &f;
    }
    ASSERT_NE(facet, nullptr);
    if (apexes.size() != 2) continue;
    const TetMesh& mesh = state.mesh;
    const Vec3 &px = mesh.point(x), &py = mesh.point(y), &pc = mesh.point(apexes[0]), &pd = mesh.point(apexes[1]);
    const double before = std::min(smallest_angle(px, py, pc), smallest_angle(px, py, pd));
    const double after = std::min(smallest_angle(pc, pd, px), smallest_angle(pc, pd, py));
    const bool planned = plan_facet_edge_flip(state, x, y, -kInf, kMinSine, plan);
    if (after < before) {
      ++lowering;
      EXPECT_FALSE(planned) << "edge " << x << "-" << y;
    }
    allowed += planned;
  }
  std::printf("l_prism: %zu facet edges whose flip would lower the smallest angle, %zu flips allowed\n", lowering,
              allowed);
  EXPECT_GT(lowering, 0u);
  EXPECT_GT(allowed, 0u);
}

TEST(Tet3dBoundaryImprovement, ImprovementPassFlipsFacetEdgesAndStaysValid) {
  // The pass with a window offers the facet edges of its bad tets to the flip; the mesh
  // stays valid and conforming with the regions' volumes.
  const TestPlc input = two_boxes();
  MeshOptions options;
  options.max_volume = input.volume / 2000.0;
  options.min_dihedral_deg = 25.0;
  options.max_dihedral_deg = 140.0;
  RefineState state(input.plc, options);
  refine(state, input);
  const ImprovementStats stats = improve_slivers(state);
  std::printf("two_boxes: %zu -> %zu tets outside [25, 140], %zu facet edge flips\n", stats.bad_before,
              stats.bad_after, stats.facet_edge_flips);
  EXPECT_GT(stats.facet_edge_flips, 0u);
  expect_valid_state(state, input.volume, input.region_volume, input.name);
}

/// Hull faces with a neighbouring hull face's apex beyond them (check_delaunay's test).
std::size_t reflex_hull_edges(const TetMesh& mesh) {
  std::size_t reflex = 0;
  for (std::uint32_t t = 0; t < mesh.tet_slots(); ++t) {
    if (mesh.is_dead(t) || !mesh.is_infinite(t)) continue;
    const TetRecord& r = mesh.tet(t);
    const int k = mesh.infinite_index(t);
    const auto& o = kFaceVertex[k];
    for (int f = 0; f < 4; ++f) {
      if (f == k) continue;
      const std::uint32_t x = mesh.tet(r.adj[f] >> 2).v[r.adj[f] & 3u];
      reflex += predicates::orient3d(mesh.coords(r.v[o[0]]), mesh.coords(r.v[o[1]]), mesh.coords(r.v[o[2]]),
                                     mesh.coords(x)) == Sign::Positive;
    }
  }
  return reflex;
}

TEST(Tet3dBoundaryImprovement, HullVerticesWithOpenHullFacesMoveAndTheHullStaysConvex) {
  // The L-shaped prism's hull spans its notch: the Steiner vertices on the notch's outer
  // edges have hull faces that are not subfacets. The pass with a window moves some of
  // them along their segments, and no hull edge becomes reflex.
  const TestPlc input = l_prism();
  MeshOptions options;
  options.max_volume = input.volume / 1000.0;
  options.min_dihedral_deg = 25.0;
  options.max_dihedral_deg = 140.0;
  RefineState state(input.plc, options);
  refine(state, input);
  TetMesh& mesh = state.mesh;
  ASSERT_EQ(reflex_hull_edges(mesh), 0u);
  // The Steiner vertices with an open hull face, and where they are.
  std::map<std::uint32_t, Vec3> open;
  for (std::uint32_t t = 0; t < mesh.tet_slots(); ++t) {
    if (mesh.is_dead(t) || !mesh.is_infinite(t)) continue;
    const auto face = mesh.face_vertices({t, static_cast<std::uint8_t>(mesh.infinite_index(t))});
    if (subface_of(state, face[0], face[1], face[2])) continue;
    for (const std::uint32_t v : face)
      if (state.vertices[v].kind == VertexKind::OnSegment || state.vertices[v].kind == VertexKind::OnFacet)
        open[v] = mesh.point(v);
  }
  ASSERT_FALSE(open.empty());
  const ImprovementStats stats = improve_slivers(state);
  std::size_t moved = 0;
  for (const auto& [v, p] : open) moved += mesh.point(v) != p;
  std::printf("l_prism: %zu -> %zu tets outside [25, 140]; %zu of %zu Steiner vertices with an open hull face moved\n",
              stats.bad_before, stats.bad_after, moved, open.size());
  EXPECT_GT(moved, 0u);
  EXPECT_EQ(reflex_hull_edges(mesh), 0u);
  expect_valid_state(state, input.volume, {}, input.name);
}

}  // namespace
}  // namespace delmesh::test
