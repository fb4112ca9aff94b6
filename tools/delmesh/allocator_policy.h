// Allocator policy of the delmesh executable: large blocks always in their own memory
// mappings (glibc malloc's mmap threshold pinned at its initial 128 KiB).
//
// glibc starts with blocks of 128 KiB and more in their own mappings, but every time such
// a block is freed it raises the threshold to that block's size (up to 32 MiB), so after
// the first few large vectors have grown once, all later large blocks come from the main
// heap. 3D refinement grows many arrays by doubling (the OpenMesh item and property
// arrays of the facet triangulations, the vertex coordinates, the boundary lookup
// tables); each buffer they outgrow then stays behind as a hole in the heap that is
// resident and mostly never reused, and it is the end of refinement, when the mesh is
// largest, that sets the peak. Pinning the threshold (which also turns off its dynamic
// adjustment) gives every large block back to the system when it is freed: cgal-bear at
// radius-edge 1.414, peak RSS 134 -> 123 MB with the same output and CPU time. Blocks
// below the threshold (the many small ones) are unaffected. A process-wide setting, so
// it belongs to the executable, not to the library.
#pragma once

namespace delmesh::cli {

/// Applies the policy above (glibc only; elsewhere nothing). Call once, before the work.
void use_mapped_large_blocks();

/// The threshold set by use_mapped_large_blocks(), in bytes.
inline constexpr int kLargeBlockBytes = 128 * 1024;

}  // namespace delmesh::cli
