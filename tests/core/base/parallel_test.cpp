#include "core/base/parallel.h"

#include <atomic>
#include <chrono>
#include <mutex>
#include <set>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

namespace sp {
namespace {

TEST(ParallelFor, RunsEveryTaskOnceOnSeveralThreads) {
    std::vector<std::atomic<int>> runs(64);
    std::mutex mutex;
    std::set<std::thread::id> threads;
    parallelFor(64, 4, [&](int i) {
        ++runs[size_t(i)];
        std::this_thread::sleep_for(std::chrono::microseconds(200)); // long enough for the workers to join
        std::lock_guard lock(mutex);
        threads.insert(std::this_thread::get_id());
    });
    for (const auto& count : runs)
        EXPECT_EQ(count, 1);
    EXPECT_GT(threads.size(), 1u);
    EXPECT_LE(threads.size(), 4u);
    EXPECT_TRUE(threads.contains(std::this_thread::get_id())); // the caller takes tasks too
}

TEST(ParallelRanges, CoverEveryItemOnceInRangesOnTheirBoundaries) {
    // 10,000 items in up to 6 ranges starting at multiples of 64, of at least 100 items: each item once.
    struct Case {
        std::size_t count, granularity, least;
        int parts;
        std::size_t ranges; // expected
    };
    for (const Case& c : {Case{10000, 64, 100, 6, 6}, Case{10000, 64, 4000, 6, 2}, Case{150, 8, 100, 6, 1},
                          Case{0, 8, 1, 4, 0}, Case{7, 1, 1, 16, 7}}) {
        std::vector<std::atomic<int>> seen(c.count);
        std::mutex mutex;
        std::vector<std::pair<std::size_t, std::size_t>> ranges;
        parallelRanges(c.count, c.granularity, c.least, c.parts, 4, [&](std::size_t begin, std::size_t end) {
            for (std::size_t i = begin; i < end; ++i)
                ++seen[i];
            std::lock_guard lock(mutex);
            ranges.emplace_back(begin, end);
        });
        const std::string label = "count " + std::to_string(c.count) + ", least " + std::to_string(c.least);
        for (const auto& count : seen)
            EXPECT_EQ(count, 1) << label;
        EXPECT_EQ(ranges.size(), c.ranges) << label;
        for (const auto& [begin, end] : ranges) {
            EXPECT_EQ(begin % c.granularity, 0u) << label;
            EXPECT_LT(begin, end) << label;
        }
    }
}

TEST(ParallelFor, OneThreadOrOneTaskRunsInOrderOnTheCaller) {
    std::vector<int> order;
    parallelFor(5, 1, [&](int i) { order.push_back(i); });
    EXPECT_EQ(order, (std::vector<int>{0, 1, 2, 3, 4}));
    const auto caller = std::this_thread::get_id();
    parallelFor(1, 8, [&](int) { EXPECT_EQ(std::this_thread::get_id(), caller); });
    parallelFor(0, 8, [&](int) { ADD_FAILURE() << "no task to run"; });
}

TEST(ParallelFor, TheFirstErrorIsRethrownAfterEveryTaskRan) {
    std::atomic<int> ran = 0;
    try {
        parallelFor(16, 4, [&](int i) {
            ++ran;
            if (i % 5 == 0)
                throw std::runtime_error("task " + std::to_string(i) + " failed");
        });
        FAIL() << "expected an error";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find(" failed"), std::string::npos);
    }
    EXPECT_EQ(ran, 16);
    // The pool is usable after an error.
    std::atomic<int> after = 0;
    parallelFor(8, 4, [&](int) { ++after; });
    EXPECT_EQ(after, 8);
}

TEST(ParallelFor, ATaskAskingForMoreRunsItInline) {
    std::atomic<int> inner = 0;
    parallelFor(4, 4, [&](int) { parallelFor(3, 4, [&](int) { ++inner; }); });
    EXPECT_EQ(inner, 12);
}

TEST(ParallelFor, ConcurrentCallersTakeTurns) {
    std::atomic<int> total = 0;
    std::vector<std::thread> callers;
    for (int c = 0; c < 3; ++c)
        callers.emplace_back([&] {
            for (int k = 0; k < 20; ++k)
                parallelFor(8, 3, [&](int) { ++total; });
        });
    for (std::thread& caller : callers)
        caller.join();
    EXPECT_EQ(total, 3 * 20 * 8);
}

} // namespace
} // namespace sp
