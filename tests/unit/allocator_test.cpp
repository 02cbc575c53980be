// engine/core/allocator.hpp, applied before main by engine/core/allocator_at_start.cpp (compiled into this program
// as into every other): a block the size of a large factor comes from the heap, not from mmap, and once freed it
// stays in the heap for the next one (nothing is trimmed back to the system). The test does not apply the policy
// itself: it fails if the program is built without allocator_at_start.cpp. Not under AddressSanitizer, whose own
// allocator mallinfo2 does not describe.
#include <gtest/gtest.h>

#include <cstdlib>
#include <cstring>

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace loom {

#if defined(__GLIBC__) && !defined(__SANITIZE_ADDRESS__)
TEST(Allocator, ALargeFreedBlockStaysInTheHeapForTheNext) {
  const char* policy = std::getenv("LOOM_MALLOC");
  ASSERT_FALSE(policy && std::strcmp(policy, "system") == 0) << "LOOM_MALLOC=system turns off the policy this test checks";
  constexpr std::size_t kBytes = std::size_t(64) << 20;  // above glibc's largest dynamic mmap threshold (32 MiB)
  const std::size_t mapped_before = mallinfo2().hblks;
  char* block = static_cast<char*>(std::malloc(kBytes));
  ASSERT_NE(block, nullptr);
  std::memset(block, 1, kBytes);
  EXPECT_EQ(mallinfo2().hblks, mapped_before);  // not a mapping of its own: glibc's default would have mapped it
  std::free(block);
  EXPECT_GE(mallinfo2().fordblks, kBytes);  // free in the heap, not given back
  char* again = static_cast<char*>(std::malloc(kBytes));
  ASSERT_NE(again, nullptr);
  EXPECT_EQ(again, block);  // the same memory, already mapped
  std::free(again);
}
#endif

}  // namespace loom
