// Recovery of a missing subfacet by flips of its facet triangulation toward the
// tetrahedralization (see subfacet_flip_recovery.h; notes §2.1.7, §4.2.1, Figure 4.8).
#include "refiners/tet3d/subfacet_flip_recovery.h"

#include <algorithm>
#include <array>
#include <unordered_set>
#include <vector>

#include "refiners/tet3d/boundary_split.h"
#include "toolkit/predicates/predicates.h"

namespace delmesh::tet3d {

namespace {

std::uint64_t directed_key(std::uint32_t x, std::uint32_t y) { return (static_cast<std::uint64_t>(x) << 32) | y; }

/// The facet's missing subfacets joined to `first` (counterclockwise in the facet's
/// projection) across edges that are not segments, and the region's boundary edges
/// directed with the region on their left; false when it has more than kMaxFlipRegion.
bool missing_region(RefineState& state, const FacetTriangulation& tri, const Subface& first,
                    std::vector<Subface>& region, std::vector<std::array<std::uint32_t, 2>>& boundary) {
  region.assign(1, first);
  boundary.clear();
  for (std::size_t i = 0; i < region.size(); ++i) {
    const Subface t = region[i];
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t x = t[k], y = t[(k + 1) % 3];
      if (!tri.is_segment(x, y)) {
        const std::uint32_t w = tri.third_vertex(y, x);
        if (w != ~0u) {
          const Subface across{y, x, w};
          const FaceKey key = sorted_face_key(y, x, w);
          if (std::any_of(region.begin(), region.end(),
                          [&](const Subface& r) { return sorted_face_key(r[0], r[1], r[2]) == key; }))
            continue;
          if (!find_face_ref(state, y, x, w)) {
            if (region.size() == kMaxFlipRegion) return false;
            region.push_back(across);
            continue;
          }
        }
      }
      boundary.push_back({x, y});
    }
  }
  return true;
}

/// Do x, y and w all lie on one input segment (its end points and the vertices splitting
/// it)? Such a triangle is flat but for the rounding of the split points, and lies on the
/// facet's boundary rather than in it.
bool on_one_segment(const RefineState& state, std::uint32_t x, std::uint32_t y, std::uint32_t w) {
  const std::array<std::uint32_t, 3> v{x, y, w};
  std::uint32_t segment = kNone;
  for (const std::uint32_t u : v)
    if (state.vertices[u].kind == VertexKind::OnSegment) segment = state.vertices[u].owner;
  if (segment == kNone) return false;
  const SegmentData& s = state.segments[segment];
  return std::all_of(v.begin(), v.end(), [&](std::uint32_t u) {
    const VertexInfo& info = state.vertices[u];
    return (info.kind == VertexKind::OnSegment && info.owner == segment) || u == s.a || u == s.b;
  });
}

/// Nodes the search for the region's triangulation by tets' faces may visit.
constexpr std::size_t kMaxSearchSteps = 4096;

/// Depth-first search for a triangulation of the region by faces of the tets: from an edge
/// with no triangle on its left yet (first the region's boundary edges, directed with the
/// region on their left), each face (x, y, w) of the tets around it whose apex w is a vertex
/// of the region left of x -> y in the facet's projection (exact orient2d_projected) is
/// tried in turn. Several such faces at one edge are the faces of flat tets lying on the
/// facet between them, and only some choices close up. A choice is dropped when a triangle
/// would overlap one taken (a directed edge with a triangle on its left already), lie
/// across the region's boundary, or exceed the region's triangle count; the search
/// succeeds when every edge has its triangle with as many triangles as the region has.
class TargetSearch {
 public:
  TargetSearch(const RefineState& state, TetMesh& mesh, Axis axis, const std::vector<std::uint32_t>& vertices,
               const std::unordered_set<std::uint64_t>& on_boundary, std::size_t triangles)
      : state_(state), mesh_(mesh), axis_(axis), vertices_(vertices), on_boundary_(on_boundary), triangles_(triangles) {}

  bool run(const std::vector<std::array<std::uint32_t, 2>>& boundary) {
    return extend(std::vector<std::array<std::uint32_t, 2>>(boundary.rbegin(), boundary.rend()));
  }
  const std::vector<Subface>& target() const { return target_; }
  /// The tets around every edge the search looked at.
  const std::vector<std::uint32_t>& around() const { return around_; }

