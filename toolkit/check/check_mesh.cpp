// check_mesh (see check_mesh.h): one sorted array of the tets' faces gives the complex checks and
// the interior faces for the Delaunay test (freed before the facet checks: the check runs
// on every result of refinement on the CCDT, so its arrays add to that run's peak
// memory); each PLC facet gets a frame (three
// non-collinear vertices, a projection axis, its loops classified as holes or not by the
// facet's hole points) used by the plane, inside, area and volume checks; PLC segments are
// walked along mesh edges with exact collinearity and betweenness tests.
#include "toolkit/check/check_mesh.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <sstream>
#include <utility>

#include "toolkit/predicates/predicates.h"
#include "toolkit/quality/tet_quality.h"

namespace delmesh {

const char* to_string(MeshCheckKind kind) {
  switch (kind) {
    case MeshCheckKind::BadIndex: return "BadIndex";
    case MeshCheckKind::InvertedTet: return "InvertedTet";
    case MeshCheckKind::FlatTet: return "FlatTet";
    case MeshCheckKind::NonManifoldFace: return "NonManifoldFace";
    case MeshCheckKind::FaceOrientation: return "FaceOrientation";
    case MeshCheckKind::UnlistedBoundaryFace: return "UnlistedBoundaryFace";
    case MeshCheckKind::MissingBoundaryFace: return "MissingBoundaryFace";
    case MeshCheckKind::DuplicateBoundaryFace: return "DuplicateBoundaryFace";
    case MeshCheckKind::WrongMarker: return "WrongMarker";
    case MeshCheckKind::FaceOffFacet: return "FaceOffFacet";
    case MeshCheckKind::FacetNotCovered: return "FacetNotCovered";
    case MeshCheckKind::MissingSegment: return "MissingSegment";
    case MeshCheckKind::NotDelaunay: return "NotDelaunay";
    case MeshCheckKind::VolumeMismatch: return "VolumeMismatch";
  }
  return "?";
}

namespace {

constexpr std::uint32_t kNoTet = ~0u;
constexpr std::uint32_t kNoFacet = ~0u;

// Outward faces of a positively oriented tet (v0 v1 v2 v3), face i opposite vertex i:
//
//          v3
//         /|\        face 0 = (v1 v2 v3)    face 2 = (v0 v1 v3)
//        / | \       face 1 = (v0 v3 v2)    face 3 = (v0 v2 v1)
//      v0--|--v2     each seen from outside is counterclockwise
//        \ | /
//         \|/
//          v1
constexpr int kFace[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};

/// Is (x, y, z) an even permutation of its sorted order (same orientation as the key)?
bool even_order(std::uint32_t x, std::uint32_t y, std::uint32_t z) {
  if (x < y && x < z) return y < z;
  if (y < x && y < z) return z < x;
  return x < y;
}

struct FaceUse {
  std::array<std::uint32_t, 2> tet{kNoTet, kNoTet};
  std::array<std::uint8_t, 2> local{0, 0};
  std::array<bool, 2> even{false, false};
  std::uint32_t count = 0;
};

enum class Location { Outside, Inside, Boundary };

using Point2 = std::array<double, 2>;

/// Exact point-in-polygon by crossing parity along the ray +x, with exact boundary test.
/// An edge matters only when p lies in its bounding box (the boundary test) or between
/// its endpoints' y and not right of both (the crossing test: an edge left of p cannot
/// cross the ray); the others are passed over without orient2d.
Location locate(const Point2& p, const std::vector<Point2>& loop) {
  bool inside = false;
  for (std::size_t i = 0, n = loop.size(); i < n; ++i) {
    const Point2& u = loop[i];
    const Point2& v = loop[(i + 1) % n];
    const bool straddles = (u[1] > p[1]) != (v[1] > p[1]);
    const bool in_box = std::min(u[0], v[0]) <= p[0] && p[0] <= std::max(u[0], v[0]) &&
                        std::min(u[1], v[1]) <= p[1] && p[1] <= std::max(u[1], v[1]);
    if (!in_box && (!straddles || std::max(u[0], v[0]) < p[0])) continue;
    const Sign o = predicates::orient2d(u.data(), v.data(), p.data());
    if (o == Sign::Zero && in_box) return Location::Boundary;
    if (straddles) {
      const Sign side = v[1] > u[1] ? o : -o;
      if (side == Sign::Positive) inside = !inside;
    }
  }
  return inside ? Location::Inside : Location::Outside;
}

bool collinear(const Vec3& a, const Vec3& b, const Vec3& c) {
  for (Axis axis : {Axis::X, Axis::Y, Axis::Z}) {
    if (predicates::orient2d_projected(a.data(), b.data(), c.data(), axis) != Sign::Zero) return false;
  }
  return true;
}

Point2 project(const Vec3& p, Axis axis) {
  return predicates::project_onto_axis_plane(p.data(), axis);
}

struct Loop {
  std::vector<Point2> points;
  /// Bounding box of the points: a point outside it is outside the loop.
  Point2 lo{0.0, 0.0}, hi{0.0, 0.0};
  Vec3 newell = Vec3::Zero();  ///< twice the vector area
  bool hole = false;
  int weight = 0;              ///< +1 / -1 / 0: how the loop's area enters the facet's area
};

/// A PLC facet prepared for geometric tests.
struct FacetFrame {
  bool valid = false;
  std::uint32_t a = 0, b = 0, c = 0;  ///< three non-collinear facet vertices
  Axis axis = Axis::Z;
  Vec3 unit_normal = Vec3::Zero();
  std::vector<Loop> loops;
  Vec3 vector_area = Vec3::Zero();  ///< oriented along unit_normal
  double area = 0.0;
  double perimeter = 0.0;  ///< total length of the facet's polygon edges

