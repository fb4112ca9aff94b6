// libFuzzer target for the Triangle .node/.poly reader (toolkit/mesh2d/triangle_format_reader.h):
// any byte string must be either accepted, with every segment naming two distinct existing
// vertices and every array consistent, or refused with an Error located in the file.
// Build: cmake -DDELMESH_FUZZ=ON with clang; run: build/bin/fuzz_triangle_format -max_total_time=60
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "toolkit/mesh2d/triangle_format_reader.h"

namespace {

void check(const delmesh::Expected<delmesh::TriangleInput>& result) {
  if (!result) {
    if (!result.error().location) __builtin_trap();
    return;
  }
  const delmesh::Pslg& p = result->pslg;
  for (const auto& s : p.segments) {
    if (s[0] >= p.points.size() || s[1] >= p.points.size() || s[0] == s[1]) __builtin_trap();
  }
  if (!p.point_markers.empty() && p.point_markers.size() != p.points.size()) __builtin_trap();
  if (!p.segment_markers.empty() && p.segment_markers.size() != p.segments.size()) __builtin_trap();
  if (p.point_attributes.size() != p.points.size() * static_cast<std::size_t>(p.num_point_attributes)) {
    __builtin_trap();
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  check(delmesh::parse_triangle_node(text, "fuzz.node"));
  check(delmesh::parse_triangle_poly(text, "fuzz.poly",
                                     [&] { return delmesh::parse_triangle_node(text, "fuzz.node"); }));
  return 0;
}
