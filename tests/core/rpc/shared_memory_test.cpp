#include <gtest/gtest.h>

#include <fcntl.h>
#include <signal.h>
#include <sys/mman.h>
#include <unistd.h>

#include <cstring>

#include "core/base/error.h"
#include "core/rpc/shared_memory.h"

using sp::rpc::SharedMemorySegment;

namespace {
// What a hostile client does to a segment the server has mapped.
void shrink(const std::string& name, off_t size) {
    const int fd = ::shm_open(name.c_str(), O_RDWR, 0);
    ASSERT_GE(fd, 0);
    ASSERT_EQ(::ftruncate(fd, size), 0);
    ::close(fd);
}
} // namespace

TEST(SharedMemory, HoldsAsksTheSegmentNotTheMapping) {
    SharedMemorySegment created = SharedMemorySegment::create(1 << 20);
    SharedMemorySegment opened = SharedMemorySegment::open(created.name(), 1 << 20);
    EXPECT_TRUE(opened.holds(1 << 20));
    EXPECT_FALSE(opened.holds((1 << 20) + 1)); // more than is mapped
    shrink(created.name(), 4096);
    EXPECT_TRUE(opened.holds(4096));
    EXPECT_FALSE(opened.holds(4097));
    // A shrunk segment cannot be opened for more than it holds.
    EXPECT_THROW(SharedMemorySegment::open(created.name(), 1 << 20), sp::InvalidArgument);
    created.unlink();
}

TEST(SharedMemory, TruncationWhileInUseRevokesTheSegmentInsteadOfCrashing) {
    sp::rpc::guardAgainstTruncation();
    SharedMemorySegment created = SharedMemorySegment::create(1 << 20);
    SharedMemorySegment opened = SharedMemorySegment::open(created.name(), 1 << 20);
    const uint64_t faults = sp::rpc::truncationFaults();
    shrink(created.name(), 0);              // between a size check and the access: no check can see it coming
    std::memset(opened.data(), 7, 1 << 20); // was SIGBUS
    EXPECT_TRUE(opened.revoked());
    EXPECT_FALSE(opened.holds(1));
    EXPECT_EQ(sp::rpc::truncationFaults(), faults + 1);
    EXPECT_EQ(static_cast<const char*>(opened.data())[(1 << 20) - 1], 7); // private memory now
    created.unlink();
}

TEST(SharedMemoryDeathTest, FaultsOutsideSegmentsStillCrash) {
    sp::rpc::guardAgainstTruncation();
    EXPECT_EXIT(
        {
            // A shrunk file mapping that is not a segment: the guard must not swallow its fault.
            const int fd = ::memfd_create("not-a-segment", 0);
            [[maybe_unused]] int sized = ::ftruncate(fd, 4096);
            auto* data =
                static_cast<volatile char*>(::mmap(nullptr, 4096, PROT_READ | PROT_WRITE, MAP_SHARED, fd, 0));
            sized = ::ftruncate(fd, 0);
            data[0] = 1;
            ::_exit(0);
        },
        testing::KilledBySignal(SIGBUS), "");
}

TEST(SharedMemory, NamesCarryThePidAndRandomBitsNoOneCanGuess) {
    // A counter made every name predictable: another user could create "/spear-<pid>-<n+1>" first, and the
    // server's next segment would fail to be created (O_EXCL) or be one of theirs.
    SharedMemorySegment first = SharedMemorySegment::create(64);
    SharedMemorySegment second = SharedMemorySegment::create(64);
    const std::string prefix = "/spear-" + std::to_string(::getpid()) + "-";
    for (const SharedMemorySegment* segment : {&first, &second}) {
        ASSERT_TRUE(segment->name().starts_with(prefix)) << segment->name();
        const std::string suffix = segment->name().substr(prefix.size());
        EXPECT_EQ(suffix.size(), 16u);
        EXPECT_EQ(suffix.find_first_not_of("0123456789abcdef"), std::string::npos) << suffix;
    }
    EXPECT_NE(first.name(), second.name());
    first.unlink();
    second.unlink();
}