  /// Innermost loop containing p (nullopt if none); boundary counts as inside.
  std::optional<std::size_t> innermost(const Point2& p, bool* on_boundary) const {
    std::optional<std::size_t> best;
    for (std::size_t i = 0; i < loops.size(); ++i) {
      const Loop& loop = loops[i];
      if (p[0] < loop.lo[0] || p[0] > loop.hi[0] || p[1] < loop.lo[1] || p[1] > loop.hi[1]) continue;
      const Location where = locate(p, loop.points);
      if (where == Location::Outside) continue;
      if (where == Location::Boundary && on_boundary) *on_boundary = true;
      if (!best || loop.newell.norm() < loops[*best].newell.norm()) best = i;
    }
    return best;
  }

  bool contains(const Point2& p) const {
    bool on_boundary = false;
    const auto loop = innermost(p, &on_boundary);
    return on_boundary || (loop && !loops[*loop].hole);
  }
};

class Checker {
 public:
  Checker(const TetraMesh& mesh, const Plc& plc, std::span<const std::uint32_t> face_facets,
          const CheckMeshOptions& options)
      : mesh_(mesh), plc_(plc), face_facets_(face_facets), options_(options) {}

  std::vector<MeshCheckIssue> run() {
    if (!check_indices()) return std::move(issues_);
    check_orientation();
    check_complex();
    set_tolerance();
    if (use_facets_) {
      build_frames();
      check_boundary_faces_in_facets();
    }
    check_segments();
    if (use_facets_ && options_.check_volume && !full()) check_volume();
    return std::move(issues_);
  }

 private:
  bool full() const { return issues_.size() >= options_.max_issues; }

  void add(MeshCheckKind kind, std::vector<std::uint32_t> ids, const std::string& message) {
    if (full()) return;
    issues_.push_back(MeshCheckIssue{kind, std::move(ids), message});
  }

  const Vec3& point(std::uint32_t v) const { return mesh_.points[v]; }
  bool domain_tet(std::uint32_t t) const { return mesh_.region_of(t) != -1; }

  bool check_indices() {
    const std::size_t n = mesh_.points.size();
    bool ok = true;
    if (!mesh_.tet_regions.empty() && mesh_.tet_regions.size() != mesh_.tets.size()) {
      add(MeshCheckKind::BadIndex, {}, "tet_regions has " + std::to_string(mesh_.tet_regions.size()) +
                                           " entries for " + std::to_string(mesh_.tets.size()) + " tets");
      ok = false;
    }
    if (mesh_.boundary_markers.size() != mesh_.boundary_faces.size()) {
      add(MeshCheckKind::BadIndex, {}, "boundary_markers has " + std::to_string(mesh_.boundary_markers.size()) +
                                           " entries for " + std::to_string(mesh_.boundary_faces.size()) +
                                           " boundary faces");
      ok = false;
    }
    for (std::uint32_t t = 0; t < mesh_.tets.size(); ++t) {
      const auto& v = mesh_.tets[t];
      const bool in_range = std::all_of(v.begin(), v.end(), [n](std::uint32_t x) { return x < n; });
      const bool distinct = v[0] != v[1] && v[0] != v[2] && v[0] != v[3] && v[1] != v[2] && v[1] != v[3] &&
                            v[2] != v[3];
      if (!in_range || !distinct) {
        add(MeshCheckKind::BadIndex, {t}, "tet " + std::to_string(t) +
                                              (in_range ? " repeats a vertex" : " has a vertex id out of range"));
        ok = false;
      }
    }
    for (std::uint32_t f = 0; f < mesh_.boundary_faces.size(); ++f) {
      const auto& v = mesh_.boundary_faces[f];
      if (v[0] >= n || v[1] >= n || v[2] >= n || v[0] == v[1] || v[1] == v[2] || v[0] == v[2]) {
        add(MeshCheckKind::BadIndex, {f}, "boundary face " + std::to_string(f) + " has a bad vertex id");
        ok = false;
      }
    }
    use_facets_ = !face_facets_.empty();
    if (use_facets_ && face_facets_.size() != mesh_.boundary_faces.size()) {
      add(MeshCheckKind::BadIndex, {}, "boundary_face_facets has " + std::to_string(face_facets_.size()) +
                                           " entries for " + std::to_string(mesh_.boundary_faces.size()) +
                                           " boundary faces");
      ok = false;
    }
    for (std::uint32_t f = 0; use_facets_ && f < face_facets_.size(); ++f) {
      if (face_facets_[f] >= plc_.facets.size()) {
        add(MeshCheckKind::BadIndex, {f, face_facets_[f]},
            "boundary face " + std::to_string(f) + " names facet " + std::to_string(face_facets_[f]) +
                " of a PLC with " + std::to_string(plc_.facets.size()));
        ok = false;
      }
    }
    for (const auto& s : plc_.segments) {
      if (s.a >= plc_.points.size() || s.b >= plc_.points.size()) {
        add(MeshCheckKind::BadIndex, {s.a, s.b}, "PLC segment with a vertex id out of range");
        ok = false;
      }
    }
    for (std::uint32_t f = 0; f < plc_.facets.size(); ++f) {
      for (const auto& polygon : plc_.facets[f].polygons) {
        for (std::uint32_t v : polygon) {
          if (v >= plc_.points.size()) {
            add(MeshCheckKind::BadIndex, {f}, "PLC facet " + std::to_string(f) + " has a vertex id out of range");
            ok = false;
          }
        }
      }
    }
    if (plc_.points.size() > n) {
      add(MeshCheckKind::BadIndex, {}, "the mesh has fewer points than the PLC");
      ok = false;
    }
    return ok;
  }

