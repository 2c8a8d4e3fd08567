#include "core/rpc/spin_poll.h"

#include <sched.h>

#include <algorithm>
#include <charconv>
#include <cstdlib>
#include <string>

#include "core/base/error.h"

namespace sp::rpc {

namespace {
constexpr int kDefaultSpinUs = 100;
constexpr int kMaxSpinUs = 10000;
} // namespace

std::chrono::microseconds spinFromEnvironment() {
    int microseconds = kDefaultSpinUs;
    if (const char* env = std::getenv("SPEAR_RPC_SPIN_US")) {
        const std::string value = env;
        const auto [end, error] = std::from_chars(value.data(), value.data() + value.size(), microseconds);
        SP_CHECK(error == std::errc() && end == value.data() + value.size() && microseconds >= 0 &&
                     microseconds <= kMaxSpinUs,
                 InvalidArgument,
                 "spear-server: SPEAR_RPC_SPIN_US must be a whole number of microseconds from 0 to ",
                 kMaxSpinUs, ", got '", value, "'");
    }
    cpu_set_t cpus;
    if (::sched_getaffinity(0, sizeof(cpus), &cpus) == 0 && CPU_COUNT(&cpus) < 2)
        return std::chrono::microseconds(0);
    return std::chrono::microseconds(microseconds);
}

int pollSpinning(pollfd* fds, nfds_t count, int timeoutMs, std::chrono::microseconds spin) {
    if (spin.count() <= 0 || timeoutMs == 0)
        return ::poll(fds, count, timeoutMs);
    using Clock = std::chrono::steady_clock;
    const Clock::time_point start = Clock::now();
    if (timeoutMs > 0 && spin > std::chrono::milliseconds(timeoutMs))
        spin = std::chrono::milliseconds(timeoutMs);
    while (true) {
        const int ready = ::poll(fds, count, 0);
        if (ready != 0)
            return ready;
        if (Clock::now() - start >= spin)
            break;
        ::sched_yield(); // whatever else is runnable on this CPU goes first
    }
    if (timeoutMs < 0)
        return ::poll(fds, count, -1);
    const auto spent = std::chrono::duration_cast<std::chrono::milliseconds>(Clock::now() - start);
    return ::poll(fds, count, std::max(0, timeoutMs - int(spent.count())));
}

} // namespace sp::rpc
