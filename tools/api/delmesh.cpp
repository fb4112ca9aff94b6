// The public library interface (see delmesh.h): thin entry points over the refiner, the
// importers and the validator.
#include "tools/api/delmesh.h"

namespace delmesh {

Expected<MeshResult> mesh(const Plc& plc, const MeshOptions& options) { return mesh_plc(plc, options); }

std::vector<MeshCheckIssue> check_mesh(const MeshResult& result, const Plc& plc, const CheckMeshOptions& options) {
  return check_mesh(result.mesh, plc, result.boundary_face_facets, options);
}

}  // namespace delmesh
