// TetMesh storage and navigation (see tet_mesh.h for the conventions).
#include "toolkit/tetmesh/tet_mesh.h"

#include <algorithm>
#include <limits>

namespace delmesh {

namespace {

// Local indices (k, l) completing (i, j) to an even permutation of (0, 1, 2, 3), so that
// (v[i], v[j], v[k], v[l]) has the orientation of the tet.
constexpr std::uint8_t kEdgeOthers[4][4][2] = {
    {{0, 0}, {2, 3}, {3, 1}, {1, 2}},
    {{3, 2}, {0, 0}, {0, 3}, {2, 0}},
    {{1, 3}, {3, 0}, {0, 0}, {0, 1}},
    {{2, 1}, {0, 2}, {1, 0}, {0, 0}},
};

}  // namespace

TetMesh::TetMesh() {
  points_.push_back(Vec3::Zero());  // the infinite vertex; its coordinates are never read
  vertex_tet_.push_back(kNone);
}

TetMesh::TetMesh(std::vector<Vec3> points) : points_(std::move(points)) {
  points_.insert(points_.begin(), Vec3::Zero());  // the infinite vertex
  vertex_tet_.assign(points_.size(), kNone);
}

std::uint32_t TetMesh::add_vertex(const Vec3& p) {
  points_.push_back(p);
  vertex_tet_.push_back(kNone);
  return static_cast<std::uint32_t>(points_.size() - 1);
}

void TetMesh::reserve(std::size_t vertices, std::size_t tets) {
  points_.reserve(vertices);
  vertex_tet_.reserve(vertices);
  tets_.reserve(tets);
  stamps_.reserve(tets);
}

std::uint32_t TetMesh::num_finite_tets() const {
  std::uint32_t count = 0;
  for (const auto& r : tets_) {
    if (r.v[0] != kNone && r.v[0] != 0 && r.v[1] != 0 && r.v[2] != 0 && r.v[3] != 0) ++count;
  }
  return count;
}

namespace {

std::array<std::uint32_t, 3> sorted_face(const TetRecord& r, int f) {
  std::array<std::uint32_t, 3> k{r.v[kFaceVertex[f][0]], r.v[kFaceVertex[f][1]],
                                 r.v[kFaceVertex[f][2]]};
  std::sort(k.begin(), k.end());
  return k;
}

}  // namespace

bool TetMesh::glue_by_vertices(std::span<const std::uint32_t> tets,
                               std::span<const std::uint32_t> outside) {
  for (const std::uint32_t t : tets) {
    for (int f = 0; f < 4; ++f) {
      if (tets_[t].adj[f] != kNone) continue;
      const auto key = sorted_face(tets_[t], f);
      bool found = false;
      for (const std::uint32_t u : tets) {
        if (u == t) continue;
        for (int g = 0; g < 4 && !found; ++g) {
          if (tets_[u].adj[g] == kNone && sorted_face(tets_[u], g) == key) {
            glue(t, f, u, g);
            found = true;
          }
        }
        if (found) break;
      }
      for (std::size_t k = 0; k < outside.size() && !found; ++k) {
        const std::uint32_t ref = outside[k];
        if (sorted_face(tets_[ref >> 2], static_cast<int>(ref & 3u)) == key) {
          glue_ref(t, f, ref);
          found = true;
        }
      }
      if (!found) return false;
    }
  }
  return true;
}

std::uint32_t TetMesh::new_stamp() {
  if (stamps_.size() != tets_.size()) {
    stamps_.assign(tets_.size(), 0u);
    current_stamp_ = 0;
  }
  if (current_stamp_ >= std::numeric_limits<std::uint32_t>::max() - 2) {
    std::fill(stamps_.begin(), stamps_.end(), 0u);
    current_stamp_ = 0;
  }
  return ++current_stamp_;
}

std::uint32_t TetMesh::new_stamp_pair() {
  const std::uint32_t s = new_stamp();
  new_stamp();
  return s;
}

void TetMesh::renumber_vertices(std::span<const std::uint32_t> new_id) {
  for (auto& r : tets_) {
    if (r.v[0] == kNone) continue;
    for (auto& v : r.v) v = new_id[v];
  }
  // Permute the points in place by following cycles; vertex_tet_ marks the visited ones
  // and is rebuilt afterwards.
  std::fill(vertex_tet_.begin(), vertex_tet_.end(), 0u);
  for (std::uint32_t start = 0; start < points_.size(); ++start) {
    if (vertex_tet_[start]) continue;
    Vec3 carried = points_[start];
    std::uint32_t v = start;
    do {
      vertex_tet_[v] = 1;
      const std::uint32_t to = new_id[v];
      std::swap(carried, points_[to]);
      v = to;
    } while (v != start);
  }
  perturbation_ids_.clear();
  perturbation_ids_.shrink_to_fit();
  rebuild_vertex_tets();
}

void TetMesh::rebuild_vertex_tets() {
  std::fill(vertex_tet_.begin(), vertex_tet_.end(), kNone);
  for (std::uint32_t t = 0; t < tets_.size(); ++t) {
    if (tets_[t].v[0] == kNone) continue;
    for (const std::uint32_t v : tets_[t].v) vertex_tet_[v] = t;
  }
}

void TetMesh::star(std::uint32_t v, std::vector<std::uint32_t>& out) {
  out.clear();
  const std::uint32_t start = vertex_tet_[v];
  if (start == kNone) return;
  const std::uint32_t s = new_stamp();
  stamps_[start] = s;
  out.push_back(start);
  for (std::size_t k = 0; k < out.size(); ++k) {
    const std::uint32_t t = out[k];
    for (int i = 0; i < 4; ++i) {
      if (tets_[t].v[i] == v) continue;  // the face opposite v does not contain v
      const std::uint32_t n = tets_[t].adj[i] >> 2;
      if (stamps_[n] == s) continue;
      stamps_[n] = s;
      out.push_back(n);
    }
  }
}

void TetMesh::vertex_neighbors(std::uint32_t v, std::vector<std::uint32_t>& out) {
  std::vector<std::uint32_t> tets;
  star(v, tets);
  out.clear();
  for (const std::uint32_t t : tets) {
    for (const std::uint32_t w : tets_[t].v) {
      if (w != v) out.push_back(w);
    }
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
}

std::optional<EdgeRef> TetMesh::find_edge(std::uint32_t a, std::uint32_t b) {
  if (a >= points_.size() || b >= points_.size() || a == b) return std::nullopt;
  const std::uint32_t start = vertex_tet_[a];
  if (start == kNone) return std::nullopt;
  // Breadth-first search over the star of a, stopping at the first tet holding b.
  std::vector<std::uint32_t> queue{start};
  const std::uint32_t s = new_stamp();
  stamps_[start] = s;
  for (std::size_t k = 0; k < queue.size(); ++k) {
    const std::uint32_t t = queue[k];
    const int j = local_index(t, b);
    if (j >= 0) {
      return EdgeRef{t, static_cast<std::uint8_t>(local_index(t, a)), static_cast<std::uint8_t>(j)};
    }
    for (int i = 0; i < 4; ++i) {
      if (tets_[t].v[i] == a) continue;
      const std::uint32_t n = tets_[t].adj[i] >> 2;
      if (stamps_[n] == s) continue;
      stamps_[n] = s;
      queue.push_back(n);
    }
  }
  return std::nullopt;
}

bool TetMesh::tets_around_edge(std::uint32_t a, std::uint32_t b, std::vector<std::uint32_t>& out,
                               std::vector<std::uint32_t>* ring) {
  out.clear();
  if (ring) ring->clear();
  const auto edge = find_edge(a, b);
  if (!edge) return false;
  const std::uint32_t start = edge->tet;
  std::uint32_t t = start;
  int i = edge->i;
  int j = edge->j;
  do {
    const int k = kEdgeOthers[i][j][0];
    out.push_back(t);
    if (ring) ring->push_back(tets_[t].v[k]);
    // The next tet shares the face (a, b, v[l]) with l = kEdgeOthers[i][j][1]: the face
    // opposite v[k].
    const std::uint32_t n = tets_[t].adj[k] >> 2;
    t = n;
    i = local_index(t, a);
    j = local_index(t, b);
  } while (t != start);
  return true;
}

std::optional<FaceRef> TetMesh::find_face(std::uint32_t a, std::uint32_t b, std::uint32_t c) {
  if (c >= points_.size() || c == a || c == b) return std::nullopt;
  const auto edge = find_edge(a, b);
  if (!edge) return std::nullopt;
  const std::uint32_t start = edge->tet;
  std::uint32_t t = start;
  int i = edge->i;
  int j = edge->j;
  do {
    if (local_index(t, c) >= 0) {
      for (int f = 0; f < 4; ++f) {
        const std::uint32_t w = tets_[t].v[f];
        if (w != a && w != b && w != c) return FaceRef{t, static_cast<std::uint8_t>(f)};
      }
    }
    const int k = kEdgeOthers[i][j][0];
    t = tets_[t].adj[k] >> 2;
    i = local_index(t, a);
    j = local_index(t, b);
  } while (t != start);
  return std::nullopt;
}

MappedArray<std::uint32_t> TetMesh::compact() {
  // The map takes over the stamp buffer: it has one entry per slot already, and stamps
  // are void after compaction anyway.
  MappedArray<std::uint32_t> remap = std::move(stamps_);
  remap.resize(tets_.size());
  std::uint32_t next = 0;
  for (std::uint32_t t = 0; t < tets_.size(); ++t) {
    remap[t] = tets_[t].v[0] != kNone ? next++ : kNone;
  }
  for (std::uint32_t t = 0; t < tets_.size(); ++t) {
    if (remap[t] == kNone) continue;
    TetRecord r = tets_[t];
    for (auto& a : r.adj) a = (remap[a >> 2] << 2) | (a & 3u);
    tets_[remap[t]] = r;
  }
  // No shrink_to_fit: it would copy the arrays (doubling the peak memory), and the
  // reserved tail that was never touched occupies no physical memory.
  tets_.resize(next);
  current_stamp_ = 0;
  free_tets_.clear();
  for (auto& t : vertex_tet_) {
    if (t != kNone) t = remap[t];
  }
  last_tet_ = last_tet_ == kNone ? kNone : remap[last_tet_];
  return remap;
}

}  // namespace delmesh