  void check_orientation() {
    positive_.assign(mesh_.tets.size(), false);
    for (std::uint32_t t = 0; t < mesh_.tets.size(); ++t) {
      const auto& v = mesh_.tets[t];
      const Sign s = predicates::orient3d(point(v[0]).data(), point(v[1]).data(), point(v[2]).data(),
                                          point(v[3]).data());
      positive_[t] = s == Sign::Positive;
      if (s == Sign::Negative) add(MeshCheckKind::InvertedTet, {t}, "tet " + std::to_string(t) + " is inverted");
      if (s == Sign::Zero) add(MeshCheckKind::FlatTet, {t}, "tet " + std::to_string(t) + " is flat");
    }
  }

  std::string face_text(const FaceKey& k) const {
    return "(" + std::to_string(k[0]) + " " + std::to_string(k[1]) + " " + std::to_string(k[2]) + ")";
  }

  /// The tets' faces as a sorted array (no hashing: sorted, then binary searches). Sorted
  /// in two steps: a counting sort on the smallest vertex id (check_indices has checked
  /// every id against the point count), then each run of faces with the same smallest
  /// vertex on the rest of the key and the tet, some 12 to 30 faces per run instead of
  /// one sort of all of them. A slot holds the key's two larger vertices, the tet, the
  /// tet's face index and the face's orientation (16 bytes): the smallest vertex is its
  /// run's. The faces of a key are consecutive slots, so the array serves the lookups as
  /// it is, without a second array of distinct faces; it and the listed faces are freed
  /// at the end, after the one answer the volume check needs from them is kept
  /// (separates_domain_).
  void check_complex() {
    const std::size_t n = mesh_.points.size();
    run_start_.assign(n + 1, 0);
    for (const auto& v : mesh_.tets)
      for (const auto& face : kFace) ++run_start_[std::min({v[face[0]], v[face[1]], v[face[2]]}) + 1];
    for (std::size_t v = 0; v < n; ++v) run_start_[v + 1] += run_start_[v];
    slots_.resize(run_start_[n]);
    {
      std::vector<std::uint32_t> cursor(run_start_.begin(), run_start_.end() - 1);
      for (std::uint32_t t = 0; t < mesh_.tets.size(); ++t) {
        const auto& v = mesh_.tets[t];
        for (std::uint8_t i = 0; i < 4; ++i) {
          const std::uint32_t x = v[kFace[i][0]], y = v[kFace[i][1]], z = v[kFace[i][2]];
          const FaceKey key = face_key(x, y, z);
          slots_[cursor[key[0]]++] = FaceSlot{key[1], key[2], t, i, even_order(x, y, z)};
        }
      }
    }
    // (key, tet) is unique: the tets' vertices are distinct (check_indices), so a tet
    // has a face once.
    const auto by_key = [](const FaceSlot& l, const FaceSlot& r) {
      if (l.y != r.y) return l.y < r.y;
      if (l.z != r.z) return l.z < r.z;
      return l.tet < r.tet;
    };
    for (std::size_t v = 0; v < n; ++v)
      std::sort(slots_.begin() + run_start_[v], slots_.begin() + run_start_[v + 1], by_key);
    listed_.reserve(mesh_.boundary_faces.size());
    for (std::uint32_t f = 0; f < mesh_.boundary_faces.size(); ++f) {
      const auto& v = mesh_.boundary_faces[f];
      listed_.emplace_back(face_key(v[0], v[1], v[2]), f);
    }
    std::sort(listed_.begin(), listed_.end());
    for (std::size_t i = 1; i < listed_.size(); ++i) {
      std::size_t first = i - 1;
      while (first > 0 && listed_[first - 1].first == listed_[i].first) --first;
      if (listed_[first].first != listed_[i].first) continue;
      add(MeshCheckKind::DuplicateBoundaryFace, {listed_[first].second, listed_[i].second},
          "boundary faces " + std::to_string(listed_[first].second) + " and " + std::to_string(listed_[i].second) +
              " are the same triangle " + face_text(listed_[i].first));
    }
    separates_domain_.assign(mesh_.boundary_faces.size(), false);
    for (std::uint32_t f = 0; f < mesh_.boundary_faces.size(); ++f) {
      const auto& v = mesh_.boundary_faces[f];
      const FaceKey key = face_key(v[0], v[1], v[2]);
      const auto use = find_face(key);
      if (!use) {
        add(MeshCheckKind::MissingBoundaryFace, {f},
            "boundary face " + std::to_string(f) + " " + face_text(key) + " is not a face of any tet");
        continue;
      }
      separates_domain_[f] = domain_tet(use->tet[0]) != (use->count == 2 && domain_tet(use->tet[1]));
    }
    for (std::uint32_t x = 0; x < n && !full(); ++x) {
      for (std::uint32_t i = run_start_[x], j; i < run_start_[x + 1] && !full(); i = j) {
        j = i + 1;
        while (j < run_start_[x + 1] && slots_[j].y == slots_[i].y && slots_[j].z == slots_[i].z) ++j;
        check_face({x, slots_[i].y, slots_[i].z}, face_use(i, j));
      }
    }
    release(slots_);
    release(run_start_);
    release(listed_);
    release(positive_);
  }

