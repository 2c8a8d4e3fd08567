#include <gtest/gtest.h>

#include <poll.h>
#include <sched.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <string>
#include <thread>

#include "core/base/error.h"
#include "core/rpc/spin_poll.h"

using namespace std::chrono_literals;
using sp::rpc::pollSpinning;
using sp::rpc::spinFromEnvironment;

namespace {

// Sets SPEAR_RPC_SPIN_US (or unsets it, for nullptr) while alive.
class SpinVariable {
  public:
    explicit SpinVariable(const char* value) {
        if (value)
            ::setenv("SPEAR_RPC_SPIN_US", value, 1);
        else
            ::unsetenv("SPEAR_RPC_SPIN_US");
    }
    ~SpinVariable() { ::unsetenv("SPEAR_RPC_SPIN_US"); }
};

int allowedCpus() {
    cpu_set_t cpus;
    EXPECT_EQ(::sched_getaffinity(0, sizeof(cpus), &cpus), 0);
    return CPU_COUNT(&cpus);
}

// A connected pair of Unix stream sockets, closed when it goes.
struct SocketPair {
    int fds[2] = {-1, -1};
    SocketPair() { EXPECT_EQ(::socketpair(AF_UNIX, SOCK_STREAM, 0, fds), 0); }
    ~SocketPair() {
        ::close(fds[0]);
        ::close(fds[1]);
    }
};

} // namespace

TEST(SpinPoll, TheEnvironmentSetsTheBudget) {
    if (allowedCpus() < 2)
        GTEST_SKIP() << "this process may run on one CPU only, where the budget is always none";
    {
        SpinVariable unset(nullptr);
        EXPECT_EQ(spinFromEnvironment(), 100us);
    }
    {
        SpinVariable zero("0");
        EXPECT_EQ(spinFromEnvironment(), 0us);
    }
    {
        SpinVariable most("10000");
        EXPECT_EQ(spinFromEnvironment(), 10000us);
    }
}

TEST(SpinPoll, ABadValueIsRefusedByName) {
    for (const char* bad : {"", "abc", "-1", "10001", "12x", " 5"}) {
        SpinVariable variable(bad);
        try {
            spinFromEnvironment();
            ADD_FAILURE() << "accepted '" << bad << "'";
        } catch (const sp::InvalidArgument& error) {
            EXPECT_NE(std::string(error.what())
                          .find("SPEAR_RPC_SPIN_US must be a whole number of microseconds "
                                "from 0 to 10000, got '" +
                                std::string(bad) + "'"),
                      std::string::npos)
                << error.what();
        }
    }
}

TEST(SpinPoll, NoneOnOneCpu) {
    // The affinity is the calling thread's: this thread is restored before it ends.
    cpu_set_t saved;
    ASSERT_EQ(::sched_getaffinity(0, sizeof(saved), &saved), 0);
    int first = 0;
    while (!CPU_ISSET(first, &saved))
        ++first;
    cpu_set_t one;
    CPU_ZERO(&one);
    CPU_SET(first, &one);
    ASSERT_EQ(::sched_setaffinity(0, sizeof(one), &one), 0);
    SpinVariable variable("5000");
    const auto spin = spinFromEnvironment();
    ASSERT_EQ(::sched_setaffinity(0, sizeof(saved), &saved), 0);
    EXPECT_EQ(spin, 0us);
}

TEST(SpinPoll, ReturnsWhatPollReturns) {
    SocketPair pair;
    pollfd fd{pair.fds[0], POLLIN, 0};
    // Nothing to read: the timeout passes, after the spin.
    EXPECT_EQ(pollSpinning(&fd, 1, 1, 200us), 0);
    EXPECT_EQ(pollSpinning(&fd, 1, 0, 200us), 0);
    // A spin longer than the timeout is cut to it.
    EXPECT_EQ(pollSpinning(&fd, 1, 1, 10000us), 0);
    // Something to read before the call, with and without a spin.
    ASSERT_EQ(::write(pair.fds[1], "x", 1), 1);
    EXPECT_EQ(pollSpinning(&fd, 1, -1, 100us), 1);
    EXPECT_EQ(fd.revents, POLLIN);
    EXPECT_EQ(pollSpinning(&fd, 1, -1, 0us), 1);
    // The peer gone.
    ::close(pair.fds[1]);
    pair.fds[1] = -1;
    EXPECT_EQ(pollSpinning(&fd, 1, -1, 100us), 1);
    EXPECT_TRUE(fd.revents & POLLHUP);
}

TEST(SpinPoll, AMessageThatComesWhileSpinningOrAfterIsSeen) {
    // Sent during the spin (1 ms into a budget of 10), and sent once the spin is over and the
    // call sleeps in poll().
    for (const auto& [spin, delay] : {std::pair{10000us, 1ms}, std::pair{50us, 20ms}}) {
        SocketPair pair;
        std::thread writer([&, delay = delay] {
            std::this_thread::sleep_for(delay);
            EXPECT_EQ(::write(pair.fds[1], "x", 1), 1);
        });
        pollfd fd{pair.fds[0], POLLIN, 0};
        EXPECT_EQ(pollSpinning(&fd, 1, -1, spin), 1);
        EXPECT_EQ(fd.revents, POLLIN);
        writer.join();
    }
}
