// libFuzzer target for the Wavefront OBJ reader (parse_obj, importers/surface/surface_soup.h):
// any byte string must be either refused with a located Error or accepted as a consistent
// SurfaceSoup (see surface_soup_check.h).
// Build: cmake -DDELMESH_FUZZ=ON with clang; run: build/bin/fuzz_obj -max_total_time=60
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "importers/surface/surface_soup.h"
#include "tests/fuzz/surface_soup_check.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  delmesh::fuzz::check_surface_soup(delmesh::parse_obj(bytes, "fuzz.obj"));
  return 0;
}
