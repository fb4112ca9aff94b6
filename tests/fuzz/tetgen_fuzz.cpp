// libFuzzer target for the TetGen .node/.poly/.smesh reader (parse_tetgen,
// importers/tetgen/tetgen_reader.h, with the name and colour comment tables it reads
// through toolkit/plc/plc_tables.h). The first input byte picks the file kind (0: .node,
// 1: .poly, 2: .smesh, by value modulo 3); the rest is the file text. No .node file is
// given, so an empty node list must be refused. Any input must be either refused with a
// located Error or accepted as a PLC whose facets, segments and markers only name
// existing points.
// Build: cmake -DDELMESH_FUZZ=ON with clang; run: build/bin/fuzz_tetgen -max_total_time=60
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "importers/tetgen/tetgen_reader.h"

namespace {

void check(const delmesh::Expected<delmesh::Plc>& result) {
  if (!result) {
    if (!result.error().location) __builtin_trap();
    return;
  }
  const delmesh::Plc& plc = *result;
  const std::size_t n = plc.points.size();
  if (!plc.point_markers.empty() && plc.point_markers.size() != n) __builtin_trap();
  for (const auto& facet : plc.facets) {
    for (const auto& polygon : facet.polygons) {
      for (const auto v : polygon) {
        if (v >= n) __builtin_trap();
      }
    }
  }
  for (const auto& s : plc.segments) {
    if (s.a >= n || s.b >= n) __builtin_trap();
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  static constexpr delmesh::TetgenFileKind kinds[] = {
      delmesh::TetgenFileKind::Node, delmesh::TetgenFileKind::Poly, delmesh::TetgenFileKind::Smesh};
  static constexpr const char* names[] = {"fuzz.node", "fuzz.poly", "fuzz.smesh"};
  const std::size_t k = data[0] % 3;
  const std::string_view text(reinterpret_cast<const char*>(data + 1), size - 1);
  check(delmesh::parse_tetgen(text, kinds[k], names[k]));
  return 0;
}
