// Facet triangulation in OpenMesh: vertex insertion by walking point location and
// 1-to-3 / 2-to-4 splits, Lawson flips for the constrained Delaunay property (notes
// §2.1.1 Lawson's flip algorithm, §2.1.2 CDTs, §4.2.1 facet maintenance). See the header.
#include "toolkit/facet/facet_triangulation.h"

#include <algorithm>
#include <set>

#include "toolkit/geometry/circumcenter.h"

namespace delmesh {

namespace {

Subface sorted_triple(Subface t) {
  std::sort(t.begin(), t.end());
  return t;
}

/// Cancels faces that an operation both removed and added.
void net_change(SubfaceChange& change) {
  std::multiset<Subface> removed(change.removed.begin(), change.removed.end());
  std::vector<Subface> added;
  for (const auto& f : change.added) {
    const auto it = removed.find(f);
    if (it != removed.end()) {
      removed.erase(it);
    } else {
      added.push_back(f);
    }
  }
  change.removed.assign(removed.begin(), removed.end());
  change.added = std::move(added);
}

/// The six orders of three items (FacetTriangulation::lone_order_).
constexpr std::uint8_t kOrders[6][3] = {{0, 1, 2}, {1, 2, 0}, {2, 0, 1}, {0, 2, 1}, {2, 1, 0}, {1, 0, 2}};

/// Declares the coordinates of a vertex being inserted for the duration of an operation.
class PendingVertex {
 public:
  PendingVertex(FacetMeshPool& pool, std::uint32_t global_id, const Vec3& position) : pool_(pool) {
    pool_.set_pending(global_id, position);
  }
  ~PendingVertex() { pool_.clear_pending(); }
  PendingVertex(const PendingVertex&) = delete;
  PendingVertex& operator=(const PendingVertex&) = delete;

