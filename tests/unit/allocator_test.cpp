// engine/core/allocator.hpp: under loom's policy a block the size of a large factor comes from the heap, not from
// mmap, and once freed it stays in the heap for the next one (nothing is trimmed back to the system).
#include <gtest/gtest.h>

#include <cstdlib>
#include <cstring>

#include "engine/core/allocator.hpp"

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace loom {

#if defined(__GLIBC__)
TEST(Allocator, ALargeFreedBlockStaysInTheHeapForTheNext) {
  ASSERT_EQ(std::getenv("LOOM_MALLOC"), nullptr) << "the test checks loom's policy; LOOM_MALLOC=system turns it off";
  keep_freed_memory_in_heap();
  constexpr std::size_t kBytes = std::size_t(64) << 20;  // above glibc's largest dynamic mmap threshold (32 MiB)
  const std::size_t mapped_before = mallinfo2().hblks;
  char* block = static_cast<char*>(std::malloc(kBytes));
  ASSERT_NE(block, nullptr);
  std::memset(block, 1, kBytes);
  EXPECT_EQ(mallinfo2().hblks, mapped_before);  // not a mapping of its own: glibc would have mapped it
  std::free(block);
  EXPECT_GE(mallinfo2().fordblks, kBytes);  // free in the heap, not given back
  char* again = static_cast<char*>(std::malloc(kBytes));
  ASSERT_NE(again, nullptr);
  EXPECT_EQ(again, block);  // the same memory, already mapped
  std::free(again);
}
#endif

}  // namespace loom