 private:
  bool extend(std::vector<std::array<std::uint32_t, 2>> todo) {
    while (!todo.empty() && covered_.count(directed_key(todo.back()[0], todo.back()[1]))) todo.pop_back();
    if (todo.empty()) return target_.size() == triangles_;
    if (target_.size() == triangles_) return false;
    const auto [x, y] = todo.back();
    todo.pop_back();
    for (const std::uint32_t w : candidates(x, y)) {
      if (++steps_ > kMaxSearchSteps) return false;
      const Subface t{x, y, w};
      std::vector<std::array<std::uint32_t, 2>> next = todo;
      bool fits = true;
      for (int k = 0; k < 3 && fits; ++k) {
        const std::uint32_t u = t[k], v = t[(k + 1) % 3];
        fits = !covered_.count(directed_key(u, v)) && !on_boundary_.count(directed_key(v, u));
        if (!on_boundary_.count(directed_key(u, v))) next.push_back({v, u});
      }
      if (!fits) continue;
      for (int k = 0; k < 3; ++k) covered_.insert(directed_key(t[k], t[(k + 1) % 3]));
      target_.push_back(t);
      if (extend(std::move(next))) return true;
      target_.pop_back();
      for (int k = 0; k < 3; ++k) covered_.erase(directed_key(t[k], t[(k + 1) % 3]));
      if (steps_ > kMaxSearchSteps) return false;
    }
    return false;
  }

  /// The apexes w of the faces (x, y, w) of the tets on the region's side of (x, y).
  std::vector<std::uint32_t> candidates(std::uint32_t x, std::uint32_t y) {
    std::vector<std::uint32_t> out;
    if (!mesh_.tets_around_edge(x, y, ring_tets_, &ring_)) return out;
    around_.insert(around_.end(), ring_tets_.begin(), ring_tets_.end());
    for (const std::uint32_t w : ring_) {
      if (w == kInfiniteVertex || !std::binary_search(vertices_.begin(), vertices_.end(), w)) continue;
      if (std::find(out.begin(), out.end(), w) != out.end() || on_one_segment(state_, x, y, w)) continue;
      if (predicates::orient2d_projected(mesh_.coords(x), mesh_.coords(y), mesh_.coords(w), axis_) == Sign::Positive)
        out.push_back(w);
    }
    return out;
  }

  const RefineState& state_;
  TetMesh& mesh_;
  Axis axis_;
  const std::vector<std::uint32_t>& vertices_;
  const std::unordered_set<std::uint64_t>& on_boundary_;
  std::size_t triangles_;
  std::vector<Subface> target_;
  std::unordered_set<std::uint64_t> covered_;
  std::vector<std::uint32_t> ring_tets_, ring_, around_;
  std::size_t steps_ = 0;
};

}  // namespace

bool recover_subface_by_flips(RefineState& state, std::uint32_t facet, const FaceKey& key) {
  FacetTriangulation& tri = *state.facets[facet];
  Subface first = key;
  if (tri.third_vertex(first[0], first[1]) != first[2]) std::swap(first[1], first[2]);
  if (tri.third_vertex(first[0], first[1]) != first[2]) return false;
  std::vector<Subface> region;
  std::vector<std::array<std::uint32_t, 2>> boundary;
  if (!missing_region(state, tri, first, region, boundary)) return false;
  std::vector<std::uint32_t> vertices;
  for (const Subface& t : region) vertices.insert(vertices.end(), t.begin(), t.end());
  std::sort(vertices.begin(), vertices.end());
  vertices.erase(std::unique(vertices.begin(), vertices.end()), vertices.end());
  std::unordered_set<std::uint64_t> on_boundary;
  for (const auto& [x, y] : boundary) on_boundary.insert(directed_key(x, y));

  // The target: the tets' faces over the region, grown from its boundary edges.
  TargetSearch search(state, state.mesh, tri.axis(), vertices, on_boundary, region.size());
  if (!search.run(boundary)) return false;
  const std::vector<Subface>& target = search.target();
  if (target.size() != region.size()) return false;
  auto change = tri.flip_to_subfaces(target);
  if (!change) return false;
  apply_subface_change(state, facet, change.value());
  // The flat tets under the new subfacets changed sides: the tets around the region's
  // edges are marked again with the step's new tets (remark_new_tets).
  if (state.collect_new_tets) state.new_tets.insert(state.new_tets.end(), search.around().begin(), search.around().end());
  return true;
}

}  // namespace delmesh::tet3d
