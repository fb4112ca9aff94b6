// VTK XML unstructured grid (.vtu, ASCII) output of a 2D triangle mesh, for ParaView and
// other VTK readers. Points get z = 0. Cell data: "min_angle" (degrees) for every triangle
// and "region" (the regional attribute) when the mesh carries triangle attributes. Point
// data: "marker" when the mesh carries point markers, and the point attributes as
// "attribute_1", "attribute_2", ...
#pragma once

#include <filesystem>

#include "toolkit/core/error.h"
#include "toolkit/mesh2d/triangle_mesh.h"

namespace delmesh {

Expected<void> write_vtu(const std::filesystem::path& path, const TriangleMesh& mesh);

}  // namespace delmesh
