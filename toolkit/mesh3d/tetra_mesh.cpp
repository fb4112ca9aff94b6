// Boundary-face ownership lookup (see tetra_mesh.h): a hash of the sorted vertex triple of
// each boundary face, then one pass over the tets' faces.
#include "toolkit/mesh3d/tetra_mesh.h"

#include <algorithm>
#include <unordered_map>

namespace delmesh {

std::vector<FaceOwner> boundary_face_owners(const TetraMesh& mesh) {
  std::unordered_map<FaceKey, std::uint32_t, FaceKeyHash> index;
  index.reserve(mesh.boundary_faces.size() * 2);
  for (std::uint32_t f = 0; f < mesh.boundary_faces.size(); ++f) index.emplace(face_key(mesh.boundary_faces[f][0], mesh.boundary_faces[f][1], mesh.boundary_faces[f][2]), f);
  std::vector<FaceOwner> owners(mesh.boundary_faces.size());
  for (std::uint32_t t = 0; t < mesh.tets.size(); ++t) {
    const auto& v = mesh.tets[t];
    for (std::uint8_t i = 0; i < 4; ++i) {
      const auto it = index.find(face_key(v[i == 0 ? 1 : 0], v[i <= 1 ? 2 : 1], v[i <= 2 ? 3 : 2]));
      if (it == index.end()) continue;
      FaceOwner& owner = owners[it->second];
      if (owner.tet == ~0u) owner = FaceOwner{t, i};
    }
  }
  return owners;
}

}  // namespace delmesh