  template <class T>
  static void release(T& x) {
    x = T();
  }

  /// The use of the face whose slots are [i, j).
  FaceUse face_use(std::uint32_t i, std::uint32_t j) const {
    FaceUse use;
    use.count = j - i;
    for (std::uint32_t k = 0; k < 2 && i + k < j; ++k) {
      use.tet[k] = slots_[i + k].tet;
      use.local[k] = slots_[i + k].local;
      use.even[k] = slots_[i + k].even;
    }
    return use;
  }

  std::optional<FaceUse> find_face(const FaceKey& key) const {
    const auto first = slots_.begin() + run_start_[key[0]], last = slots_.begin() + run_start_[key[0] + 1];
    const auto it = std::lower_bound(first, last, key, [](const FaceSlot& slot, const FaceKey& k) {
      return slot.y != k[1] ? slot.y < k[1] : slot.z < k[2];
    });
    if (it == last || it->y != key[1] || it->z != key[2]) return std::nullopt;
    auto end = it;
    while (end != last && end->y == key[1] && end->z == key[2]) ++end;
    return face_use(static_cast<std::uint32_t>(it - slots_.begin()), static_cast<std::uint32_t>(end - slots_.begin()));
  }

  /// Index of the first listed boundary face with this key.
  std::optional<std::uint32_t> find_listed(const FaceKey& key) const {
    const auto it = std::lower_bound(listed_.begin(), listed_.end(), std::make_pair(key, std::uint32_t{0}));
    if (it == listed_.end() || it->first != key) return std::nullopt;
    return it->second;
  }

  void check_face(const FaceKey& key, const FaceUse& use) {
    if (use.count > 2) {
      add(MeshCheckKind::NonManifoldFace, {key[0], key[1], key[2]},
          "face " + face_text(key) + " is shared by " + std::to_string(use.count) + " tets");
      return;
    }
    if (use.count == 2 && use.even[0] == use.even[1]) {
      add(MeshCheckKind::FaceOrientation, {use.tet[0], use.tet[1]},
          "tets " + std::to_string(use.tet[0]) + " and " + std::to_string(use.tet[1]) + " have face " +
              face_text(key) + " in the same orientation (overlap)");
    }
    // The domain boundary: faces with exactly one domain tet (region != -1) beside them.
    int domain_side = -1;
    const bool d0 = domain_tet(use.tet[0]);
    const bool d1 = use.count == 2 && domain_tet(use.tet[1]);
    if (d0 != d1) domain_side = d0 ? 0 : 1;
    // Looked up only where it is read.
    const bool needs_listed = domain_side >= 0 || (use.count == 2 && options_.check_delaunay);
    const auto listed = needs_listed ? find_listed(key) : std::nullopt;
    if (domain_side >= 0) {
      const std::uint32_t t = use.tet[domain_side];
      if (!listed) {
        add(MeshCheckKind::UnlistedBoundaryFace, {t, key[0], key[1], key[2]},
            "face " + face_text(key) + " of tet " + std::to_string(t) +
                " is on the domain boundary but not a listed boundary face");
      } else {
        const auto& f = mesh_.boundary_faces[*listed];
        if (even_order(f[0], f[1], f[2]) != use.even[domain_side]) {
          add(MeshCheckKind::FaceOrientation, {*listed},
              "boundary face " + std::to_string(*listed) + " " + face_text(key) +
                  " faces into the domain");
        }
      }
    }
    if (use.count == 2 && !listed && options_.check_delaunay && positive_[use.tet[0]] &&
        positive_[use.tet[1]]) {
      const auto& a = mesh_.tets[use.tet[0]];
      const std::uint32_t apex = mesh_.tets[use.tet[1]][use.local[1]];
      if (predicates::insphere(point(a[0]).data(), point(a[1]).data(), point(a[2]).data(), point(a[3]).data(),
                               point(apex).data()) == Sign::Positive) {
        add(MeshCheckKind::NotDelaunay, {use.tet[0], use.tet[1]},
            "face " + face_text(key) + " between tets " + std::to_string(use.tet[0]) + " and " +
                std::to_string(use.tet[1]) + " is not locally Delaunay and lies on no facet");
      }
    }
  }

