// Bulk Delaunay tetrahedralization (see delaunay.h).
#include "toolkit/tetmesh/delaunay.h"

#include <cmath>
#include <string>

#include "toolkit/predicates/predicates.h"
#include "toolkit/tetmesh/tet_bulk.h"
#include "toolkit/tetmesh/tet_insert.h"

namespace delmesh {

namespace {

constexpr double kMaxMagnitude = 1e140;

bool same_position(const Vec3& a, const Vec3& b) {
  return a[0] == b[0] && a[1] == b[1] && a[2] == b[2];
}

bool collinear(const double* a, const double* b, const double* c) {
  return predicates::orient2d_projected(a, b, c, Axis::X) == Sign::Zero &&
         predicates::orient2d_projected(a, b, c, Axis::Y) == Sign::Zero &&
         predicates::orient2d_projected(a, b, c, Axis::Z) == Sign::Zero;
}

// Finds four non-coplanar points among vertices 1..n, scanning in id (= insertion) order;
// returns their positions 0..n-1 or an Error describing the degeneracy.
Expected<std::array<std::size_t, 4>> find_first_tet(const TetMesh& mesh, std::size_t n) {
  auto coords = [&](std::size_t k) { return mesh.coords(static_cast<std::uint32_t>(k + 1)); };
  auto point = [&](std::size_t k) { return mesh.point(static_cast<std::uint32_t>(k + 1)); };
  std::array<std::size_t, 4> pick{0, n, n, n};
  for (std::size_t k = 1; k < n && pick[1] == n; ++k) {
    if (!same_position(point(k), point(0))) pick[1] = k;
  }
  if (pick[1] == n) {
    return make_error(ErrorCode::DegenerateInput,
                      "all " + std::to_string(n) + " points are at the same position");
  }
  for (std::size_t k = 1; k < n && pick[2] == n; ++k) {
    if (!collinear(coords(pick[0]), coords(pick[1]), coords(k))) pick[2] = k;
  }
  if (pick[2] == n) {
    return make_error(ErrorCode::DegenerateInput,
                      "all " + std::to_string(n) +
                          " points are collinear: they have no 3D tetrahedralization");
  }
  for (std::size_t k = 1; k < n && pick[3] == n; ++k) {
    if (predicates::orient3d(coords(pick[0]), coords(pick[1]), coords(pick[2]), coords(k)) !=
        Sign::Zero) {
      pick[3] = k;
    }
  }
  if (pick[3] == n) {
    return make_error(ErrorCode::DegenerateInput,
                      "all " + std::to_string(n) +
                          " points are coplanar: they have no 3D tetrahedralization");
  }
  return pick;
}

// Of each group of coincident points keep the lowest input index: relabel the vertex
// that was inserted if a lower-indexed duplicate exists.
void keep_lowest_duplicate(TetMesh& mesh, std::vector<std::uint32_t>& duplicate_of) {
  const std::size_t n = duplicate_of.size();
  std::vector<std::uint32_t> lowest(n, kNone);  // for each kept point: lowest member
  for (std::uint32_t i = 0; i < n; ++i) {
    const std::uint32_t r = duplicate_of[i];
    if (r != kNone && (lowest[r] == kNone || i < lowest[r])) lowest[r] = i;
  }
  std::vector<std::uint32_t> relabel;  // old vertex id -> new, only when some change
  for (std::uint32_t r = 0; r < n; ++r) {
    if (lowest[r] == kNone || lowest[r] > r) continue;
    if (relabel.empty()) {
      relabel.resize(mesh.num_vertices());
      for (std::uint32_t v = 0; v < relabel.size(); ++v) relabel[v] = v;
    }
    relabel[r + 1] = lowest[r] + 1;
  }
  if (!relabel.empty()) {
    for (auto& rec : mesh.records()) {
      if (rec.v[0] == kNone) continue;
      for (auto& v : rec.v) v = relabel[v];
    }
    for (std::uint32_t v = 1; v < relabel.size(); ++v) {
      if (relabel[v] != v) {
        mesh.set_vertex_tet(relabel[v], mesh.vertex_tet(v));
        mesh.set_vertex_tet(v, kNone);
      }
    }
  }
  for (std::uint32_t i = 0; i < n; ++i) {
    const std::uint32_t r = duplicate_of[i];
    if (r != kNone && lowest[r] < r) duplicate_of[i] = lowest[r];
  }
  for (std::uint32_t r = 0; r < n; ++r) {
    if (lowest[r] == kNone || lowest[r] > r) continue;
    duplicate_of[lowest[r]] = kNone;
    duplicate_of[r] = lowest[r];
  }
}

}  // namespace

Expected<DelaunayResult> delaunay_tetrahedralize(std::span<const Vec3> points,
                                                 const DelaunayOptions& options) {
  if (points.size() >= kNone - 1) {
    return make_error(ErrorCode::InvalidInput, "too many points for 32-bit vertex ids");
  }
  // Room for the infinite vertex that TetMesh puts in front, so the copy is not
  // reallocated once more.
  std::vector<Vec3> copy;
  copy.reserve(points.size() + 1);
  copy.assign(points.begin(), points.end());
  return delaunay_tetrahedralize(std::move(copy), options);
}

Expected<DelaunayResult> delaunay_tetrahedralize(std::vector<Vec3>&& input,
                                                 const DelaunayOptions& options) {
  std::vector<Vec3> points = std::move(input);  // the caller's array is empty from here on
  const std::size_t n = points.size();
  if (n >= kNone - 1) {
    return make_error(ErrorCode::InvalidInput, "too many points for 32-bit vertex ids");
  }
  for (std::size_t i = 0; i < n; ++i) {
    for (int k = 0; k < 3; ++k) {
      const double x = points[i][k];
      if (!std::isfinite(x) || std::abs(x) > kMaxMagnitude) {
        Error e = make_error(ErrorCode::InvalidInput,
                             "point " + std::to_string(i) + " has coordinate " +
                                 std::to_string(x) + " (must be finite, |x| <= 1e140)");
        e.entity_ids.push_back(static_cast<std::uint32_t>(i));
        return e;
      }
    }
  }
  if (n < 4) {
    return make_error(ErrorCode::DegenerateInput,
                      "a tetrahedralization needs at least 4 points, got " + std::to_string(n));
  }

  // Vertices are stored in insertion order while building (vertex k + 1 = input point
  // order[k]): consecutive insertions then touch neighbouring memory. They are perturbed
  // by input index (the perturbation id of vertex k + 1 is order[k] + 1), and renumbered
  // to input order at the end. The mesh takes the caller's point array and permutes it
  // in place, so the points are stored once.
  // (input_id is allocated after the sort, in memory its scratch buffers gave back.)
  std::vector<std::uint32_t> input_id;  // vertex id -> input index + 1
  {
    std::vector<std::uint32_t> order;
    if (options.spatial_sort) {
      order = brio_order(points, options.seed);
    } else {
      order.resize(n);
      for (std::uint32_t i = 0; i < n; ++i) order[i] = i;
    }
    input_id.assign(n + 1, 0);
    for (std::size_t k = 0; k < n; ++k) input_id[k + 1] = order[k] + 1;
  }
  DelaunayResult result{TetMesh(std::move(points)), {}, 0};
  TetMesh& mesh = result.mesh;
  {
    std::vector<std::uint32_t> insertion_id(n + 1);  // input index + 1 -> vertex id
    for (std::uint32_t v = 0; v <= n; ++v) insertion_id[input_id[v]] = v;
    mesh.renumber_vertices(insertion_id);
  }
  mesh.set_perturbation_ids(std::move(input_id));
  // About 6.5 tets per point for uniform random points (fewer when most points are on
  // the hull, but then the hull adds about two infinite tets per hull point): reserving
  // avoids reallocation copies, and reserved pages never touched cost no memory.
  mesh.reserve(n + 1, 7 * n + 64);

  auto first = find_first_tet(mesh, n);
  if (!first) return first.error();
  const auto& pick = *first;
  make_first_tet(mesh, static_cast<std::uint32_t>(pick[0] + 1), static_cast<std::uint32_t>(pick[1] + 1),
                 static_cast<std::uint32_t>(pick[2] + 1), static_cast<std::uint32_t>(pick[3] + 1));

  Cavity cavity;
  cavity.update_vertex_tets = false;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> duplicates;  // (input index, input index)
  for (std::size_t k = 1; k < n; ++k) {
    if (k == pick[1] || k == pick[2] || k == pick[3]) continue;
    const auto v = static_cast<std::uint32_t>(k + 1);
    const InsertResult r = insert_vertex(mesh, v, kNone, cavity);
    if (r.duplicate_of != kNone) {
      duplicates.emplace_back(mesh.perturbation_id(v) - 1, mesh.perturbation_id(r.duplicate_of) - 1);
    }
  }
  cavity = Cavity{};
  mesh.renumber_vertices(mesh.take_perturbation_ids());
  if (!duplicates.empty()) {
    result.duplicate_of.assign(n, kNone);
    for (const auto& [i, existing] : duplicates) result.duplicate_of[i] = existing;
    result.num_duplicates = duplicates.size();
    keep_lowest_duplicate(mesh, result.duplicate_of);
  }
  mesh.compact();
  mesh.rebuild_vertex_tets();
  log(options.log, LogLevel::Info,
      "delaunay: " + std::to_string(n) + " points, " + std::to_string(result.num_duplicates) +
          " duplicates merged, " + std::to_string(mesh.num_finite_tets()) + " tets");
  return result;
}

std::vector<std::array<std::uint32_t, 4>> finite_tets_as_input_indices(const TetMesh& mesh) {
  std::vector<std::array<std::uint32_t, 4>> tets;
  tets.reserve(mesh.num_finite_tets());
  for (std::uint32_t t = 0; t < mesh.tet_slots(); ++t) {
    if (mesh.is_dead(t) || mesh.is_infinite(t)) continue;
    const auto& v = mesh.tet(t).v;
    tets.push_back({v[0] - 1, v[1] - 1, v[2] - 1, v[3] - 1});
  }
  return tets;
}

Expected<TetList> delaunay_tet_list(std::span<const Vec3> points, const DelaunayOptions& options) {
  auto built = delaunay_tetrahedralize(points, options);
  if (!built) return built.error();
  TetList list;
  list.tets = finite_tets_as_input_indices(built->mesh);
  list.duplicate_of = std::move(built->duplicate_of);
  list.num_duplicates = built->num_duplicates;
  return list;
}

}  // namespace delmesh
