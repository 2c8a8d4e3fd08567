#include "core/base/progress.h"

#include <atomic>
#include <cstdio>

namespace sp::base {

namespace {
std::atomic<ProgressSink> gSink{nullptr};

constexpr std::chrono::milliseconds kQuietStart{500}; // work done sooner shows nothing
constexpr std::chrono::milliseconds kInterval{100};

void writeToStderr(std::string_view task, double done, double total, bool finished) {
    std::fprintf(stderr, "[spear-progress] %.17g %.17g %d %.*s\n", done, total, finished ? 1 : 0,
                 int(task.size()), task.data());
    std::fflush(stderr);
}
} // namespace

void setProgressSink(ProgressSink sink) {
    gSink.store(sink);
}

Progress::Progress(std::string task, double total)
    : task_(std::move(task)), total_(total), start_(Clock::now()), last_(start_) {}

Progress::~Progress() {
    if (reported_ || Clock::now() - start_ >= kQuietStart)
        report(true);
}

void Progress::set(double done) {
    done_ = done;
    const Clock::time_point now = Clock::now();
    if (now - start_ < kQuietStart || now - last_ < kInterval)
        return;
    last_ = now;
    report(false);
}

void Progress::report(bool finished) {
    reported_ = true;
    const ProgressSink sink = gSink.load();
    try {
        (sink ? sink : &writeToStderr)(task_, done_, total_, finished);
    } catch (...) { // progress is never worth failing the work for (and ~Progress must not throw)
    }
}

} // namespace sp::base
