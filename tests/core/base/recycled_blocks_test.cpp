#include <gtest/gtest.h>

#include <cstring>
#include <thread>
#include <vector>

#include "core/base/recycled_blocks.h"

namespace {
// Sizes no other test of this binary uses: the pool is process-wide.
constexpr std::size_t kSize = (std::size_t(3) << 20) + 17;
} // namespace

TEST(RecycledBlocks, ABlockLetGoIsHandedToTheNextRequestOfItsSize) {
    const std::size_t before = sp::recycledBytesKept();
    char* address = nullptr;
    {
        auto block = sp::takeRecycledBlock(kSize);
        address = block.get();
        std::memset(block.get(), 7, kSize); // all of it is ours to write
        auto copy = block;                  // kept while any owner holds it
        block.reset();
        EXPECT_EQ(sp::recycledBytesKept(), before);
    }
    EXPECT_EQ(sp::recycledBytesKept(), before + kSize);
    auto again = sp::takeRecycledBlock(kSize);
    EXPECT_EQ(again.get(), address);
    EXPECT_EQ(sp::recycledBytesKept(), before);
    auto other = sp::takeRecycledBlock(kSize); // none kept now: a new one
    EXPECT_NE(other.get(), address);
}

TEST(RecycledBlocks, ThePoolKeepsAtMostItsLimitGivingUpTheOldestFirst) {
    const std::size_t size = (std::size_t(5) << 20) + 3;
    std::vector<std::shared_ptr<char[]>> blocks;
    const std::size_t count = sp::kMaxRecycledBytes / size + 3;
    for (std::size_t i = 0; i < count; ++i)
        blocks.push_back(sp::takeRecycledBlock(size));
    const char* newest = blocks.back().get();
    blocks.clear(); // front to back: the first ones are the oldest in the pool
    EXPECT_LE(sp::recycledBytesKept(), sp::kMaxRecycledBytes);
    EXPECT_EQ(sp::takeRecycledBlock(size).get(), newest); // the newest was kept, and is taken first
    // A block larger than the whole pool is never kept.
    { auto huge = sp::takeRecycledBlock(sp::kMaxRecycledBytes + 1); }
    EXPECT_LE(sp::recycledBytesKept(), sp::kMaxRecycledBytes);
}

TEST(RecycledBlocks, ThreadsTakeAndGiveBackConcurrently) {
    const std::size_t size = (std::size_t(2) << 20) + 5;
    std::vector<std::thread> threads;
    for (int t = 0; t < 4; ++t)
        threads.emplace_back([size] {
            for (int i = 0; i < 200; ++i) {
                auto block = sp::takeRecycledBlock(size);
                block[0] = 1;
                block[size - 1] = 2;
            }
        });
    for (std::thread& thread : threads)
        thread.join();
    EXPECT_LE(sp::recycledBytesKept(), sp::kMaxRecycledBytes);
}