 private:
  FacetMeshPool& pool_;
};

}  // namespace

FacetTriangulation::FacetTriangulation(FacetMeshPool& pool, const Vec3& normal)
    : pool_(&pool),
      normal_(normal),
      facet_(pool.new_facet()),
      axis_(static_cast<Axis>(dominant_axis(normal))) {}

bool FacetTriangulation::has_vertex(std::uint32_t global_id) const {
  if (deferred()) return global_id == lone_[0] || global_id == lone_[1] || global_id == lone_[2];
  return vertex_handle(global_id).is_valid();
}

Subface FacetTriangulation::lone_face() const {
  const auto& order = kOrders[lone_order_];
  return {lone_[order[0]], lone_[order[1]], lone_[order[2]]};
}

Expected<void> FacetTriangulation::assign_lone_triangle(const std::array<std::uint32_t, 3>& vertices,
                                                        const Subface& triangle) {
  DELMESH_CHECK(face_count_ == 0 && !deferred(), "FacetTriangulation::assign called twice");
  for (const std::uint32_t g : vertices) DELMESH_CHECK(!has_vertex(g), "facet vertex added twice");
  DELMESH_CHECK(vertices[0] != vertices[1] && vertices[1] != vertices[2] && vertices[0] != vertices[2],
                "facet vertex added twice");
  for (const std::uint32_t g : triangle)
    if (g != vertices[0] && g != vertices[1] && g != vertices[2])
      return make_error(ErrorCode::InvalidInput,
                        "facet triangle 0 names vertex " + std::to_string(g) + " that the facet lacks");
  // As assign: counterclockwise in projection, the second and third swapped otherwise.
  Subface t = triangle;
  const Sign s = predicates::orient2d_projected(pool_->coords(t[0]), pool_->coords(t[1]), pool_->coords(t[2]), axis_);
  if (s == Sign::Zero) return make_error(ErrorCode::DegenerateInput, "facet triangle 0 is degenerate");
  if (s == Sign::Negative) std::swap(t[1], t[2]);
  for (std::uint8_t k = 0; k < 6; ++k) {
    const auto& order = kOrders[k];
    if (vertices[order[0]] == t[0] && vertices[order[1]] == t[1] && vertices[order[2]] == t[2]) lone_order_ = k;
  }
  lone_ = vertices;
  face_count_ = 1;
  return {};
}

void FacetTriangulation::build_deferred() {
  if (!deferred()) return;
  const std::array<std::uint32_t, 3> vertices = lone_;
  const Subface t = lone_face();
  lone_ = {kNoVertex, kNoVertex, kNoVertex};
  face_count_ = 0;
  for (const std::uint32_t g : vertices) pool_->add_vertex(facet_, g);
  // Every edge of a lone triangle is on the boundary, hence a segment.
  const auto built = assign(std::span<const Subface>(&t, 1), {});
  DELMESH_CHECK(built.has_value(), "a deferred facet triangle could not be built");
}

void FacetTriangulation::add_vertex(std::uint32_t global_id) {
  build_deferred();
  DELMESH_CHECK(!has_vertex(global_id), "facet vertex added twice");
  pool_->add_vertex(facet_, global_id);
}

std::vector<OpenMesh::FaceHandle> FacetTriangulation::face_list() const {
  std::vector<FH> out;
  out.reserve(face_count_);
  for (FH f = first_face_; f.is_valid(); f = pool_->next_face(f)) out.push_back(f);
  return out;
}

std::vector<OpenMesh::EdgeHandle> FacetTriangulation::edge_list() const {
  std::vector<EH> out;
  for (EH e = first_edge_; e.is_valid(); e = pool_->next_edge(e)) out.push_back(e);
  return out;
}

void FacetTriangulation::adopt(Mark before) {
  for (std::size_t i = before.faces; i < mesh().n_faces(); ++i) {
    const FH f = mesh().face_handle(static_cast<unsigned>(i));
    pool_->set_next_face(f, FH());
    if (tail_face_.is_valid()) {
      pool_->set_next_face(tail_face_, f);
    } else {
      first_face_ = f;
    }
    tail_face_ = f;
    ++face_count_;
  }
  for (std::size_t i = before.edges; i < mesh().n_edges(); ++i) {
    const EH e = mesh().edge_handle(static_cast<unsigned>(i));
    pool_->set_next_edge(e, EH());
    pool_->set_segment(e, false);
    if (tail_edge_.is_valid()) {
      pool_->set_next_edge(tail_edge_, e);
    } else {
      first_edge_ = e;
    }
    tail_edge_ = e;
  }
}

Subface FacetTriangulation::face_ids(FH f) const {
  Subface t{};
  int i = 0;
  for (VH v : mesh().fv_range(f)) t[i++] = id(v);
  return t;
}

Expected<void> FacetTriangulation::assign(std::span<const Subface> triangles,
                                          std::span<const std::array<std::uint32_t, 2>> segments) {
  DELMESH_CHECK(face_count_ == 0, "FacetTriangulation::assign called twice");
  for (std::size_t i = 0; i < triangles.size(); ++i) {
    std::array<VH, 3> v;
    for (int k = 0; k < 3; ++k) {
      v[k] = vertex_handle(triangles[i][k]);
      if (!v[k].is_valid())
        return make_error(ErrorCode::InvalidInput, "facet triangle " + std::to_string(i) + " names vertex " +
                                                       std::to_string(triangles[i][k]) + " that the facet lacks");
    }
    const Sign s = predicates::orient2d_projected(coords(v[0]), coords(v[1]), coords(v[2]), axis_);
    if (s == Sign::Zero)
      return make_error(ErrorCode::DegenerateInput, "facet triangle " + std::to_string(i) + " is degenerate");
    if (s == Sign::Negative) std::swap(v[1], v[2]);
    const Mark before = mark();
    const FH added = mesh().add_face(v[0], v[1], v[2]);
    adopt(before);
    if (!added.is_valid())
      return make_error(ErrorCode::NonManifold, "facet triangle " + std::to_string(i) + " makes the facet non-manifold");
  }
  for (const auto& s : segments) {
    const HH h = find_halfedge(s[0], s[1]);
    if (!h.is_valid())
      return make_error(ErrorCode::InvalidInput, "segment (" + std::to_string(s[0]) + ", " + std::to_string(s[1]) +
                                                     ") is not an edge of the facet triangulation");
    pool_->set_segment(mesh().edge_handle(h), true);
  }
  // The facet's outer and hole boundaries are segments whether listed or not.
  for (EH e : edge_list())
    if (mesh().is_boundary(e)) pool_->set_segment(e, true);
  last_face_ = first_face_;
  return {};
}

OpenMesh::HalfedgeHandle FacetTriangulation::find_halfedge(std::uint32_t a, std::uint32_t b) const {
  const VH va = vertex_handle(a);
  if (!va.is_valid()) return HH();
  const VH vb = vertex_handle(b);
  if (!vb.is_valid()) return HH();
  return mesh().find_halfedge(va, vb);
}

bool FacetTriangulation::has_subface(std::uint32_t a, std::uint32_t b, std::uint32_t c) const {
  if (deferred()) return a != b && a != c && b != c && has_vertex(a) && has_vertex(b) && has_vertex(c);
  const HH h = find_halfedge(a, b);
  if (!h.is_valid()) return false;
  for (HH g : {h, mesh().opposite_halfedge_handle(h)}) {
    if (mesh().is_boundary(g)) continue;
    if (id(mesh().to_vertex_handle(mesh().next_halfedge_handle(g))) == c) return true;
  }
  return false;
}

bool FacetTriangulation::is_segment(std::uint32_t a, std::uint32_t b) const {
  if (deferred()) return a != b && has_vertex(a) && has_vertex(b);
  const HH h = find_halfedge(a, b);
  return h.is_valid() && constrained(mesh().edge_handle(h));
}

std::vector<std::array<std::uint32_t, 2>> FacetTriangulation::segments() const {
  std::vector<std::array<std::uint32_t, 2>> out;
  if (deferred()) {
    // add_face's edges, each from the face's vertex to the next.
    const Subface t = lone_face();
    return {{t[0], t[1]}, {t[1], t[2]}, {t[2], t[0]}};
  }
  for (EH e : edge_list())
    if (constrained(e)) {
      const HH h = mesh().halfedge_handle(e, 0);
      out.push_back({id(mesh().from_vertex_handle(h)), id(mesh().to_vertex_handle(h))});
    }
  return out;
}

std::vector<Subface> FacetTriangulation::subfaces() const {
  if (deferred()) return {lone_face()};
  std::vector<Subface> out;
  out.reserve(face_count_);
  for (FH f = first_face_; f.is_valid(); f = pool_->next_face(f)) out.push_back(face_ids(f));
  return out;
}

bool FacetTriangulation::should_flip(EH e) const {
  if (constrained(e) || mesh().is_boundary(e)) return false;
  const HH h0 = mesh().halfedge_handle(e, 0), h1 = mesh().halfedge_handle(e, 1);
  const VH a = mesh().from_vertex_handle(h0), b = mesh().to_vertex_handle(h0);
  const VH c = mesh().to_vertex_handle(mesh().next_halfedge_handle(h0));
  const VH d = mesh().to_vertex_handle(mesh().next_halfedge_handle(h1));
  return predicates::incircle_in_plane(coords(a), coords(b), coords(c), coords(d), axis_, normal_.data()) ==
         Sign::Positive;
}

void FacetTriangulation::record_removed(FH f, SubfaceChange* change) const {
  if (change) change->removed.push_back(sorted_triple(face_ids(f)));
}

void FacetTriangulation::record_added(FH f, SubfaceChange* change) const {
  if (change) change->added.push_back(sorted_triple(face_ids(f)));
}

std::size_t FacetTriangulation::flip_edges(std::vector<EH>& stack, SubfaceChange* change) {
  std::size_t flips = 0;
  while (!stack.empty()) {
    const EH e = stack.back();
    stack.pop_back();
    if (!should_flip(e)) continue;
    const HH h0 = mesh().halfedge_handle(e, 0), h1 = mesh().halfedge_handle(e, 1);
    const FH f0 = mesh().face_handle(h0), f1 = mesh().face_handle(h1);
    // A non-Delaunay edge between two valid triangles has a strictly convex quadrilateral
    // (the metric is an affine image of the Euclidean one), so the flip is always legal.
    DELMESH_CHECK(mesh().is_flip_ok(e), "Delaunay flip of an edge whose flip is topologically invalid");
    record_removed(f0, change);
    record_removed(f1, change);
    const std::array<EH, 4> outer{mesh().edge_handle(mesh().next_halfedge_handle(h0)),
                                  mesh().edge_handle(mesh().prev_halfedge_handle(h0)),
                                  mesh().edge_handle(mesh().next_halfedge_handle(h1)),
                                  mesh().edge_handle(mesh().prev_halfedge_handle(h1))};
    mesh().flip(e);
    record_added(mesh().face_handle(mesh().halfedge_handle(e, 0)), change);
    record_added(mesh().face_handle(mesh().halfedge_handle(e, 1)), change);
    for (EH o : outer) stack.push_back(o);
    ++flips;
  }
  return flips;
}

std::size_t FacetTriangulation::make_delaunay(SubfaceChange* change) {
  if (deferred()) return 0;  // a lone triangle's edges are all segments
  std::vector<EH> stack = edge_list();
  const std::size_t flips = flip_edges(stack, change);
  if (change) net_change(*change);
  return flips;
}


Expected<SubfaceChange> FacetTriangulation::split_edge_at(EH e, VH v, bool delaunay) {
  SubfaceChange change;
  const HH h0 = mesh().halfedge_handle(e, 0);
  const VH a = mesh().from_vertex_handle(h0), b = mesh().to_vertex_handle(h0);
  const bool was_segment = constrained(e);
  for (HH h : {h0, mesh().halfedge_handle(e, 1)})
    if (!mesh().is_boundary(h)) record_removed(mesh().face_handle(h), &change);
  const Mark before = mark();
  mesh().split(e, v);
  adopt(before);
  std::vector<EH> stack;
  for (HH h : mesh().voh_range(v)) {
    const EH spoke = mesh().edge_handle(h);
    const VH w = mesh().to_vertex_handle(h);
    pool_->set_segment(spoke, was_segment && (w == a || w == b));
    if (!mesh().is_boundary(h)) {
      const FH f = mesh().face_handle(h);
      record_added(f, &change);
      stack.push_back(mesh().edge_handle(mesh().next_halfedge_handle(h)));
      last_face_ = f;
    }
  }
  if (delaunay) flip_edges(stack, &change);
  net_change(change);
  return change;
}

Expected<SubfaceChange> FacetTriangulation::insert_vertex(std::uint32_t global_id, const Vec3& position,
                                                          std::uint32_t near_vertex, bool delaunay) {
  if (face_count_ == 0) return make_error(ErrorCode::InvalidInput, "insertion into an empty facet");
  build_deferred();
  DELMESH_CHECK(!has_vertex(global_id), "facet vertex added twice");
  // Visibility walk from a triangle at near_vertex, else from the last face touched;
  // rotating the starting edge each step keeps it from cycling in constrained
  // (non-Delaunay) triangulations, and a full scan backs it up. Where it starts changes
  // only which of the triangles holding p on an edge it stops at, and the insertion
  // splits that edge either way.
  FH f = last_face_.is_valid() ? last_face_ : first_face_;
  if (const VH near = vertex_handle(near_vertex); near.is_valid()) {
    for (FH g : mesh().vf_range(near)) {
      f = g;
      break;
    }
  }
  const PendingVertex pending(*pool_, global_id, position);
  const VH v = pool_->add_vertex(facet_, global_id);
  const double* p = coords(v);
  // Returns the first edge (starting `rotation` edges after the face's first) that has p
  // strictly on its outer side, or invalid when p is in the closed face; counts the
  // edges p lies on.
  auto classify = [&](FH face, std::size_t rotation, HH& on_edge, int& zeros) {
    zeros = 0;
    HH h = mesh().halfedge_handle(face);
    for (std::size_t r = 0; r < rotation % 3; ++r) h = mesh().next_halfedge_handle(h);
    for (int k = 0; k < 3; ++k, h = mesh().next_halfedge_handle(h)) {
      const Sign s = predicates::orient2d_projected(coords(mesh().from_vertex_handle(h)),
                                                    coords(mesh().to_vertex_handle(h)), p, axis_);
      if (s == Sign::Negative) return h;
      if (s == Sign::Zero) {
        ++zeros;
        on_edge = h;
      }
    }
    return HH();
  };
  HH on_edge;
  int zeros = 0;
  bool found = false;
  const std::size_t limit = 4 * std::size_t{face_count_} + 16;
  for (std::size_t step = 0; step < limit; ++step) {
    const HH exit = classify(f, step, on_edge, zeros);
    if (!exit.is_valid()) {
      found = true;
      break;
    }
    const HH across = mesh().opposite_halfedge_handle(exit);
    if (mesh().is_boundary(across)) break;  // left the domain through its boundary
    f = mesh().face_handle(across);
  }
  if (!found) {
    for (FH g = first_face_; g.is_valid(); g = pool_->next_face(g)) {
      if (!classify(g, 0, on_edge, zeros).is_valid()) {
        f = g;
        found = true;
        break;
      }
    }
  }
  if (!found || zeros >= 2) {
    // The refused vertex stays in the mesh isolated: no face, edge or id lookup reaches it.
    pool_->unlink_vertex(v);
    return make_error(found ? ErrorCode::DuplicateVertex : ErrorCode::InvalidInput,
                      "facet vertex " + std::to_string(global_id) +
                          (found ? " coincides with an existing vertex in the facet's projection"
                                 : " lies outside the facet"));
  }
  if (zeros == 1) return split_edge_at(mesh().edge_handle(on_edge), v, delaunay);
  SubfaceChange change;
  record_removed(f, &change);
  const Mark before = mark();
  mesh().split(f, v);
  adopt(before);
  std::vector<EH> stack;
  for (HH h : mesh().voh_range(v)) {
    pool_->set_segment(mesh().edge_handle(h), false);
    const FH g = mesh().face_handle(h);
    record_added(g, &change);
    stack.push_back(mesh().edge_handle(mesh().next_halfedge_handle(h)));
    last_face_ = g;
  }
  if (delaunay) flip_edges(stack, &change);
  net_change(change);
  return change;
}

Expected<SubfaceChange> FacetTriangulation::split_segment(std::uint32_t a, std::uint32_t b, std::uint32_t v,
                                                          const Vec3& position, bool delaunay) {
  build_deferred();
  const HH h = find_halfedge(a, b);
  if (!h.is_valid() || !constrained(mesh().edge_handle(h)))
    return make_error(ErrorCode::InvalidInput, "(" + std::to_string(a) + ", " + std::to_string(b) +
                                                   ") is not a segment of the facet");
  DELMESH_CHECK(!has_vertex(v), "facet vertex added twice");
  const PendingVertex pending(*pool_, v, position);
  return split_edge_at(mesh().edge_handle(h), pool_->add_vertex(facet_, v), delaunay);
}

std::optional<Subface> FacetTriangulation::locate(const double* p, std::uint32_t near_vertex) const {
  if (face_count_ == 0) return std::nullopt;
  if (deferred()) {
    const Subface t = lone_face();
    for (int k = 0; k < 3; ++k)
      if (predicates::orient2d_projected(pool_->coords(t[k]), pool_->coords(t[(k + 1) % 3]), p, axis_) ==
          Sign::Negative)
        return std::nullopt;
    return t;
  }
  FH f = first_face_;
  if (const VH near = vertex_handle(near_vertex); near.is_valid()) {
    for (FH g : mesh().vf_range(near)) {
      f = g;
      break;
    }
  }
  // Returns an edge of `face` with p strictly outside, starting `rotation` edges in.
  auto exit_edge = [&](FH face, std::size_t rotation) {
    HH h = mesh().halfedge_handle(face);
    for (std::size_t r = 0; r < rotation % 3; ++r) h = mesh().next_halfedge_handle(h);
    for (int k = 0; k < 3; ++k, h = mesh().next_halfedge_handle(h)) {
      if (predicates::orient2d_projected(coords(mesh().from_vertex_handle(h)), coords(mesh().to_vertex_handle(h)), p,
                                         axis_) == Sign::Negative)
        return h;
    }
    return HH();
  };
  const std::size_t limit = 4 * std::size_t{face_count_} + 16;
  for (std::size_t step = 0; step < limit; ++step) {
    const HH exit = exit_edge(f, step);
    if (!exit.is_valid()) return face_ids(f);
    const HH across = mesh().opposite_halfedge_handle(exit);
    // Leaving through the boundary: p projects outside the facet (or, for a nonconvex
    // facet, beyond a notch; the caller then falls back to the subfacet it knows).
    if (mesh().is_boundary(across)) return std::nullopt;
    f = mesh().face_handle(across);
  }
  for (FH g = first_face_; g.is_valid(); g = pool_->next_face(g))
    if (!exit_edge(g, 0).is_valid()) return face_ids(g);
  return std::nullopt;
}

std::uint32_t FacetTriangulation::third_vertex(std::uint32_t a, std::uint32_t b) const {
  if (deferred()) {
    const Subface t = lone_face();
    for (int k = 0; k < 3; ++k)
      if (t[k] == a && t[(k + 1) % 3] == b) return t[(k + 2) % 3];
    return ~0u;
  }
  const HH h = find_halfedge(a, b);
  if (!h.is_valid() || mesh().is_boundary(h)) return ~0u;
  return id(mesh().to_vertex_handle(mesh().next_halfedge_handle(h)));
}

Expected<SubfaceChange> FacetTriangulation::flip_edge(std::uint32_t a, std::uint32_t b) {
  build_deferred();
  const HH h0 = find_halfedge(a, b);
  if (!h0.is_valid()) return make_error(ErrorCode::InvalidInput, "flip_edge: not an edge");
  const EH e = mesh().edge_handle(h0);
  if (constrained(e) || mesh().is_boundary(e))
    return make_error(ErrorCode::InvalidInput, "flip_edge: constrained or boundary edge");
  const HH h1 = mesh().opposite_halfedge_handle(h0);
  const VH va = mesh().from_vertex_handle(h0), vb = mesh().to_vertex_handle(h0);
  const VH c = mesh().to_vertex_handle(mesh().next_halfedge_handle(h0));
  const VH d = mesh().to_vertex_handle(mesh().next_halfedge_handle(h1));
  // The new triangles (c, d, b)... must both be counterclockwise: the quad is convex.
  if (predicates::orient2d_projected(coords(d), coords(c), coords(va), axis_) != Sign::Positive ||
      predicates::orient2d_projected(coords(c), coords(d), coords(vb), axis_) != Sign::Positive)
    return make_error(ErrorCode::InvalidInput, "flip_edge: quadrilateral not strictly convex");
  SubfaceChange change;
  record_removed(mesh().face_handle(h0), &change);
  record_removed(mesh().face_handle(h1), &change);
  mesh().flip(e);
  record_added(mesh().face_handle(mesh().halfedge_handle(e, 0)), &change);
  record_added(mesh().face_handle(mesh().halfedge_handle(e, 1)), &change);
  last_face_ = mesh().face_handle(mesh().halfedge_handle(e, 0));
  return change;
}

bool FacetTriangulation::can_move_vertex(std::uint32_t global_id, const Vec3& position) const {
  if (deferred()) {
    if (!has_vertex(global_id)) return false;
    std::array<const double*, 3> p{};
    const Subface t = lone_face();
    for (int k = 0; k < 3; ++k) p[k] = t[k] == global_id ? position.data() : pool_->coords(t[k]);
    return predicates::orient2d_projected(p[0], p[1], p[2], axis_) == Sign::Positive;
  }
  const VH moved = vertex_handle(global_id);
  if (!moved.is_valid()) return false;
  for (FH f : mesh().vf_range(moved)) {
    std::array<const double*, 3> p{};
    int i = 0;
    for (VH v : mesh().fv_range(f)) p[i++] = v == moved ? position.data() : coords(v);
    if (predicates::orient2d_projected(p[0], p[1], p[2], axis_) != Sign::Positive) return false;
  }
  return true;
}

std::vector<std::string> FacetTriangulation::check() const {
  std::vector<std::string> issues;
  if (deferred()) {
    const Subface t = lone_face();
    if (predicates::orient2d_projected(pool_->coords(t[0]), pool_->coords(t[1]), pool_->coords(t[2]), axis_) !=
        Sign::Positive)
      issues.push_back("subface (" + std::to_string(t[0]) + ", " + std::to_string(t[1]) + ", " +
                       std::to_string(t[2]) + ") is not counterclockwise in projection");
    return issues;
  }
  for (FH f = first_face_; f.is_valid(); f = pool_->next_face(f)) {
    std::array<const double*, 3> p{};
    int i = 0;
    for (VH v : mesh().fv_range(f)) p[i++] = coords(v);
    if (predicates::orient2d_projected(p[0], p[1], p[2], axis_) != Sign::Positive) {
      const Subface t = face_ids(f);
      issues.push_back("subface (" + std::to_string(t[0]) + ", " + std::to_string(t[1]) + ", " +
                       std::to_string(t[2]) + ") is not counterclockwise in projection");
    }
  }
  for (EH e : edge_list()) {
    if (should_flip(e)) {
      const HH h = mesh().halfedge_handle(e, 0);
      issues.push_back("edge (" + std::to_string(id(mesh().from_vertex_handle(h))) + ", " +
                       std::to_string(id(mesh().to_vertex_handle(h))) + ") is not locally Delaunay");
    }
  }
  return issues;
}

}  // namespace delmesh
