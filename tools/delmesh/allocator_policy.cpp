// Allocator policy of the delmesh executable (see allocator_policy.h).
#include "tools/delmesh/allocator_policy.h"

#include <cstdlib>  // defines __GLIBC__ on glibc systems

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace delmesh::cli {

void use_mapped_large_blocks() {
#if defined(__GLIBC__)
  mallopt(M_MMAP_THRESHOLD, kLargeBlockBytes);
#endif
}

}  // namespace delmesh::cli
