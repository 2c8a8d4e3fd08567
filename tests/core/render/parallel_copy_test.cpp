// parallelCopy(): every byte lands where memcpy would put it, whatever the size, alignment and thread
// count, and concurrent callers take turns at the workers.

#include "core/render/parallel_copy.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <thread>
#include <vector>

namespace sp::render {
namespace {

std::vector<std::uint8_t> pattern(std::size_t bytes, std::uint32_t seed) {
    std::vector<std::uint8_t> data(bytes);
    std::uint32_t x = seed;
    for (std::uint8_t& b : data) {
        x = x * 1664525u + 1013904223u;
        b = std::uint8_t(x >> 24);
    }
    return data;
}

TEST(ParallelCopyTest, CopiesEveryByteForAnySizeAndThreadCount) {
    // Below, at and above the split threshold (2 MiB), sizes that are not multiples of a page, and an
    // offset source and destination.
    const std::size_t sizes[] = {
        0, 1, 4095, std::size_t(2) << 20, (std::size_t(2) << 20) + 1, 8294400, (std::size_t(13) << 20) + 123};
    for (std::size_t bytes : sizes)
        for (int threads : {1, 2, 3, 4, 8}) {
            const std::vector<std::uint8_t> source = pattern(bytes + 3, std::uint32_t(bytes) + 7);
            std::vector<std::uint8_t> destination(bytes + 5, 0xab);
            parallelCopy(destination.data() + 1, source.data() + 3, bytes, threads);
            EXPECT_EQ(destination[0], 0xab) << bytes << " bytes, " << threads << " threads: wrote before";
            EXPECT_EQ(destination[bytes + 1], 0xab)
                << bytes << " bytes, " << threads << " threads: wrote past";
            EXPECT_TRUE(std::equal(source.begin() + 3, source.end(), destination.begin() + 1))
                << bytes << " bytes, " << threads << " threads";
        }
}

TEST(ParallelCopyTest, ConcurrentCallersEachGetTheirOwnBytes) {
    constexpr std::size_t kBytes = std::size_t(6) << 20;
    std::vector<std::thread> callers;
    std::vector<int> failures(4, 0);
    for (int c = 0; c < 4; ++c)
        callers.emplace_back([&, c] {
            const std::vector<std::uint8_t> source = pattern(kBytes, std::uint32_t(100 + c));
            std::vector<std::uint8_t> destination(kBytes);
            for (int round = 0; round < 20; ++round) {
                std::fill(destination.begin(), destination.end(), 0);
                parallelCopy(destination.data(), source.data(), kBytes, 4);
                failures[std::size_t(c)] += destination != source;
            }
        });
    for (std::thread& caller : callers)
        caller.join();
    for (int c = 0; c < 4; ++c)
        EXPECT_EQ(failures[std::size_t(c)], 0) << "caller " << c;
}

TEST(ParallelCopyTest, DefaultThreadsAreBetweenOneAndFour) {
    const int threads = defaultCopyThreads();
    EXPECT_GE(threads, 1);
    EXPECT_LE(threads, 4);
}

} // namespace
} // namespace sp::render
