// Flips and edge removal (see tet_flips.h).
#include "toolkit/tetmesh/tet_flips.h"

#include <algorithm>
#include <array>
#include <cmath>

#include <Eigen/Geometry>

#include "toolkit/core/error.h"
#include "toolkit/predicates/predicates.h"
#include "toolkit/tetmesh/ring_triangulation.h"

namespace delmesh {

namespace {

using Quad = std::array<std::uint32_t, 4>;

bool positive(const TetMesh& mesh, const Quad& q) {
  for (const std::uint32_t v : q) {
    if (v == kInfiniteVertex) return false;
  }
  return predicates::orient3d(mesh.coords(q[0]), mesh.coords(q[1]), mesh.coords(q[2]),
                              mesh.coords(q[3])) == Sign::Positive;
}

// Replaces the tets `old_tets` by `new_tets` (which fill the same region, positively
// oriented), gluing them to each other and to the tets around the region.
void replace_region(TetMesh& mesh, const std::vector<std::uint32_t>& old_tets,
                    const std::vector<Quad>& new_tets, std::vector<std::uint32_t>* created) {
  const std::uint32_t s = mesh.new_stamp();
  for (const std::uint32_t t : old_tets) mesh.set_stamp(t, s);
  std::vector<std::uint32_t> outside;
  for (const std::uint32_t t : old_tets) {
    for (int f = 0; f < 4; ++f) {
      const std::uint32_t ref = mesh.tet(t).adj[f];
      if (mesh.stamp(ref >> 2) != s) outside.push_back(ref);
    }
  }
  for (const std::uint32_t t : old_tets) mesh.kill_tet(t);
  std::vector<std::uint32_t> made;
  for (const Quad& q : new_tets) made.push_back(mesh.create_tet(q[0], q[1], q[2], q[3]));
  const bool glued = mesh.glue_by_vertices(made, outside);
  DELMESH_CHECK(glued, "flip: new tets do not close up with the surrounding mesh");
  for (const std::uint32_t t : made) {
    for (const std::uint32_t v : mesh.tet(t).v) mesh.set_vertex_tet(v, t);
  }
  if (created) *created = std::move(made);
}

bool ring_is_finite(std::uint32_t a, std::uint32_t b, const std::vector<std::uint32_t>& ring) {
  if (a == kInfiniteVertex || b == kInfiniteVertex) return false;
  for (const std::uint32_t c : ring) {
    if (c == kInfiniteVertex) return false;
  }
  return true;
}

// The two tets of ring triangle (i, j, k), given in cyclic ring order: the ring turns
// counterclockwise seen from b, so (ci, cj, ck, b) and (cj, ci, ck, a) are positive.
void add_triangle_tets(std::uint32_t a, std::uint32_t b, const std::vector<std::uint32_t>& ring,
                       int i, int j, int k, std::vector<Quad>& out) {
  out.push_back({ring[i], ring[j], ring[k], b});
  out.push_back({ring[j], ring[i], ring[k], a});
}

}  // namespace

double tet_shape_quality(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  const double volume = (b - a).cross(c - a).dot(d - a) / 6.0;
  const double sum = (b - a).squaredNorm() + (c - a).squaredNorm() + (d - a).squaredNorm() +
                     (c - b).squaredNorm() + (d - b).squaredNorm() + (d - c).squaredNorm();
  const double lrms = std::sqrt(sum / 6.0);
  if (lrms == 0) return 0;
  return 6.0 * std::sqrt(2.0) * volume / (lrms * lrms * lrms);
}

bool flip23(TetMesh& mesh, FaceRef face, std::vector<std::uint32_t>* created) {
  const std::uint32_t t = face.tet;
  if (t >= mesh.tet_slots() || mesh.is_dead(t) || mesh.is_infinite(t)) return false;
  const std::uint32_t u = mesh.neighbor(t, face.face);
  if (mesh.is_infinite(u)) return false;
  const std::uint32_t e = mesh.opposite_vertex(face);
  std::vector<Quad> fresh;
  for (const std::uint8_t p : kFaceVertex[face.face]) {
    Quad q = mesh.tet(t).v;
    q[p] = e;  // replace one vertex of the shared face by the far apex
    if (!positive(mesh, q)) return false;
    fresh.push_back(q);
  }
  replace_region(mesh, {t, u}, fresh, created);
  return true;
}

bool flip32(TetMesh& mesh, std::uint32_t a, std::uint32_t b, std::vector<std::uint32_t>* created) {
  std::vector<std::uint32_t> tets, ring;
  if (!mesh.tets_around_edge(a, b, tets, &ring) || tets.size() != 3) return false;
  if (!ring_is_finite(a, b, ring)) return false;
  std::vector<Quad> fresh;
  add_triangle_tets(a, b, ring, 0, 1, 2, fresh);
  for (const Quad& q : fresh) {
    if (!positive(mesh, q)) return false;
  }
  replace_region(mesh, tets, fresh, created);
  return true;
}

bool flip44(TetMesh& mesh, std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t e,
            std::vector<std::uint32_t>* created) {
  std::vector<std::uint32_t> tets, ring;
  if (!mesh.tets_around_edge(a, b, tets, &ring) || tets.size() != 4) return false;
  if (!ring_is_finite(a, b, ring)) return false;
  int k = -1;
  for (int i = 0; i < 4; ++i) {
    if ((ring[i] == c && ring[(i + 2) % 4] == e) || (ring[i] == e && ring[(i + 2) % 4] == c)) k = i;
  }
  if (k < 0) return false;
  std::vector<Quad> fresh;
  add_triangle_tets(a, b, ring, k, (k + 1) % 4, (k + 2) % 4, fresh);
  add_triangle_tets(a, b, ring, k, (k + 2) % 4, (k + 3) % 4, fresh);
  for (const Quad& q : fresh) {
    if (!positive(mesh, q)) return false;
  }
  replace_region(mesh, tets, fresh, created);
  return true;
}

bool remove_edge(TetMesh& mesh, std::uint32_t a, std::uint32_t b, double must_exceed,
                 std::vector<std::uint32_t>* created, const TetQualityFn& quality) {
  std::vector<std::uint32_t> tets, ring;
  if (!mesh.tets_around_edge(a, b, tets, &ring)) return false;
  const int m = static_cast<int>(ring.size());
  if (m < 3 || m > 64 || !ring_is_finite(a, b, ring)) return false;

  // Quality of ring triangle (i, j, k): the worse of its two tets, -inf if invalid. The
  // floating-point quality comes first: a triangle at or below must_exceed cannot be part
  // of an accepted triangulation, so its exact orientation tests are skipped.
  constexpr double kInvalid = -std::numeric_limits<double>::infinity();
  auto triangle_quality = [&](int i, int j, int k) {
    const std::array<Quad, 2> q{Quad{ring[i], ring[j], ring[k], b}, Quad{ring[j], ring[i], ring[k], a}};
    double worst = std::numeric_limits<double>::infinity();
    for (const Quad& x : q) {
      const Vec3 &p0 = mesh.point(x[0]), &p1 = mesh.point(x[1]), &p2 = mesh.point(x[2]), &p3 = mesh.point(x[3]);
      worst = std::min(worst, quality ? quality(p0, p1, p2, p3) : tet_shape_quality(p0, p1, p2, p3));
      if (!(worst > must_exceed)) return worst;
    }
    if (!positive(mesh, q[0]) || !positive(mesh, q[1])) return kInvalid;
    return worst;
  };
  std::vector<std::array<int, 3>> triangles;
  if (best_ring_triangulation(m, must_exceed, triangle_quality, triangles) == kInvalid) return false;
  std::vector<Quad> fresh;
  for (const auto& [i, k, j] : triangles) add_triangle_tets(a, b, ring, i, k, j, fresh);
  replace_region(mesh, tets, fresh, created);
  return true;
}

}  // namespace delmesh
