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

}  // namespace

FacetTriangulation::FacetTriangulation(const Vec3& normal)
    : normal_(normal), axis_(static_cast<Axis>(dominant_axis(normal))) {
  mesh_.add_property(global_id_);
  mesh_.add_property(segment_);
}

void FacetTriangulation::add_vertex(std::uint32_t global_id, const Vec3& position) {
  DELMESH_CHECK(!handle_.count(global_id), "facet vertex added twice");
  const VH v = mesh_.add_vertex(FacetMesh::Point(position.x(), position.y(), position.z()));
  mesh_.property(global_id_, v) = global_id;
  handle_.emplace(global_id, v);
}

Subface FacetTriangulation::face_ids(FH f) const {
  Subface t{};
  int i = 0;
  for (VH v : mesh_.fv_range(f)) t[i++] = id(v);
  return t;
}

Expected<void> FacetTriangulation::assign(std::span<const Subface> triangles,
                                          std::span<const std::array<std::uint32_t, 2>> segments) {
  DELMESH_CHECK(mesh_.n_faces() == 0, "FacetTriangulation::assign called twice");
  for (std::size_t i = 0; i < triangles.size(); ++i) {
    std::array<VH, 3> v;
    for (int k = 0; k < 3; ++k) {
      const auto it = handle_.find(triangles[i][k]);
      if (it == handle_.end())
        return make_error(ErrorCode::InvalidInput, "facet triangle " + std::to_string(i) + " names vertex " +
                                                       std::to_string(triangles[i][k]) + " that the facet lacks");
      v[k] = it->second;
    }
    const Sign s = predicates::orient2d_projected(coords(v[0]), coords(v[1]), coords(v[2]), axis_);
    if (s == Sign::Zero)
      return make_error(ErrorCode::DegenerateInput, "facet triangle " + std::to_string(i) + " is degenerate");
    if (s == Sign::Negative) std::swap(v[1], v[2]);
    if (!mesh_.add_face(v[0], v[1], v[2]).is_valid())
      return make_error(ErrorCode::NonManifold, "facet triangle " + std::to_string(i) + " makes the facet non-manifold");
  }
  for (const auto& s : segments) {
    const HH h = find_halfedge(s[0], s[1]);
    if (!h.is_valid())
      return make_error(ErrorCode::InvalidInput, "segment (" + std::to_string(s[0]) + ", " + std::to_string(s[1]) +
                                                     ") is not an edge of the facet triangulation");
    mesh_.property(segment_, mesh_.edge_handle(h)) = true;
  }
  // The facet's outer and hole boundaries are segments whether listed or not.
  for (EH e : mesh_.edges())
    if (mesh_.is_boundary(e)) mesh_.property(segment_, e) = true;
  last_face_ = mesh_.n_faces() ? mesh_.face_handle(0) : FH();
  return {};
}

OpenMesh::HalfedgeHandle FacetTriangulation::find_halfedge(std::uint32_t a, std::uint32_t b) const {
  const auto ia = handle_.find(a), ib = handle_.find(b);
  if (ia == handle_.end() || ib == handle_.end()) return HH();
  return mesh_.find_halfedge(ia->second, ib->second);
}

bool FacetTriangulation::has_subface(std::uint32_t a, std::uint32_t b, std::uint32_t c) const {
  const HH h = find_halfedge(a, b);
  if (!h.is_valid()) return false;
  for (HH g : {h, mesh_.opposite_halfedge_handle(h)}) {
    if (mesh_.is_boundary(g)) continue;
    if (id(mesh_.to_vertex_handle(mesh_.next_halfedge_handle(g))) == c) return true;
  }
  return false;
}

bool FacetTriangulation::is_segment(std::uint32_t a, std::uint32_t b) const {
  const HH h = find_halfedge(a, b);
  return h.is_valid() && constrained(mesh_.edge_handle(h));
}

std::vector<std::array<std::uint32_t, 2>> FacetTriangulation::segments() const {
  std::vector<std::array<std::uint32_t, 2>> out;
  for (EH e : mesh_.edges())
    if (constrained(e)) {
      const HH h = mesh_.halfedge_handle(e, 0);
      out.push_back({id(mesh_.from_vertex_handle(h)), id(mesh_.to_vertex_handle(h))});
    }
  return out;
}

