#include <gtest/gtest.h>

#include <cstdlib>
#include <cstring>
#include <malloc.h>
#include <vector>

#include "core/base/process_memory.h"

TEST(ProcessMemory, MemoryFreedAtTheTopOfTheHeapStaysWithTheProcess) {
    if (!sp::keepFreedMemory())
        GTEST_SKIP() << "not glibc's allocator (a sanitizer's), or MALLOC_* thresholds in the environment";
    EXPECT_TRUE(sp::keepFreedMemory()); // decided once
    // Three blocks under the 32 MiB mmap threshold come from the heap; freed together they leave 90 MiB free
    // at its top, past the 64 MiB at which glibc's own settings would hand it back, under the 128 MiB kept.
    constexpr std::size_t kBlock = std::size_t(30) << 20;
    const struct mallinfo2 before = mallinfo2();
    std::vector<void*> blocks;
    for (int i = 0; i < 3; ++i) {
        blocks.push_back(std::malloc(kBlock));
        ASSERT_NE(blocks.back(), nullptr);
        std::memset(blocks.back(), 1, kBlock);
    }
    const struct mallinfo2 held = mallinfo2();
    EXPECT_EQ(held.hblks, before.hblks) << "a block under the threshold was mapped on its own";
    for (void* block : blocks)
        std::free(block);
    const struct mallinfo2 after = mallinfo2();
    EXPECT_EQ(after.arena, held.arena) << "the heap was trimmed";
    EXPECT_GE(after.fordblks, 3 * kBlock);
}

TEST(ProcessMemory, TheEnvironmentsThresholdsWin) {
    // In a new process (the death test re-runs this binary), so that the decision is not already made.
    GTEST_FLAG_SET(death_test_style, "threadsafe");
    EXPECT_EXIT(
        {
            ::setenv("MALLOC_TRIM_THRESHOLD_", "131072", 1);
            std::exit(sp::keepFreedMemory() ? 1 : 0);
        },
        ::testing::ExitedWithCode(0), "");
}
