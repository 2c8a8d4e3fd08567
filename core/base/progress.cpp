#include "core/base/progress.h"

#include <atomic>
#include <cstdio>

#include "core/base/listeners.h"

namespace sp::base {

namespace {
std::atomic<ProgressSink> gProgressSink{nullptr};
BusyHook gBusyHook = nullptr; // (set and called on the one thread that runs the work)
void* gBusyContext = nullptr;
std::atomic<bool> gStopRequested{false};
static_assert(std::atomic<bool>::is_always_lock_free); // requestStop() runs in signal handlers

constexpr std::chrono::milliseconds kBusyAfter{1000};
constexpr std::chrono::milliseconds kBusyInterval{50};

constexpr std::chrono::milliseconds kQuietStart{500}; // work done sooner shows nothing
constexpr std::chrono::milliseconds kInterval{100};

void writeToStderr(std::string_view task, double done, double total, bool finished) {
    std::fprintf(stderr, "[spear-progress] %.17g %.17g %d %.*s\n", done, total, finished ? 1 : 0,
                 int(task.size()), task.data());
    std::fflush(stderr);
}
} // namespace

void setProgressSink(ProgressSink sink) {
    gProgressSink.store(sink);
}

namespace {
ListenerList<std::string_view, double, double, bool>& progressListeners() {
    static ListenerList<std::string_view, double, double, bool> instance;
    return instance;
}
} // namespace

int addProgressListener(ProgressListener listener) {
    return progressListeners().add(std::move(listener));
}

void removeProgressListener(int id) {
    progressListeners().remove(id);
}

void setBusyHook(BusyHook hook, void* context) {
    gBusyHook = hook;
    gBusyContext = context;
}

void requestStop() {
    gStopRequested.store(true);
}

bool stopRequested() {
    return gStopRequested.load(std::memory_order_relaxed);
}

Progress::Progress(std::string task, double total)
    : task_(std::move(task)), total_(total), start_(Clock::now()), last_(start_), lastBusy_(start_) {}

Progress::~Progress() {
    if (reported_ || Clock::now() - start_ >= kQuietStart)
        report(true);
}

void Progress::set(double done) {
    done_ = done;
    const Clock::time_point now = Clock::now();
    if (gBusyHook && now - start_ >= kBusyAfter && now - lastBusy_ >= kBusyInterval) {
        lastBusy_ = now;
        gBusyHook(gBusyContext, task_, std::chrono::duration<double>(now - start_).count());
    }
    if (now - start_ < kQuietStart || now - last_ < kInterval)
        return;
    last_ = now;
    report(false);
}

void Progress::report(bool finished) {
    reported_ = true;
    const ProgressSink sink = gProgressSink.load();
    try {
        (sink ? sink : &writeToStderr)(task_, done_, total_, finished);
        progressListeners().tell(task_, done_, total_, finished);
    } catch (...) { // progress is never worth failing the work for (and ~Progress must not throw)
    }
}

} // namespace sp::base
