// Randomized visibility walk (see tet_locate.h).
#include "toolkit/tetmesh/tet_locate.h"

#include "toolkit/core/error.h"
#include "toolkit/predicates/predicates.h"

namespace delmesh {

namespace {

inline std::uint32_t next_random(std::uint64_t& state) {
  // xorshift64*: cheap, deterministic, good enough to break walk cycles.
  state ^= state >> 12;
  state ^= state << 25;
  state ^= state >> 27;
  return static_cast<std::uint32_t>((state * 0x2545F4914F6CDD1DULL) >> 32);
}

// Where p lies in the closed finite tet t, given its side of each face (none Negative).
Location classify(std::uint32_t t, const Sign (&s)[4]) {
  int zeros = 0;
  int nonzero_face = -1;
  int zero_faces[3] = {0, 0, 0};
  for (int f = 0; f < 4; ++f) {
    if (s[f] == Sign::Zero) {
      zero_faces[zeros < 3 ? zeros : 2] = f;
      ++zeros;
    } else {
      nonzero_face = f;
    }
  }
  Location loc;
  loc.tet = t;
  switch (zeros) {
    case 0: loc.kind = LocationKind::InTet; break;
    case 1:
      loc.kind = LocationKind::OnFace;
      loc.i = static_cast<std::uint8_t>(zero_faces[0]);
      break;
    case 2: {
      // p lies on both zero faces: on the edge they share, made of the other two vertices.
      loc.kind = LocationKind::OnEdge;
      int k = 0;
      std::uint8_t e[2] = {0, 0};
      for (int f = 0; f < 4; ++f) {
        if (f != zero_faces[0] && f != zero_faces[1]) e[k++] = static_cast<std::uint8_t>(f);
      }
      loc.i = e[0];
      loc.j = e[1];
      break;
    }
    default:
      loc.kind = LocationKind::OnVertex;
      loc.i = static_cast<std::uint8_t>(nonzero_face);
      break;
  }
  return loc;
}

// Side of p with respect to face f of t: orientation of t with v[f] replaced by p.
inline Sign face_side(const TetMesh& mesh, const TetRecord& r, int f, const double* p) {
  const auto& o = kFaceVertex[f];
  return predicates::orient3d(mesh.coords(r.v[o[0]]), mesh.coords(r.v[o[1]]),
                              mesh.coords(r.v[o[2]]), p);
}

Location locate_by_scan(const TetMesh& mesh, const double* p) {
  for (std::uint32_t t = 0; t < mesh.tet_slots(); ++t) {
    if (mesh.is_dead(t) || mesh.is_infinite(t)) continue;
    const TetRecord& r = mesh.tet(t);
    Sign s[4];
    bool inside = true;
    for (int f = 0; f < 4 && inside; ++f) {
      s[f] = face_side(mesh, r, f, p);
      inside = s[f] != Sign::Negative;
    }
    if (inside) return classify(t, s);
  }
  for (std::uint32_t t = 0; t < mesh.tet_slots(); ++t) {
    if (mesh.is_dead(t)) continue;
    const int k = mesh.infinite_index(t);
    if (k >= 0 && face_side(mesh, mesh.tet(t), k, p) == Sign::Positive) {
      return Location{LocationKind::OutsideHull, t, static_cast<std::uint8_t>(k), 0};
    }
  }
  DELMESH_CHECK(false, "point location found no tet containing the point");
  return {};
}

}  // namespace

Location locate(const TetMesh& mesh, const double* p, std::uint32_t hint, std::uint64_t& rng) {
  std::uint32_t t = hint != kNone ? hint : mesh.last_tet();
  DELMESH_CHECK(t != kNone && t < mesh.tet_slots() && !mesh.is_dead(t),
                "locate needs a live starting tet");
  const std::uint64_t budget = 64 + 4ull * mesh.tet_slots();
  int came_from = -1;  // face of t through which the walk entered t
  for (std::uint64_t step = 0; step < budget; ++step) {
    const TetRecord& r = mesh.tet(t);
    const int k = mesh.infinite_index(t);
    if (k >= 0) {
      if (came_from != k && face_side(mesh, r, k, p) != Sign::Positive) {
        // Started in an infinite tet whose hull face does not see p: step inside.
        came_from = mesh.mirror_face(t, k);
        t = mesh.neighbor(t, k);
        continue;
      }
      // Entered through a face that separated p from a finite tet: p is outside.
      return Location{LocationKind::OutsideHull, t, static_cast<std::uint8_t>(k), 0};
    }
    Sign s[4];
    const int start = static_cast<int>(next_random(rng) & 3u);
    int exit = -1;
    for (int n = 0; n < 4; ++n) {
      const int f = (start + n) & 3;
      if (f == came_from) {
        s[f] = Sign::Positive;  // p was strictly beyond this face seen from the last tet
        continue;
      }
      s[f] = face_side(mesh, r, f, p);
      if (s[f] == Sign::Negative) {
        exit = f;
        break;
      }
    }
    if (exit < 0) return classify(t, s);
    came_from = mesh.mirror_face(t, exit);
    t = mesh.neighbor(t, exit);
  }
  return locate_by_scan(mesh, p);
}

}  // namespace delmesh
