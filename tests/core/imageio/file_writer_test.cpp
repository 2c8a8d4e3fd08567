// The background writer runs every task once, reports each task's error by ticket, bounds the tasks in
// flight, and waits for all of them when asked or destroyed.

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <stdexcept>
#include <thread>

#include "core/imageio/file_writer.h"

namespace sp::imageio {
namespace {

TEST(FileWriter, RunsEveryTaskAndReportsErrorsByTicket) {
    std::atomic<int> ran{0};
    FileWriter writer(2, 3, 1 << 20);
    std::uint64_t failing = 0;
    for (int i = 0; i < 10; ++i) {
        const std::uint64_t ticket = writer.submit(1, [&ran, i] {
            ++ran;
            if (i == 4)
                throw std::runtime_error("disk full");
        });
        if (i == 4)
            failing = ticket;
    }
    writer.waitAll();
    EXPECT_EQ(ran.load(), 10);
    EXPECT_EQ(writer.pending(), 0);
    const auto finished = writer.takeFinished();
    ASSERT_EQ(finished.size(), 10u);
    for (const auto& done : finished)
        EXPECT_EQ(done.error, done.ticket == failing ? "disk full" : "") << done.ticket;
    EXPECT_TRUE(writer.takeFinished().empty());
}

TEST(FileWriter, BoundsTheTasksInFlight) {
    std::atomic<int> running{0}, most{0};
    FileWriter writer(4, 2, 1 << 20);
    for (int i = 0; i < 12; ++i)
        writer.submit(1, [&] {
            const int now = ++running;
            for (int seen = most.load(); now > seen && !most.compare_exchange_weak(seen, now);) {
            }
            std::this_thread::sleep_for(std::chrono::milliseconds(2));
            --running;
        });
    EXPECT_LE(writer.pending(), 2);
    writer.waitAll();
    EXPECT_LE(most.load(), 2);
}

TEST(FileWriter, BoundsTheBytesHeldButRunsAnyTaskAlone) {
    std::atomic<int> running{0}, most{0};
    FileWriter writer(4, 8, 100);
    for (int i = 0; i < 8; ++i)
        writer.submit(i == 3 ? 500 : 40, [&] { // 40 + 40 fit, a third does not; 500 runs alone
            const int now = ++running;
            for (int seen = most.load(); now > seen && !most.compare_exchange_weak(seen, now);) {
            }
            std::this_thread::sleep_for(std::chrono::milliseconds(2));
            --running;
        });
    writer.waitAll();
    EXPECT_LE(most.load(), 2);
    EXPECT_EQ(writer.takeFinished().size(), 8u);
}

TEST(FileWriter, DestroyingItWaitsForItsTasks) {
    std::atomic<int> ran{0};
    {
        FileWriter writer(1, 8, 1 << 20);
        for (int i = 0; i < 5; ++i)
            writer.submit(1, [&] {
                std::this_thread::sleep_for(std::chrono::milliseconds(3));
                ++ran;
            });
    }
    EXPECT_EQ(ran.load(), 5);
}

} // namespace
} // namespace sp::imageio