std::vector<Subface> FacetTriangulation::subfaces() const {
  std::vector<Subface> out;
  out.reserve(mesh_.n_faces());
  for (FH f : mesh_.faces()) out.push_back(face_ids(f));
  return out;
}

bool FacetTriangulation::should_flip(EH e) const {
  if (constrained(e) || mesh_.is_boundary(e)) return false;
  const HH h0 = mesh_.halfedge_handle(e, 0), h1 = mesh_.halfedge_handle(e, 1);
  const VH a = mesh_.from_vertex_handle(h0), b = mesh_.to_vertex_handle(h0);
  const VH c = mesh_.to_vertex_handle(mesh_.next_halfedge_handle(h0));
  const VH d = mesh_.to_vertex_handle(mesh_.next_halfedge_handle(h1));
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
    const HH h0 = mesh_.halfedge_handle(e, 0), h1 = mesh_.halfedge_handle(e, 1);
    const FH f0 = mesh_.face_handle(h0), f1 = mesh_.face_handle(h1);
    // A non-Delaunay edge between two valid triangles has a strictly convex quadrilateral
    // (the metric is an affine image of the Euclidean one), so the flip is always legal.
    DELMESH_CHECK(mesh_.is_flip_ok(e), "Delaunay flip of an edge whose flip is topologically invalid");
    record_removed(f0, change);
    record_removed(f1, change);
    const std::array<EH, 4> outer{mesh_.edge_handle(mesh_.next_halfedge_handle(h0)),
                                  mesh_.edge_handle(mesh_.prev_halfedge_handle(h0)),
                                  mesh_.edge_handle(mesh_.next_halfedge_handle(h1)),
                                  mesh_.edge_handle(mesh_.prev_halfedge_handle(h1))};
    mesh_.flip(e);
    record_added(mesh_.face_handle(mesh_.halfedge_handle(e, 0)), change);
    record_added(mesh_.face_handle(mesh_.halfedge_handle(e, 1)), change);
    for (EH o : outer) stack.push_back(o);
    ++flips;
  }
  return flips;
}

std::size_t FacetTriangulation::make_delaunay(SubfaceChange* change) {
  std::vector<EH> stack(mesh_.edges().begin(), mesh_.edges().end());
  const std::size_t flips = flip_edges(stack, change);
  if (change) net_change(*change);
  return flips;
}


Expected<SubfaceChange> FacetTriangulation::split_edge_at(EH e, VH v) {
  SubfaceChange change;
  const HH h0 = mesh_.halfedge_handle(e, 0);
  const VH a = mesh_.from_vertex_handle(h0), b = mesh_.to_vertex_handle(h0);
  const bool was_segment = constrained(e);
  for (HH h : {h0, mesh_.halfedge_handle(e, 1)})
    if (!mesh_.is_boundary(h)) record_removed(mesh_.face_handle(h), &change);
  mesh_.split(e, v);
  std::vector<EH> stack;
  for (HH h : mesh_.voh_range(v)) {
    const EH spoke = mesh_.edge_handle(h);
    const VH w = mesh_.to_vertex_handle(h);
    mesh_.property(segment_, spoke) = was_segment && (w == a || w == b);
    if (!mesh_.is_boundary(h)) {
      const FH f = mesh_.face_handle(h);
      record_added(f, &change);
      stack.push_back(mesh_.edge_handle(mesh_.next_halfedge_handle(h)));
      last_face_ = f;
    }
  }
  flip_edges(stack, &change);
  net_change(change);
  return change;
}

