// Input format detection by extension (see input_format.h).
#include "importers/input_format.h"

#include <algorithm>
#include <cctype>
#include <string>

namespace delmesh {

InputFormat detect_input_format(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (ext == ".step" || ext == ".stp") return InputFormat::Step;
  if (ext == ".brep" || ext == ".brp") return InputFormat::Brep;
  if (ext == ".iges" || ext == ".igs") return InputFormat::Iges;
  if (ext == ".stl") return InputFormat::Stl;
  if (ext == ".off") return InputFormat::Off;
  if (ext == ".obj") return InputFormat::Obj;
  if (ext == ".ply") return InputFormat::Ply;
  if (ext == ".poly") return InputFormat::TetgenPoly;
  if (ext == ".smesh") return InputFormat::TetgenSmesh;
  if (ext == ".node") return InputFormat::Node;
  return InputFormat::Unknown;
}

std::string_view to_string(InputFormat format) {
  switch (format) {
    case InputFormat::Step: return "STEP";
    case InputFormat::Brep: return "BREP";
    case InputFormat::Iges: return "IGES";
    case InputFormat::Stl: return "STL";
    case InputFormat::Off: return "OFF";
    case InputFormat::Obj: return "OBJ";
    case InputFormat::Ply: return "PLY";
    case InputFormat::TetgenPoly: return "TetGen .poly";
    case InputFormat::TetgenSmesh: return "TetGen .smesh";
    case InputFormat::Node: return ".node";
    case InputFormat::Unknown: return "unknown";
  }
  return "unknown";
}

}  // namespace delmesh
