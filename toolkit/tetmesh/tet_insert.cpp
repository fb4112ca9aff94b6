// Bowyer–Watson insertion and splits (see tet_insert.h).
#include "toolkit/tetmesh/tet_insert.h"

#include <algorithm>
#include <bit>

#include "toolkit/core/error.h"
#include "toolkit/predicates/predicates.h"

namespace delmesh {

namespace {

// insphere first (filtered, cheap); only an exactly cospherical p needs the perturbed
// test. ip is the perturbation id of p (TetMesh::perturbation_id).
inline bool finite_in_conflict(const TetMesh& mesh, const TetRecord& r, const double* p,
                               std::uint32_t ip) {
  const double* a = mesh.coords(r.v[0]);
  const double* b = mesh.coords(r.v[1]);
  const double* c = mesh.coords(r.v[2]);
  const double* d = mesh.coords(r.v[3]);
  const Sign s = predicates::insphere(a, b, c, d, p);
  if (s != Sign::Zero) return s == Sign::Positive;
  return predicates::insphere_sos(a, b, c, d, p, mesh.perturbation_id(r.v[0]),
                                  mesh.perturbation_id(r.v[1]), mesh.perturbation_id(r.v[2]),
                                  mesh.perturbation_id(r.v[3]), ip) == Sign::Positive;
}

constexpr std::uint64_t kEmptyKey = ~std::uint64_t{0};

inline std::uint64_t edge_key(std::uint32_t a, std::uint32_t b) {
  return (static_cast<std::uint64_t>(a) << 32) | b;
}

inline std::size_t edge_hash(std::uint64_t key, std::size_t mask) {
  return static_cast<std::size_t>((key * 0x9E3779B97F4A7C15ULL) >> 40) & mask;
}

// The conflict rule of tet_insert.h; ip is the perturbation id of p.
inline bool in_conflict(const TetMesh& mesh, std::uint32_t t, const double* p, std::uint32_t ip) {
  const TetRecord& r = mesh.tet(t);
  const int k = mesh.infinite_index(t);
  if (k < 0) return finite_in_conflict(mesh, r, p, ip);
  const auto& o = kFaceVertex[k];
  const Sign s = predicates::orient3d(mesh.coords(r.v[o[0]]), mesh.coords(r.v[o[1]]),
                                      mesh.coords(r.v[o[2]]), p);
  if (s != Sign::Zero) return s == Sign::Positive;
  return finite_in_conflict(mesh, mesh.tet(mesh.neighbor(t, k)), p, ip);
}

}  // namespace

bool tet_in_conflict(const TetMesh& mesh, std::uint32_t t, const double* p, std::uint32_t ip) {
  return in_conflict(mesh, t, p, mesh.perturbation_id(ip));
}

namespace {

// The depth-first search of compute_cavity from the located tet; faces for which
// blocked(t, f) holds are boundary faces whatever their far tet.
template <class Blocked>
void grow_cavity(TetMesh& mesh, const double* p, std::uint32_t ip, std::uint32_t start, Cavity& cavity,
                 const Blocked& blocked) {
  // The located tet contains p (or, outside the hull, its hull face sees p): it is in
  // conflict. Depth-first search over the conflict region; `in` marks conflict tets and
  // `out` tets found not in conflict (each tested once). The stack holds face refs 4*t + j:
  // face j of tet t is the one the search entered t through (none for the start), which
  // the blocker let through already and answers alike from t's side.
  const std::uint32_t in = mesh.new_stamp_pair();
  const std::uint32_t out = in + 1;
  const TetRecord* tets = mesh.records().data();
  std::uint32_t* stamps = mesh.stamps().data();
  auto& stack = cavity.stack;
  auto& boundary = cavity.boundary;
  stack.clear();
  stamps[start] = in;
  stack.push_back(start << 2);
  cavity.tets.push_back(start);
  bool at_start = true;
  while (!stack.empty()) {
    const std::uint32_t entry = stack.back();
    stack.pop_back();
    const std::uint32_t t = entry >> 2;
    const int entered = at_start ? 4 : static_cast<int>(entry & 3u);
    at_start = false;
    const TetRecord& r = tets[t];
    // The four neighbours' stamps and records are scattered over arrays far larger than
    // the cache: ask for all of them before the first is tested, so that their misses
    // overlap instead of following one another.
    for (int f = 0; f < 4; ++f) {
      __builtin_prefetch(stamps + (r.adj[f] >> 2));
      __builtin_prefetch(tets + (r.adj[f] >> 2));
    }
    for (int f = 0; f < 4; ++f) {
      const std::uint32_t ref = r.adj[f];
      const std::uint32_t n = ref >> 2;
      const std::uint32_t sn = stamps[n];
      if (sn == in) {
        if (f == entered || !blocked(t, f)) continue;
      } else if (sn != out && !blocked(t, f)) {
        if (in_conflict(mesh, n, p, ip)) {
          stamps[n] = in;
          cavity.tets.push_back(n);
          stack.push_back(ref);
          continue;
        }
        stamps[n] = out;
      }
      const auto& o = kFaceVertex[f];
      boundary.push_back(CavityFace{{r.v[o[0]], r.v[o[1]], r.v[o[2]]}, ref});
    }
  }
}

struct NeverBlocked {
  constexpr bool operator()(std::uint32_t, int) const { return false; }
};

/// Locates p from hint and grows its cavity through the faces `blocked` lets through.
template <typename Blocker>
Location locate_and_grow(TetMesh& mesh, const double* p, std::uint32_t ip, std::uint32_t hint, Cavity& cavity,
                         const Blocker& blocked) {
  cavity.tets.clear();
  cavity.boundary.clear();
  cavity.created.clear();
  const Location loc = locate(mesh, p, hint, cavity.rng);
  cavity.location = loc;
  if (loc.kind == LocationKind::OnVertex) return loc;
  grow_cavity(mesh, p, mesh.perturbation_id(ip), loc.tet, cavity, blocked);
  return loc;
}

}  // namespace

Location compute_cavity(TetMesh& mesh, const double* p, std::uint32_t ip, std::uint32_t hint,
                        Cavity& cavity) {
  return locate_and_grow(mesh, p, ip, hint, cavity, NeverBlocked{});
}

Location compute_constrained_cavity(TetMesh& mesh, const double* p, std::uint32_t ip, std::uint32_t hint,
                                    const CavityBlocker& blocked, Cavity& cavity) {
  return locate_and_grow(mesh, p, ip, hint, cavity, blocked);
}

namespace {

/// Starts a new epoch of cavity.vertex_mark, whose entries read (epoch << 6) | a local
/// number (glue_new_tets_by_table) or (epoch << 6) alone (a membership mark): marks of
/// earlier epochs need no clearing. Sized for every vertex id below mesh.num_vertices().
std::uint32_t new_vertex_epoch(const TetMesh& mesh, Cavity& cavity) {
  auto& mark = cavity.vertex_mark;
  if (mark.size() < mesh.num_vertices()) mark.resize(mesh.num_vertices() + mesh.num_vertices() / 4, 0);
  if (++cavity.epoch >= (1u << 26)) {
    std::fill(mark.begin(), mark.end(), 0u);
    cavity.epoch = 1;
  }
  return cavity.epoch;
}

}  // namespace

bool shrink_cavity_to_star(TetMesh& mesh, const double* p, std::uint32_t keep, Cavity& cavity, bool& shrunk) {
  // Scratch of the Cavity (no allocation per call); the vertices of the boundary (the
  // rim) are marked in cavity.vertex_mark.
  auto& drop = cavity.drop;
  auto& kept = cavity.kept;
  const std::size_t rounds = cavity.tets.size();
  for (std::size_t round = 0; round <= rounds; ++round) {
    drop.clear();
    const std::uint32_t rim = new_vertex_epoch(mesh, cavity) << 6;
    std::uint32_t* marks = cavity.vertex_mark.data();
    for (const CavityFace& f : cavity.boundary) {
      for (const std::uint32_t w : f.v) marks[w] = rim;
      if (f.v[0] == kInfiniteVertex || f.v[1] == kInfiniteVertex || f.v[2] == kInfiniteVertex) continue;
      if (predicates::orient3d(mesh.coords(f.v[0]), mesh.coords(f.v[1]), mesh.coords(f.v[2]), p) != Sign::Positive)
        drop.push_back(mesh.tet(f.outside >> 2).adj[f.outside & 3u] >> 2);
    }
    for (const std::uint32_t t : cavity.tets)
      for (const std::uint32_t w : mesh.tet(t).v)
        if (marks[w] != rim) drop.push_back(t);
    if (drop.empty()) return true;
    std::sort(drop.begin(), drop.end());
    drop.erase(std::unique(drop.begin(), drop.end()), drop.end());
    if (std::binary_search(drop.begin(), drop.end(), keep)) return false;
    kept.clear();
    for (const std::uint32_t t : cavity.tets)
      if (!std::binary_search(drop.begin(), drop.end(), t)) kept.push_back(t);
    if (kept.empty()) return false;
    shrunk = true;
    cavity_from_tets(mesh, kept, cavity);
  }
  return false;
}

namespace {

// Glues the new tets of a cavity to each other. The face (a, b, c) of new tet
// (a, b, c, v) meets another new tet across each of its edges: (b, c) at face 0, (c, a)
// at face 1, (a, b) at face 2; the neighbouring boundary face runs through the same
// edge in the opposite direction.
//
// Fast path: the boundary vertices get small local numbers (a per-vertex mark tagged
// with an epoch, so nothing is ever cleared); pass 1 writes every directed edge (x, y)
// into a 64 x 64 table, pass 2 reads the reversed edge. No probing and no
// data-dependent branches. Returns false when there are more than 64 boundary vertices.
bool glue_new_tets_by_table(TetMesh& mesh, Cavity& cavity) {
  constexpr std::uint32_t kMaxLocal = 64;
  const std::uint32_t epoch = new_vertex_epoch(mesh, cavity);
  if (cavity.edge_table.size() < kMaxLocal * kMaxLocal) cavity.edge_table.resize(kMaxLocal * kMaxLocal);
  std::uint32_t* table = cavity.edge_table.data();
  std::uint32_t* marks = cavity.vertex_mark.data();
  std::uint32_t count = 0;
  const std::size_t nfaces = cavity.boundary.size();
  for (std::size_t k = 0; k < nfaces; ++k) {
    const CavityFace& face = cavity.boundary[k];
    std::uint32_t l[3];
    for (int i = 0; i < 3; ++i) {
      std::uint32_t& m = marks[face.v[i]];
      if ((m >> 6) != epoch) {
        if (count == kMaxLocal) return false;
        m = (epoch << 6) | count++;
      }
      l[i] = m & 63u;
    }
    const std::uint32_t t4 = cavity.created[k] << 2;
    table[l[1] * kMaxLocal + l[2]] = t4 | 0u;
    table[l[2] * kMaxLocal + l[0]] = t4 | 1u;
    table[l[0] * kMaxLocal + l[1]] = t4 | 2u;
  }
  TetRecord* tets = mesh.records().data();
  for (std::size_t k = 0; k < nfaces; ++k) {
    const CavityFace& face = cavity.boundary[k];
    const std::uint32_t l0 = marks[face.v[0]] & 63u, l1 = marks[face.v[1]] & 63u,
                        l2 = marks[face.v[2]] & 63u;
    auto& adj = tets[cavity.created[k]].adj;
    adj[0] = table[l2 * kMaxLocal + l1];
    adj[1] = table[l0 * kMaxLocal + l2];
    adj[2] = table[l1 * kMaxLocal + l0];
  }
  return true;
}

// General path for large cavities: a hash of undirected edges; each edge is met twice,
// the first time it is recorded, the second time the two faces are glued.
void glue_new_tets_by_hash(TetMesh& mesh, Cavity& cavity) {
  const std::size_t nfaces = cavity.boundary.size();
  const std::size_t table = std::max<std::size_t>(64, std::bit_ceil(nfaces * 4));
  const std::size_t mask = table - 1;
  if (cavity.edge_keys.size() < table) {
    cavity.edge_keys.assign(table, kEmptyKey);
    cavity.edge_values.assign(table, 0);
  }
  std::uint64_t* keys = cavity.edge_keys.data();
  std::uint32_t* values = cavity.edge_values.data();
  auto& used = cavity.used_slots;
  for (std::size_t k = 0; k < nfaces; ++k) {
    const CavityFace& face = cavity.boundary[k];
    const std::uint32_t t = cavity.created[k];
    const std::uint32_t a = face.v[0], b = face.v[1], c = face.v[2];
    const std::uint32_t edge[3][2] = {{b, c}, {c, a}, {a, b}};
    for (int f = 0; f < 3; ++f) {
      const std::uint64_t key = edge_key(std::min(edge[f][0], edge[f][1]), std::max(edge[f][0], edge[f][1]));
      std::size_t h = edge_hash(key, mask);
      while (keys[h] != kEmptyKey && keys[h] != key) h = (h + 1) & mask;
      if (keys[h] == key) {
        const std::uint32_t ref = values[h];
        mesh.glue(t, f, ref >> 2, static_cast<int>(ref & 3u));
      } else {
        keys[h] = key;
        values[h] = (t << 2) | static_cast<std::uint32_t>(f);
        used.push_back(static_cast<std::uint32_t>(h));
      }
    }
  }
  for (const std::uint32_t h : used) keys[h] = kEmptyKey;  // reset only the slots used
  used.clear();
}

}  // namespace

std::uint32_t commit_cavity(TetMesh& mesh, std::uint32_t v, Cavity& cavity) {
  for (const std::uint32_t t : cavity.tets) mesh.kill_tet(t);
  const std::size_t nfaces = cavity.boundary.size();
  cavity.created.resize(nfaces);
  std::uint32_t finite_tet = kNone;
  for (std::size_t k = 0; k < nfaces; ++k) {
    const CavityFace& face = cavity.boundary[k];
    const std::uint32_t a = face.v[0], b = face.v[1], c = face.v[2];
    const std::uint32_t t = mesh.create_tet(a, b, c, v);
    cavity.created[k] = t;
    mesh.glue_ref(t, 3, face.outside);
    if (cavity.update_vertex_tets) {
      mesh.set_vertex_tet(a, t);
      mesh.set_vertex_tet(b, t);
      mesh.set_vertex_tet(c, t);
    }
    if (a != kInfiniteVertex && b != kInfiniteVertex && c != kInfiniteVertex) finite_tet = t;
  }
  if (!glue_new_tets_by_table(mesh, cavity)) glue_new_tets_by_hash(mesh, cavity);
  const std::uint32_t any = finite_tet != kNone ? finite_tet : cavity.created.back();
  mesh.set_vertex_tet(v, any);
  mesh.set_last_tet(any);
  return any;
}

void cavity_from_tets(TetMesh& mesh, std::span<const std::uint32_t> tets, Cavity& cavity) {
  cavity.tets.assign(tets.begin(), tets.end());
  cavity.boundary.clear();
  cavity.created.clear();
  const std::uint32_t s = mesh.new_stamp();
  for (const std::uint32_t t : tets) mesh.set_stamp(t, s);
  for (const std::uint32_t t : tets) {
    const TetRecord& r = mesh.tet(t);
    for (int f = 0; f < 4; ++f) {
      if (mesh.stamp(r.adj[f] >> 2) == s) continue;
      const auto& o = kFaceVertex[f];
      cavity.boundary.push_back(CavityFace{{r.v[o[0]], r.v[o[1]], r.v[o[2]]}, r.adj[f]});
    }
  }
}

bool cavity_is_star_shaped(const TetMesh& mesh, const double* p, const Cavity& cavity) {
  for (const CavityFace& f : cavity.boundary) {
    if (f.v[0] == kInfiniteVertex || f.v[1] == kInfiniteVertex || f.v[2] == kInfiniteVertex) {
      continue;
    }
    if (predicates::orient3d(mesh.coords(f.v[0]), mesh.coords(f.v[1]), mesh.coords(f.v[2]), p) !=
        Sign::Positive) {
      return false;
    }
  }
  return true;
}

InsertResult insert_vertex(TetMesh& mesh, std::uint32_t v, std::uint32_t hint, Cavity& cavity) {
  InsertResult result;
  result.location = compute_cavity(mesh, mesh.coords(v), v, hint, cavity);
  if (result.location.kind == LocationKind::OnVertex) {
    result.duplicate_of = mesh.vertex(result.location.tet, result.location.i);
    return result;
  }
  result.tet = commit_cavity(mesh, v, cavity);
  return result;
}

std::uint32_t make_first_tet(TetMesh& mesh, std::uint32_t a, std::uint32_t b, std::uint32_t c,
                             std::uint32_t d) {
  DELMESH_CHECK(mesh.num_live_tets() == 0, "make_first_tet needs an empty mesh");
  const Sign s = predicates::orient3d(mesh.coords(a), mesh.coords(b), mesh.coords(c), mesh.coords(d));
  DELMESH_CHECK(s != Sign::Zero, "make_first_tet needs four non-coplanar points");
  if (s == Sign::Negative) std::swap(a, b);
  const std::uint32_t t = mesh.create_tet(a, b, c, d);
  std::uint32_t all[5] = {t, 0, 0, 0, 0};
  for (int f = 0; f < 4; ++f) {
    // The hull face seen from outside: the face of t reversed, joined to infinity.
    const auto& o = kFaceVertex[f];
    const TetRecord& r = mesh.tet(t);
    all[f + 1] = mesh.create_tet(r.v[o[1]], r.v[o[0]], r.v[o[2]], kInfiniteVertex);
  }
  const bool glued = mesh.glue_by_vertices(all, {});
  DELMESH_CHECK(glued, "first tet: faces failed to pair up");
  for (const std::uint32_t w : mesh.tet(t).v) mesh.set_vertex_tet(w, t);
  mesh.set_vertex_tet(kInfiniteVertex, all[1]);
  mesh.set_last_tet(t);
  return t;
}

namespace {

bool split_star(TetMesh& mesh, std::span<const std::uint32_t> star, std::uint32_t v,
                Cavity& cavity) {
  cavity_from_tets(mesh, star, cavity);
  if (!cavity_is_star_shaped(mesh, mesh.coords(v), cavity)) {
    cavity.tets.clear();
    cavity.boundary.clear();
    return false;
  }
  commit_cavity(mesh, v, cavity);
  return true;
}

}  // namespace

bool split_tet(TetMesh& mesh, std::uint32_t t, std::uint32_t v, Cavity& cavity) {
  if (mesh.is_dead(t) || mesh.is_infinite(t)) return false;
  const std::uint32_t star[1] = {t};
  return split_star(mesh, star, v, cavity);
}

bool split_face(TetMesh& mesh, FaceRef face, std::uint32_t v, Cavity& cavity) {
  if (mesh.is_dead(face.tet)) return false;
  const std::uint32_t star[2] = {face.tet, mesh.neighbor(face.tet, face.face)};
  // Both sides are replaced; for a hull face the infinite tet becomes three infinite
  // tets on the three parts of the split hull face.
  return split_star(mesh, star, v, cavity);
}

bool split_edge(TetMesh& mesh, std::uint32_t a, std::uint32_t b, std::uint32_t v, Cavity& cavity) {
  std::vector<std::uint32_t> ring;
  if (!mesh.tets_around_edge(a, b, ring)) return false;
  return split_star(mesh, ring, v, cavity);
}

}  // namespace delmesh