  void set_tolerance() {
    if (mesh_.points.empty()) return;
    Vec3 lo = mesh_.points[0], hi = mesh_.points[0];
    for (const Vec3& p : mesh_.points) {
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
    center_ = 0.5 * (lo + hi);
    tolerance_ = options_.roundoff_tolerance * (hi - lo).norm();
  }

  /// Exactly on the plane, or within the roundoff tolerance of it. The tolerance is asked
  /// first: a vertex on the plane up to roundoff passes there, and the exact test of such a
  /// point is the predicate's slowest case (the answer is the same in either order).
  bool on_plane(const FacetFrame& frame, const Vec3& p) const {
    const Vec3& a = plc_.points[frame.a];
    if (std::abs(frame.unit_normal.dot(p - a)) <= tolerance_) return true;
    return predicates::orient3d(a.data(), plc_.points[frame.b].data(), plc_.points[frame.c].data(), p.data()) ==
           Sign::Zero;
  }

  bool on_line(const Vec3& a, const Vec3& b, const Vec3& p) const {
    if (collinear(a, b, p)) return true;
    const double length = (b - a).norm();
    return length > 0 && (p - a).cross(b - a).norm() / length <= tolerance_;
  }

  FacetFrame make_frame(const Plc::Facet& facet) const {
    FacetFrame frame;
    std::vector<std::uint32_t> vertices;
    for (const auto& polygon : facet.polygons) vertices.insert(vertices.end(), polygon.begin(), polygon.end());
    if (vertices.empty()) return frame;
    frame.a = vertices[0];
    const auto b = std::find_if(vertices.begin(), vertices.end(),
                                [&](std::uint32_t v) { return plc_.points[v] != plc_.points[frame.a]; });
    if (b == vertices.end()) return frame;
    frame.b = *b;
    const Vec3 &pa = plc_.points[frame.a], &pb = plc_.points[frame.b];
    // a and b themselves are collinear with a and b: passed over without the predicate,
    // whose exact zero is its slowest case.
    const auto c = std::find_if(vertices.begin(), vertices.end(), [&](std::uint32_t v) {
      return v != frame.a && v != frame.b && !collinear(pa, pb, plc_.points[v]);
    });
    if (c == vertices.end()) return frame;
    frame.c = *c;
    const Vec3& pc = plc_.points[frame.c];
    const Vec3 n = (pb - pa).cross(pc - pa);
    frame.unit_normal = n.normalized();
    // Projection axis: the normal's dominant component, as long as the projection of
    // a, b, c is exactly non-degenerate (it always is for the dominant one in practice).
    std::array<Axis, 3> order{Axis::X, Axis::Y, Axis::Z};
    std::sort(order.begin(), order.end(), [&](Axis l, Axis r) {
      return std::abs(n[static_cast<int>(l)]) > std::abs(n[static_cast<int>(r)]);
    });
    frame.axis = order[0];
    for (Axis axis : order) {
      if (predicates::orient2d_projected(pa.data(), pb.data(), pc.data(), axis) != Sign::Zero) {
        frame.axis = axis;
        break;
      }
    }
    for (const auto& polygon : facet.polygons) {
      if (polygon.size() < 3) continue;
      Loop loop;
      for (std::size_t i = 0; i < polygon.size(); ++i) {
        const Vec3 &p = plc_.points[polygon[i]], &q = plc_.points[polygon[(i + 1) % polygon.size()]];
        loop.points.push_back(project(p, frame.axis));
        loop.newell += (p - center_).cross(q - center_);
        frame.perimeter += (q - p).norm();
      }
      loop.lo = loop.hi = loop.points.front();
      for (const Point2& x : loop.points) {
        loop.lo = {std::min(loop.lo[0], x[0]), std::min(loop.lo[1], x[1])};
        loop.hi = {std::max(loop.hi[0], x[0]), std::max(loop.hi[1], x[1])};
      }
      frame.loops.push_back(std::move(loop));
    }
    classify_loops(facet, frame);
    frame.valid = true;
    return frame;
  }

  /// Marks hole loops (innermost loop around a facet hole point) and weighs each loop's
  /// area by the change of "inside the facet" across it: +1 outer boundaries and islands,
  /// -1 holes, 0 constraint loops inside the facet.
  void classify_loops(const Plc::Facet& facet, FacetFrame& frame) const {
    for (const Vec3& hole : facet.holes) {
      if (const auto loop = frame.innermost(project(hole, frame.axis), nullptr)) frame.loops[*loop].hole = true;
    }
    for (std::size_t i = 0; i < frame.loops.size(); ++i) {
      std::optional<std::size_t> parent;
      for (std::size_t j = 0; j < frame.loops.size(); ++j) {
        if (j == i || !loop_inside(frame.loops[i], frame.loops[j])) continue;
        if (!parent || frame.loops[j].newell.norm() < frame.loops[*parent].newell.norm()) parent = j;
      }
      const int inside = frame.loops[i].hole ? 0 : 1;
      const int outside = parent && !frame.loops[*parent].hole ? 1 : 0;
      frame.loops[i].weight = inside - outside;
      const Loop& loop = frame.loops[i];
      const double sign = loop.newell.dot(frame.unit_normal) >= 0 ? 1.0 : -1.0;
      frame.vector_area += 0.5 * loop.weight * sign * loop.newell;
    }
    frame.area = frame.vector_area.norm();
  }

  /// Is loop `inner` inside loop `outer`? Decided by its first vertex not on `outer`.
  static bool loop_inside(const Loop& inner, const Loop& outer) {
    for (const Point2& p : inner.points) {
      const Location where = locate(p, outer.points);
      if (where != Location::Boundary) return where == Location::Inside;
    }
    return false;
  }

  void build_frames() {
    frames_.reserve(plc_.facets.size());
    for (std::uint32_t f = 0; f < plc_.facets.size(); ++f) {
      frames_.push_back(make_frame(plc_.facets[f]));
      if (!frames_.back().valid) {
        add(MeshCheckKind::FacetNotCovered, {f}, "PLC facet " + std::to_string(f) + " is degenerate (no three "
                                                 "non-collinear vertices)");
      }
    }
  }

  void check_boundary_faces_in_facets() {
    std::vector<double> covered(plc_.facets.size(), 0.0);
    // The facet each vertex was last found on the plane of: a vertex lies on some six
    // boundary faces of its facet, and the exact test of a point on the plane is the
    // predicate's slowest case.
    std::vector<std::uint32_t> on_plane_of(mesh_.points.size(), kNoFacet);
    for (std::uint32_t f = 0; f < mesh_.boundary_faces.size(); ++f) {
      const std::uint32_t facet = face_facets_[f];
      const auto& v = mesh_.boundary_faces[f];
      if (mesh_.boundary_markers[f] != plc_.facets[facet].marker) {
        add(MeshCheckKind::WrongMarker, {f, facet},
            "boundary face " + std::to_string(f) + " has marker " + std::to_string(mesh_.boundary_markers[f]) +
                ", its facet " + std::to_string(facet) + " has " + std::to_string(plc_.facets[facet].marker));
      }
      const FacetFrame& frame = frames_[facet];
      if (!frame.valid) continue;
      const Vec3 &p = point(v[0]), &q = point(v[1]), &r = point(v[2]);
      covered[facet] += 0.5 * (q - p).cross(r - p).norm();
      std::string problem;
      for (std::uint32_t x : v) {
        if (on_plane_of[x] == facet) continue;
        if (on_plane(frame, point(x)))
          on_plane_of[x] = facet;
        else
          problem = "vertex " + std::to_string(x) + " is off the facet's plane";
      }
      const Vec3 centroid = (p + q + r) / 3.0;
      if (problem.empty() && !frame.contains(project(centroid, frame.axis))) {
        problem = "it lies outside the facet polygon";
      }
      if (!problem.empty()) {
        add(MeshCheckKind::FaceOffFacet, {f, facet},
            "boundary face " + std::to_string(f) + " is not in facet " + std::to_string(facet) + ": " + problem);
      }
    }
    for (std::uint32_t facet = 0; facet < plc_.facets.size(); ++facet) {
      const FacetFrame& frame = frames_[facet];
      if (!frame.valid) continue;
      const double scale = std::max(frame.area, covered[facet]);
      // A facet with the domain on neither side (between a hole and the exterior) is
      // rightly absent from the domain boundary: no tet reaches its interior.
      if (covered[facet] == 0.0 && outside_domain(plc_.facets[facet], frame)) continue;
      // Boundary vertices on the facet's segments may sit off them by the roundoff the
      // plane and line tests accept (tolerance_), which moves the covered area by up to the
      // perimeter times that distance: on a needle facet this exceeds relative_tolerance.
      const double roundoff_area = frame.perimeter * tolerance_;
      if (std::abs(frame.area - covered[facet]) > options_.relative_tolerance * scale + roundoff_area) {
        std::ostringstream text;
        text.precision(17);
        text << "facet " << facet << " has area " << frame.area << " but its boundary faces cover "
             << covered[facet];
        add(MeshCheckKind::FacetNotCovered, {facet}, text.str());
      }
    }
  }

  /// True if a point strictly inside the facet (the centroid of three consecutive vertices
  /// of one of its polygons, off every loop) lies in no domain tet, closed (exact orient3d
  /// against each face, compared with the tet's own opposite vertex). False when no such
  /// point is found.
  bool outside_domain(const Plc::Facet& facet, const FacetFrame& frame) const {
    std::optional<Vec3> inside;
    for (const auto& loop : facet.polygons) {
      const std::size_t n = loop.size();
      for (std::size_t i = 0; n >= 3 && i < n && !inside; ++i) {
        const Vec3 c =
            (plc_.points[loop[(i + n - 1) % n]] + plc_.points[loop[i]] + plc_.points[loop[(i + 1) % n]]) / 3.0;
        bool on_boundary = false;
        const auto innermost = frame.innermost(project(c, frame.axis), &on_boundary);
        if (!on_boundary && innermost && !frame.loops[*innermost].hole) inside = c;
      }
    }
    if (!inside) return false;
    for (std::uint32_t t = 0; t < mesh_.tets.size(); ++t) {
      if (!domain_tet(t)) continue;
      const auto& v = mesh_.tets[t];
      bool in_tet = true;
      for (int f = 0; f < 4 && in_tet; ++f) {
        const double* a = point(v[kFace[f][0]]).data();
        const double* b = point(v[kFace[f][1]]).data();
        const double* c = point(v[kFace[f][2]]).data();
        const Sign side = predicates::orient3d(a, b, c, inside->data());
        in_tet = side == Sign::Zero || side == predicates::orient3d(a, b, c, point(v[f]).data());
      }
      if (in_tet) return false;
    }
    return true;
  }

  void check_segments() {
    // Sorted and distinct (an edge shared by two facets is listed twice).
    std::vector<std::pair<std::uint32_t, std::uint32_t>> segments;
    auto insert = [&](std::uint32_t a, std::uint32_t b) {
      if (a != b) segments.emplace_back(std::min(a, b), std::max(a, b));
    };
    for (const auto& facet : plc_.facets) {
      for (const auto& polygon : facet.polygons) {
        if (polygon.size() == 2) insert(polygon[0], polygon[1]);
        if (polygon.size() < 3) continue;
        for (std::size_t i = 0; i < polygon.size(); ++i) insert(polygon[i], polygon[(i + 1) % polygon.size()]);
      }
    }
    for (const auto& s : plc_.segments) insert(s.a, s.b);
    if (segments.empty()) return;
    std::sort(segments.begin(), segments.end());
    segments.erase(std::unique(segments.begin(), segments.end()), segments.end());

    // The tets at each vertex, in one array (offsets into it per vertex); the edges at a
    // vertex are listed from them when a walk reaches it (Neighbors::of).
    const std::size_t n = mesh_.points.size();
    std::vector<std::uint32_t> offsets(n + 1, 0);
    for (const auto& t : mesh_.tets)
      for (const std::uint32_t v : t) ++offsets[v + 1];
    for (std::size_t v = 0; v < n; ++v) offsets[v + 1] += offsets[v];
    std::vector<std::uint32_t> tets_at(offsets[n]);
    std::vector<std::uint32_t> fill(offsets.begin(), offsets.end() - 1);
    for (std::uint32_t t = 0; t < mesh_.tets.size(); ++t)
      for (const std::uint32_t v : mesh_.tets[t]) tets_at[fill[v]++] = t;
    Neighbors neighbors{mesh_, offsets, tets_at, {}};
    for (const auto& [a, b] : segments) {
      if (full()) return;
      if (!segment_is_chain(neighbors, a, b)) {
        add(MeshCheckKind::MissingSegment, {a, b},
            "PLC segment " + std::to_string(a) + "-" + std::to_string(b) + " is not a chain of mesh edges");
      }
    }
  }

  /// The vertices joined to a vertex by a mesh edge, sorted and distinct, listed from the
  /// tets at it (tets_at[offsets[v] .. offsets[v + 1])).
  struct Neighbors {
    const TetraMesh& mesh;
    const std::vector<std::uint32_t>& offsets;
    const std::vector<std::uint32_t>& tets_at;
    std::vector<std::uint32_t> list;
    const std::vector<std::uint32_t>& of(std::uint32_t v) {
      list.clear();
      for (std::uint32_t k = offsets[v]; k < offsets[v + 1]; ++k)
        for (const std::uint32_t w : mesh.tets[tets_at[k]])
          if (w != v) list.push_back(w);
      std::sort(list.begin(), list.end());
      list.erase(std::unique(list.begin(), list.end()), list.end());
      return list;
    }
    /// Is (v, w) a mesh edge? A scan of the tets at v, without listing its edges.
    bool joined(std::uint32_t v, std::uint32_t w) const {
      for (std::uint32_t k = offsets[v]; k < offsets[v + 1]; ++k) {
        const auto& t = mesh.tets[tets_at[k]];
        if (t[0] == w || t[1] == w || t[2] == w || t[3] == w) return true;
      }
      return false;
    }
  };

  /// Walks from a to b along mesh edges whose far vertex lies on segment ab strictly
  /// between the current vertex and b, taking the nearest one each step. The edges at the
  /// current vertex are listed only when b is not one of them (most segments of a surface
  /// mesh are a single edge).
  bool segment_is_chain(Neighbors& neighbors, std::uint32_t a, std::uint32_t b) const {
    const Vec3 &pa = point(a), &pb = point(b);
    std::uint32_t current = a;
    for (std::size_t step = 0; step <= mesh_.points.size(); ++step) {
      if (neighbors.joined(current, b)) return true;
      const Vec3& pc = point(current);
      std::uint32_t best = kNoTet;
      for (std::uint32_t w : neighbors.of(current)) {
        const Vec3& pw = point(w);
        if (predicates::dot3d(pc.data(), pb.data(), pw.data()) != Sign::Negative || !on_line(pa, pb, pw)) continue;
        if (best == kNoTet || predicates::dot3d(pc.data(), point(best).data(), pw.data()) == Sign::Negative) {
          best = w;
        }
      }
      if (best == kNoTet) return false;
      current = best;
    }
    return false;
  }

  void check_volume() {
    double mesh_volume = 0.0;
    for (std::uint32_t t = 0; t < mesh_.tets.size(); ++t) {
      if (!domain_tet(t)) continue;
      const auto& v = mesh_.tets[t];
      mesh_volume += signed_volume(point(v[0]), point(v[1]), point(v[2]), point(v[3]));
    }
    // Orientation of each facet from one of its outward domain-boundary faces.
    std::vector<int> facet_sign(plc_.facets.size(), 0);
    for (std::uint32_t f = 0; f < mesh_.boundary_faces.size(); ++f) {
      const std::uint32_t facet = face_facets_[f];
      if (facet_sign[facet] != 0 || !frames_[facet].valid || !separates_domain_[f]) continue;
      const auto& v = mesh_.boundary_faces[f];
      const Vec3 normal = (point(v[1]) - point(v[0])).cross(point(v[2]) - point(v[0]));
      facet_sign[facet] = normal.dot(frames_[facet].unit_normal) >= 0 ? 1 : -1;
    }
    double plc_volume = 0.0;
    for (std::uint32_t facet = 0; facet < plc_.facets.size(); ++facet) {
      if (facet_sign[facet] == 0) continue;
      const FacetFrame& frame = frames_[facet];
      plc_volume += facet_sign[facet] * frame.vector_area.dot(plc_.points[frame.a] - center_) / 3.0;
    }
    const double scale = std::max(std::abs(mesh_volume), std::abs(plc_volume));
    if (std::abs(mesh_volume - plc_volume) > options_.relative_tolerance * scale) {
      std::ostringstream text;
      text.precision(17);
      text << "the tets' volume " << mesh_volume << " differs from the volume enclosed by the PLC " << plc_volume;
      add(MeshCheckKind::VolumeMismatch, {}, text.str());
    }
  }

  const TetraMesh& mesh_;
  const Plc& plc_;
  std::span<const std::uint32_t> face_facets_;
  const CheckMeshOptions& options_;
  std::vector<MeshCheckIssue> issues_;
  bool use_facets_ = false;
  std::vector<bool> positive_;
  /// check_complex's faces: slots_[run_start_[x] .. run_start_[x + 1]) are those whose
  /// smallest vertex is x, sorted by (y, z, tet).
  struct FaceSlot {
    std::uint32_t y, z, tet;
    std::uint8_t local;  ///< the tet's face index (its vertex opposite the face)
    bool even;           ///< the tet's face is an even permutation of (x, y, z)
  };
  std::vector<std::uint32_t> run_start_;
  std::vector<FaceSlot> slots_;
  std::vector<std::pair<FaceKey, std::uint32_t>> listed_;  ///< sorted (key, index)
  /// Per boundary face: a face of some tet with a domain tet on exactly one side.
  std::vector<bool> separates_domain_;
  std::vector<FacetFrame> frames_;
  Vec3 center_ = Vec3::Zero();
  double tolerance_ = 0.0;
};

}  // namespace

std::vector<MeshCheckIssue> check_mesh(const TetraMesh& mesh, const Plc& plc,
                                       std::span<const std::uint32_t> boundary_face_facets,
                                       const CheckMeshOptions& options) {
  return Checker(mesh, plc, boundary_face_facets, options).run();
}

}  // namespace delmesh
