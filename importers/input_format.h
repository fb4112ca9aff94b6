// Which importer reads a file: decided by its extension (case-insensitive).
#pragma once

#include <filesystem>
#include <string_view>

namespace delmesh {

enum class InputFormat {
  Step,      ///< .step .stp (also .brep .iges .igs through the same OCCT importer)
  Brep,
  Iges,
  Stl,
  Off,
  Obj,
  Ply,
  TetgenPoly,   ///< 3D .poly
  TetgenSmesh,  ///< .smesh
  Node,         ///< .node point set
  Unknown,
};

InputFormat detect_input_format(const std::filesystem::path& path);
std::string_view to_string(InputFormat format);

}  // namespace delmesh
