// The public library interface (see delmesh.h): thin entry points over the refiner, the
// importers and the validator.
#include "tools/api/delmesh.h"

#include "refiners/tet3d/angle_bearing.h"

namespace delmesh {

Expected<MeshResult> mesh(const Plc& plc, const MeshOptions& options) { return mesh_plc(plc, options); }

Expected<MeshResult> mesh(const std::filesystem::path& file, const MeshOptions& options,
                          const ImportOptions& import_options) {
  ImportOptions imported = import_options;
  if (options.quality && !(imported.step.surface_min_angle_deg > 0.0))
    imported.step.surface_min_angle_deg = tet3d::tessellation_min_angle_deg(options.max_radius_edge);
  auto plc = import_file(file, imported);
  if (!plc) return plc.error();
  auto result = mesh_plc(*plc, options);
  if (!result) {
    Error error = result.error();
    if (!error.location) error.location = SourceLocation{file.string(), 0};
    return error;
  }
  result->mesh.marker_names.insert(plc->facet_marker_names.begin(), plc->facet_marker_names.end());
  result->mesh.region_names.insert(plc->region_names.begin(), plc->region_names.end());
  return result;
}

std::vector<MeshCheckIssue> check_mesh(const MeshResult& result, const Plc& plc, const CheckMeshOptions& options) {
  // The improvement pass leaves a valid mesh that is no longer Delaunay.
  CheckMeshOptions used = options;
  used.check_delaunay = options.check_delaunay && result.constrained_delaunay;
  return check_mesh(result.mesh, plc, result.boundary_face_facets, used);
}

}  // namespace delmesh