Expected<SubfaceChange> FacetTriangulation::insert_vertex(std::uint32_t global_id, const Vec3& position) {
  if (mesh_.n_faces() == 0) return make_error(ErrorCode::InvalidInput, "insertion into an empty facet");
  add_vertex(global_id, position);
  const VH v = handle_.at(global_id);
  const double* p = coords(v);
  // Visibility walk from the last face touched; rotating the starting edge each step keeps
  // it from cycling in constrained (non-Delaunay) triangulations, and a full scan backs it
  // up.
  FH f = last_face_.is_valid() ? last_face_ : mesh_.face_handle(0);
  // Returns the first edge (starting `rotation` edges after the face's first) that has p
  // strictly on its outer side, or invalid when p is in the closed face; counts the
  // edges p lies on.
  auto classify = [&](FH face, std::size_t rotation, HH& on_edge, int& zeros) {
    zeros = 0;
    HH h = mesh_.halfedge_handle(face);
    for (std::size_t r = 0; r < rotation % 3; ++r) h = mesh_.next_halfedge_handle(h);
    for (int k = 0; k < 3; ++k, h = mesh_.next_halfedge_handle(h)) {
      const Sign s = predicates::orient2d_projected(coords(mesh_.from_vertex_handle(h)),
                                                    coords(mesh_.to_vertex_handle(h)), p, axis_);
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
  const std::size_t limit = 4 * mesh_.n_faces() + 16;
  for (std::size_t step = 0; step < limit; ++step) {
    const HH exit = classify(f, step, on_edge, zeros);
    if (!exit.is_valid()) {
      found = true;
      break;
    }
    const HH across = mesh_.opposite_halfedge_handle(exit);
    if (mesh_.is_boundary(across)) break;  // left the domain through its boundary
    f = mesh_.face_handle(across);
  }
  if (!found) {
    for (FH g : mesh_.faces()) {
      if (!classify(g, 0, on_edge, zeros).is_valid()) {
        f = g;
        found = true;
        break;
      }
    }
  }
  if (!found || zeros >= 2) {
    // The refused vertex stays in the mesh isolated: no face, edge or id lookup reaches it.
    handle_.erase(global_id);
    return make_error(found ? ErrorCode::DuplicateVertex : ErrorCode::InvalidInput,
                      "facet vertex " + std::to_string(global_id) +
                          (found ? " coincides with an existing vertex in the facet's projection"
                                 : " lies outside the facet"));
  }
  if (zeros == 1) return split_edge_at(mesh_.edge_handle(on_edge), v);
  SubfaceChange change;
  record_removed(f, &change);
  mesh_.split(f, v);
  std::vector<EH> stack;
  for (HH h : mesh_.voh_range(v)) {
    mesh_.property(segment_, mesh_.edge_handle(h)) = false;
    const FH g = mesh_.face_handle(h);
    record_added(g, &change);
    stack.push_back(mesh_.edge_handle(mesh_.next_halfedge_handle(h)));
    last_face_ = g;
  }
  flip_edges(stack, &change);
  net_change(change);
  return change;
}

Expected<SubfaceChange> FacetTriangulation::split_segment(std::uint32_t a, std::uint32_t b, std::uint32_t v,
                                                          const Vec3& position) {
  const HH h = find_halfedge(a, b);
  if (!h.is_valid() || !constrained(mesh_.edge_handle(h)))
    return make_error(ErrorCode::InvalidInput, "(" + std::to_string(a) + ", " + std::to_string(b) +
                                                   ") is not a segment of the facet");
  add_vertex(v, position);
  return split_edge_at(mesh_.edge_handle(h), handle_.at(v));
}

std::optional<Subface> FacetTriangulation::locate(const double* p, std::uint32_t near_vertex) const {
  if (mesh_.n_faces() == 0) return std::nullopt;
  FH f = mesh_.face_handle(0);
  if (const auto it = handle_.find(near_vertex); it != handle_.end()) {
    for (FH g : mesh_.vf_range(it->second)) {
      f = g;
      break;
    }
  }
  // Returns an edge of `face` with p strictly outside, starting `rotation` edges in.
  auto exit_edge = [&](FH face, std::size_t rotation) {
    HH h = mesh_.halfedge_handle(face);
    for (std::size_t r = 0; r < rotation % 3; ++r) h = mesh_.next_halfedge_handle(h);
    for (int k = 0; k < 3; ++k, h = mesh_.next_halfedge_handle(h)) {
      if (predicates::orient2d_projected(coords(mesh_.from_vertex_handle(h)), coords(mesh_.to_vertex_handle(h)), p,
                                         axis_) == Sign::Negative)
        return h;
    }
    return HH();
  };
  const std::size_t limit = 4 * mesh_.n_faces() + 16;
  for (std::size_t step = 0; step < limit; ++step) {
    const HH exit = exit_edge(f, step);
    if (!exit.is_valid()) return face_ids(f);
    const HH across = mesh_.opposite_halfedge_handle(exit);
    // Leaving through the boundary: p projects outside the facet (or, for a nonconvex
    // facet, beyond a notch; the caller then falls back to the subfacet it knows).
    if (mesh_.is_boundary(across)) return std::nullopt;
    f = mesh_.face_handle(across);
  }
  for (FH g : mesh_.faces())
    if (!exit_edge(g, 0).is_valid()) return face_ids(g);
  return std::nullopt;
}

std::uint32_t FacetTriangulation::third_vertex(std::uint32_t a, std::uint32_t b) const {
  const HH h = find_halfedge(a, b);
  if (!h.is_valid() || mesh_.is_boundary(h)) return ~0u;
  return id(mesh_.to_vertex_handle(mesh_.next_halfedge_handle(h)));
}

Expected<SubfaceChange> FacetTriangulation::flip_edge(std::uint32_t a, std::uint32_t b) {
  const HH h0 = find_halfedge(a, b);
  if (!h0.is_valid()) return make_error(ErrorCode::InvalidInput, "flip_edge: not an edge");
  const EH e = mesh_.edge_handle(h0);
  if (constrained(e) || mesh_.is_boundary(e))
    return make_error(ErrorCode::InvalidInput, "flip_edge: constrained or boundary edge");
  const HH h1 = mesh_.opposite_halfedge_handle(h0);
  const VH va = mesh_.from_vertex_handle(h0), vb = mesh_.to_vertex_handle(h0);
  const VH c = mesh_.to_vertex_handle(mesh_.next_halfedge_handle(h0));
  const VH d = mesh_.to_vertex_handle(mesh_.next_halfedge_handle(h1));
  // The new triangles (c, d, b)... must both be counterclockwise: the quad is convex.
  if (predicates::orient2d_projected(coords(d), coords(c), coords(va), axis_) != Sign::Positive ||
      predicates::orient2d_projected(coords(c), coords(d), coords(vb), axis_) != Sign::Positive)
    return make_error(ErrorCode::InvalidInput, "flip_edge: quadrilateral not strictly convex");
  SubfaceChange change;
  record_removed(mesh_.face_handle(h0), &change);
  record_removed(mesh_.face_handle(h1), &change);
  mesh_.flip(e);
  record_added(mesh_.face_handle(mesh_.halfedge_handle(e, 0)), &change);
  record_added(mesh_.face_handle(mesh_.halfedge_handle(e, 1)), &change);
  last_face_ = mesh_.face_handle(mesh_.halfedge_handle(e, 0));
  return change;
}

bool FacetTriangulation::can_move_vertex(std::uint32_t global_id, const Vec3& position) const {
  const auto it = handle_.find(global_id);
  if (it == handle_.end()) return false;
  const VH moved = it->second;
  for (FH f : mesh_.vf_range(moved)) {
    std::array<const double*, 3> p{};
    int i = 0;
    for (VH v : mesh_.fv_range(f)) p[i++] = v == moved ? position.data() : coords(v);
    if (predicates::orient2d_projected(p[0], p[1], p[2], axis_) != Sign::Positive) return false;
  }
  return true;
}

void FacetTriangulation::move_vertex(std::uint32_t global_id, const Vec3& position) {
  const auto it = handle_.find(global_id);
  if (it == handle_.end()) return;
  mesh_.set_point(it->second, FacetMesh::Point(position.x(), position.y(), position.z()));
}

std::vector<std::string> FacetTriangulation::check() const {
  std::vector<std::string> issues;
  for (FH f : mesh_.faces()) {
    std::array<const double*, 3> p{};
    int i = 0;
    for (VH v : mesh_.fv_range(f)) p[i++] = coords(v);
    if (predicates::orient2d_projected(p[0], p[1], p[2], axis_) != Sign::Positive) {
      const Subface t = face_ids(f);
      issues.push_back("subface (" + std::to_string(t[0]) + ", " + std::to_string(t[1]) + ", " +
                       std::to_string(t[2]) + ") is not counterclockwise in projection");
    }
  }
  for (EH e : mesh_.edges()) {
    if (should_flip(e)) {
      const HH h = mesh_.halfedge_handle(e, 0);
      issues.push_back("edge (" + std::to_string(id(mesh_.from_vertex_handle(h))) + ", " +
                       std::to_string(id(mesh_.to_vertex_handle(h))) + ") is not locally Delaunay");
    }
  }
  return issues;
}

}  // namespace delmesh
