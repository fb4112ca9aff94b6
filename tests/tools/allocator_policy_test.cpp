// The delmesh executable's allocator policy (tools/delmesh/allocator_policy.h): once it
// is applied, freeing a large block no longer raises glibc's mmap threshold, so a later
// block of 256 KiB still gets its own mapping instead of coming from the main heap.
#include <gtest/gtest.h>

#include <cstdlib>
#include <cstring>

#if defined(__GLIBC__)
#include <malloc.h>
#endif

#include "tools/delmesh/allocator_policy.h"

namespace delmesh::cli {
namespace {

#if defined(__GLIBC__)
/// Bytes in blocks that have their own mapping.
std::size_t mapped_bytes() { return mallinfo2().hblkhd; }

/// Published blocks: the compiler may not drop their allocations.
char* volatile published = nullptr;
#endif

TEST(AllocatorPolicy, LargeBlocksStayMappedAfterALargerOneIsFreed) {
  use_mapped_large_blocks();
#if defined(__GLIBC__)
  // Without the policy, freeing this 4 MiB block would raise the threshold to 4 MiB.
  char* big = static_cast<char*>(std::malloc(std::size_t{4} << 20));
  ASSERT_NE(big, nullptr);
  std::memset(big, 1, std::size_t{4} << 20);
  published = big;
  EXPECT_GE(mapped_bytes(), std::size_t{4} << 20);
  std::free(big);
  const std::size_t before = mapped_bytes();
  const std::size_t size = 2 * static_cast<std::size_t>(kLargeBlockBytes);
  char* block = static_cast<char*>(std::malloc(size));
  ASSERT_NE(block, nullptr);
  std::memset(block, 2, size);
  published = block;
  const std::size_t after = mapped_bytes();
  EXPECT_EQ(block[size - 1], 2);
  std::free(block);
  EXPECT_GE(after, before + size);
#endif
}

}  // namespace
}  // namespace delmesh::cli
