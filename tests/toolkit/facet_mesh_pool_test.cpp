// FacetMeshPool: several facet triangulations in one OpenMesh mesh, their vertex copies
// of shared global vertices, per-facet element lists, and coordinates read by id.
#include <gtest/gtest.h>

#include <random>

#include "toolkit/facet/facet_mesh_pool.h"
#include "toolkit/facet/facet_triangulation.h"

namespace delmesh {
namespace {

const std::vector<std::array<std::uint32_t, 2>> kNoSegments;

TEST(FacetMeshPool, VertexCopiesAreFoundPerFacetAndUnlinked) {
  std::vector<Vec3> points(10, Vec3::Zero());
  FacetMeshPool pool(points);
  const std::uint32_t f0 = pool.new_facet(), f1 = pool.new_facet(), f2 = pool.new_facet();
  EXPECT_EQ(pool.facet_count(), 3u);
  const auto a = pool.add_vertex(f0, 7);
  const auto b = pool.add_vertex(f1, 7);
  const auto c = pool.add_vertex(f2, 7);
  const auto d = pool.add_vertex(f1, 3);
  EXPECT_EQ(pool.find_vertex(f0, 7), a);
  EXPECT_EQ(pool.find_vertex(f1, 7), b);
  EXPECT_EQ(pool.find_vertex(f2, 7), c);
  EXPECT_EQ(pool.find_vertex(f1, 3), d);
  EXPECT_FALSE(pool.find_vertex(f0, 3).is_valid());
  EXPECT_FALSE(pool.find_vertex(f0, 1000).is_valid());  // beyond every id seen
  EXPECT_EQ(pool.global_id(b), 7u);
  EXPECT_EQ(pool.facet_of(c), f2);
  // Unlinking the middle of the chain (f1's copy) keeps the others reachable.
  pool.unlink_vertex(b);
  EXPECT_FALSE(pool.find_vertex(f1, 7).is_valid());
  EXPECT_EQ(pool.find_vertex(f0, 7), a);
  EXPECT_EQ(pool.find_vertex(f2, 7), c);
  const auto e = pool.add_vertex(f1, 7);
  EXPECT_EQ(pool.find_vertex(f1, 7), e);
  EXPECT_NE(e, b);
}

TEST(FacetMeshPool, CoordinatesComeFromTheArrayOrThePendingVertex) {
  std::vector<Vec3> points{Vec3(1, 2, 3)};
  FacetMeshPool pool(points);
  EXPECT_EQ(pool.coords(0)[2], 3.0);
  pool.set_pending(1, Vec3(4, 5, 6));
  EXPECT_EQ(pool.coords(1)[0], 4.0);
  EXPECT_EQ(pool.coords(0)[0], 1.0);
  pool.clear_pending();
  points.push_back(Vec3(7, 8, 9));  // the pool follows the vector as it grows
  EXPECT_EQ(pool.coords(1)[0], 7.0);
}

/// Two squares in perpendicular planes sharing the edge (0, 1), as two facets of a PLC.
struct TwoFacets {
  std::vector<Vec3> points{{0, 0, 0}, {4, 0, 0}, {4, 4, 0}, {0, 4, 0}, {4, 0, 4}, {0, 0, 4}};
  FacetMeshPool pool{points};
  FacetTriangulation floor{pool, Vec3(0, 0, 1)};
  FacetTriangulation wall{pool, Vec3(0, 1, 0)};
  TwoFacets() {
    for (std::uint32_t v : {0u, 1u, 2u, 3u}) floor.add_vertex(v);
    for (std::uint32_t v : {0u, 1u, 4u, 5u}) wall.add_vertex(v);
    const std::vector<Subface> floor_tris{{0, 1, 2}, {0, 2, 3}}, wall_tris{{0, 1, 4}, {0, 4, 5}};
    EXPECT_TRUE(floor.assign(floor_tris, kNoSegments));
    EXPECT_TRUE(wall.assign(wall_tris, kNoSegments));
  }
};

TEST(FacetMeshPool, FacetsSharingVerticesKeepSeparateTriangulations) {
  TwoFacets t;
  EXPECT_NE(t.floor.facet_id(), t.wall.facet_id());
  EXPECT_TRUE(t.floor.has_vertex(0) && t.wall.has_vertex(0));
  EXPECT_FALSE(t.floor.has_vertex(4));
  EXPECT_FALSE(t.wall.has_vertex(2));
  EXPECT_TRUE(t.floor.is_segment(0, 1));  // boundary of both facets
  EXPECT_TRUE(t.wall.is_segment(0, 1));
  // Splitting the shared segment in both facets, as 3D refinement does.
  t.points.push_back(Vec3(2, 0, 0));
  ASSERT_TRUE(t.floor.split_segment(0, 1, 6, t.points[6]));
  ASSERT_TRUE(t.wall.split_segment(0, 1, 6, t.points[6]));
  EXPECT_EQ(t.floor.subface_count(), 3u);
  EXPECT_EQ(t.wall.subface_count(), 3u);
  // Interior insertions in one facet leave the other untouched.
  const auto wall_before = t.wall.subfaces();
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(0.05, 3.95);
  for (int i = 0; i < 50; ++i) {
    const std::uint32_t id = static_cast<std::uint32_t>(t.points.size());
    t.points.push_back(Vec3(u(rng), u(rng), 0));
    ASSERT_TRUE(t.floor.insert_vertex(id, t.points.back()));
  }
  EXPECT_EQ(t.wall.subfaces(), wall_before);
  EXPECT_EQ(t.floor.subface_count(), 3u + 2u * 50u);
  EXPECT_EQ(t.floor.subfaces().size(), t.floor.subface_count());
  EXPECT_TRUE(t.floor.check().empty());
  EXPECT_TRUE(t.wall.check().empty());
  EXPECT_EQ(t.floor.segments().size(), 5u);
  EXPECT_EQ(t.wall.segments().size(), 5u);
  for (const Subface& f : t.wall.subfaces())
    for (const std::uint32_t v : f) EXPECT_TRUE(v == 0 || v == 1 || v == 4 || v == 5 || v == 6);
}

TEST(FacetMeshPool, RefusedInsertionLeavesTheIdFreeForTheNextVertex) {
  TwoFacets t;
  const std::uint32_t id = static_cast<std::uint32_t>(t.points.size());
  // Outside the floor: refused before the core would have added the point.
  ASSERT_FALSE(t.floor.insert_vertex(id, Vec3(5, 5, 0)));
  EXPECT_FALSE(t.floor.has_vertex(id));
  // The core then gives the id to another point, which the floor accepts.
  t.points.push_back(Vec3(1, 2, 0));
  ASSERT_TRUE(t.floor.insert_vertex(id, t.points.back()));
  EXPECT_TRUE(t.floor.has_vertex(id));
  EXPECT_TRUE(t.floor.check().empty());
  EXPECT_EQ(t.floor.subface_count(), 4u);
}

TEST(FacetMeshPool, AFacetEnumeratesItsSubfacesAsItWouldAlone) {
  // The same insertions into a facet alone in its pool and into a facet that shares its
  // pool with another, interleaved with that other's insertions: the same subfaces in
  // the same order (the order the result extraction writes them in).
  auto run = [](bool interleave) {
    TwoFacets t;
    std::mt19937_64 rng(11), other(12);
    std::uniform_real_distribution<double> u(0.05, 3.95);
    for (int i = 0; i < 40; ++i) {
      std::uint32_t id = static_cast<std::uint32_t>(t.points.size());
      t.points.push_back(Vec3(u(rng), u(rng), 0));
      EXPECT_TRUE(t.floor.insert_vertex(id, t.points.back()));
      if (interleave) {
        id = static_cast<std::uint32_t>(t.points.size());
        t.points.push_back(Vec3(u(other), 0, u(other)));
        EXPECT_TRUE(t.wall.insert_vertex(id, t.points.back()));
      }
    }
    std::vector<Subface> out = t.floor.subfaces();
    // Ids differ between the runs (the wall takes every other one): compare by position.
    std::vector<std::array<double, 6>> coords;
    for (const Subface& f : out)
      coords.push_back({t.points[f[0]].x(), t.points[f[0]].y(), t.points[f[1]].x(), t.points[f[1]].y(),
                        t.points[f[2]].x(), t.points[f[2]].y()});
    return coords;
  };
  EXPECT_EQ(run(false), run(true));
}

}  // namespace
}  // namespace delmesh
