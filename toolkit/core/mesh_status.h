// Outcome of a meshing run that produced a valid mesh (failures are Errors instead).
#pragma once

#include <cstdint>

namespace delmesh {

enum class MeshStatus : std::uint8_t {
  Complete,  ///< every requested bound is met
  Partial,   ///< a valid mesh, but some bounds are unmet (small input angles, Steiner budget)
};

inline const char* to_string(MeshStatus status) {
  return status == MeshStatus::Complete ? "Complete" : "Partial";
}

}  // namespace delmesh
