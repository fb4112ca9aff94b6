// Constrained gift-wrapping of a polyhedral cavity (see cavity_gift_wrap.h; notes
// §2.1.3, §2.1.7).
#include "refiners/tet3d/cavity_gift_wrap.h"

#include <algorithm>
#include <unordered_map>
#include <unordered_set>

#include "toolkit/predicates/predicates.h"

namespace delmesh::tet3d {

namespace {

using Key = std::array<std::uint32_t, 3>;
using Face = std::array<std::uint32_t, 3>;

struct KeyHash {
  std::size_t operator()(const Key& k) const {
    return static_cast<std::size_t>((k[0] * 0x9E3779B97F4A7C15ULL) ^ (k[1] * 0xC2B2AE3D27D4EB4FULL) ^
                                    (k[2] * 0x165667B19E3779F9ULL));
  }
};

Key key_of(const Face& f) {
  Key k = f;
  std::sort(k.begin(), k.end());
  return k;
}

/// Same vertices in the same cyclic order.
bool same_orientation(const Face& f, const Face& g) {
  for (int r = 0; r < 3; ++r)
    if (f[0] == g[static_cast<std::size_t>(r)] && f[1] == g[static_cast<std::size_t>((r + 1) % 3)] &&
        f[2] == g[static_cast<std::size_t>((r + 2) % 3)])
      return true;
  return false;
}

/// Does the segment pq meet the closed triangle abc while its endpoints lie strictly on
/// opposite sides of the triangle's plane? (A segment sharing a vertex with the triangle
/// never does.) Exact.
bool segment_crosses_triangle(const double* p, const double* q, const double* a, const double* b,
                              const double* c) {
  const Sign op = predicates::orient3d(a, b, c, p);
  const Sign oq = predicates::orient3d(a, b, c, q);
  if (op == Sign::Zero || oq == Sign::Zero || op == oq) return false;
  const Sign s[3] = {predicates::orient3d(p, q, a, b), predicates::orient3d(p, q, b, c),
                     predicates::orient3d(p, q, c, a)};
  bool pos = false, neg = false;
  for (const Sign x : s) {
    pos = pos || x == Sign::Positive;
    neg = neg || x == Sign::Negative;
  }
  return !(pos && neg);
}

struct Box {
  double lo[3], hi[3];
};

Box box_of(const TetMesh& mesh, std::initializer_list<std::uint32_t> vs) {
  Box b{};
  bool first = true;
  for (const std::uint32_t v : vs) {
    const double* p = mesh.coords(v);
    for (int k = 0; k < 3; ++k) {
      b.lo[k] = first ? p[k] : std::min(b.lo[k], p[k]);
      b.hi[k] = first ? p[k] : std::max(b.hi[k], p[k]);
    }
    first = false;
  }
  return b;
}

bool overlaps(const Box& x, const Box& y) {
  for (int k = 0; k < 3; ++k)
    if (x.hi[k] < y.lo[k] || y.hi[k] < x.lo[k]) return false;
  return true;
}

}  // namespace

bool gift_wrap_cavity(const TetMesh& mesh, std::span<const std::array<std::uint32_t, 3>> faces,
                      std::size_t max_tets, std::vector<std::array<std::uint32_t, 4>>& out) {
  std::vector<std::uint32_t> vertices;
  for (const Face& f : faces) vertices.insert(vertices.end(), f.begin(), f.end());
  std::sort(vertices.begin(), vertices.end());
  vertices.erase(std::unique(vertices.begin(), vertices.end()), vertices.end());

  // The front: open faces by key (-> slot), each wanting a tet on its positive side, in
  // the order they were opened (deterministic); slots keep each open face's box.
  struct Slot {
    Face f;
    Box box;
    bool open;
  };
  std::vector<Slot> slots;
  std::unordered_map<Key, std::size_t, KeyHash> open;
  std::unordered_set<Key, KeyHash> closed;
  auto add_open = [&](const Face& f) {
    if (!open.emplace(key_of(f), slots.size()).second) return false;
    slots.push_back({f, box_of(mesh, {f[0], f[1], f[2]}), true});
    return true;
  };
  for (const Face& f : faces)
    if (!add_open(f)) return false;
  // Is apex d visible from the open face f: the tet (f, d) meets no open face but at
  // shared vertices, edges or faces?
  auto visible = [&](const Face& f, std::uint32_t d) {
    const Box tb = box_of(mesh, {f[0], f[1], f[2], d});
    const double* pd = mesh.coords(d);
    for (const Slot& slot : slots) {
      if (!slot.open || !overlaps(tb, slot.box)) continue;
      const Face& g = slot.f;
      const double* ga = mesh.coords(g[0]);
      const double* gb = mesh.coords(g[1]);
      const double* gc = mesh.coords(g[2]);
      for (const std::uint32_t v : f)
        if (segment_crosses_triangle(mesh.coords(v), pd, ga, gb, gc)) return false;
      for (int e = 0; e < 3; ++e) {
        const double* p = mesh.coords(g[static_cast<std::size_t>(e)]);
        const double* q = mesh.coords(g[static_cast<std::size_t>((e + 1) % 3)]);
        for (int s = 0; s < 3; ++s) {
          const double* a = mesh.coords(f[static_cast<std::size_t>(s)]);
          const double* b = mesh.coords(f[static_cast<std::size_t>((s + 1) % 3)]);
          if (segment_crosses_triangle(p, q, a, b, pd)) return false;
        }
      }
    }
    return true;
  };
  // The vertex strictly on f's positive side with the smallest sphere through f, among
  // those `admit` accepts (tested only for vertices that would improve the choice).
  auto best_apex = [&](const Face& f, auto admit) {
    const double* pa = mesh.coords(f[0]);
    const double* pb = mesh.coords(f[1]);
    const double* pc = mesh.coords(f[2]);
    std::uint32_t best = kNone;
    for (const std::uint32_t v : vertices) {
      if (v == f[0] || v == f[1] || v == f[2]) continue;
      const double* pv = mesh.coords(v);
      if (predicates::orient3d(pa, pb, pc, pv) != Sign::Positive) continue;
      if (best != kNone &&
          predicates::insphere_sos(pa, pb, pc, mesh.coords(best), pv, f[0], f[1], f[2], best, v) != Sign::Positive)
        continue;
      if (!admit(v)) continue;
      best = v;
    }
    return best;
  };

  std::vector<std::array<std::uint32_t, 4>> tets;
  for (std::size_t head = 0; head < slots.size(); ++head) {
    if (!slots[head].open) continue;
    const Face f = slots[head].f;
    // The best apex overall is the best visible one when it is visible (the usual case).
    std::uint32_t best = best_apex(f, [](std::uint32_t) { return true; });
    if (best != kNone && !visible(f, best)) best = best_apex(f, [&](std::uint32_t v) { return visible(f, v); });
    if (best == kNone || tets.size() == max_tets) return false;
    const std::array<std::uint32_t, 4> t = {f[0], f[1], f[2], best};
    for (const auto& fv : kFaceVertex) {
      // The tet lies on the positive side of its faces in kFaceVertex order.
      const Face g = {t[fv[0]], t[fv[1]], t[fv[2]]};
      const Key k = key_of(g);
      if (const auto o = open.find(k); o != open.end()) {
        if (!same_orientation(slots[o->second].f, g)) return false;
        slots[o->second].open = false;
        open.erase(o);
        closed.insert(k);
        continue;
      }
      if (closed.count(k)) return false;
      add_open(Face{g[0], g[2], g[1]});
    }
    tets.push_back(t);
  }
  if (!open.empty()) return false;
  out.insert(out.end(), tets.begin(), tets.end());
  return true;
}

}  // namespace delmesh::tet3d
