#include "core/base/log.h"

#include <atomic>
#include <cstdio>
#include <mutex>

#include "core/base/listeners.h"

namespace sp::base {

namespace {
std::atomic<LogSink> gLogSink{nullptr};

ListenerList<std::string_view, int, std::string_view>& listeners() {
    static ListenerList<std::string_view, int, std::string_view> instance;
    return instance;
}
} // namespace

void setLogSink(LogSink sink) {
    gLogSink.store(sink);
}

int addLogListener(LogListener listener) {
    return listeners().add(std::move(listener));
}

void removeLogListener(int id) {
    listeners().remove(id);
}

void writeLogLine(std::string_view file, int line, std::string_view message) {
    static std::mutex mutex;
    // Only the file's base name: full build paths make logs noisy and machine-specific.
    if (auto slash = file.rfind('/'); slash != std::string_view::npos)
        file.remove_prefix(slash + 1);
    if (const LogSink sink = gLogSink.load()) {
        sink(file, line, message);
    } else {
        std::lock_guard lock(mutex);
        std::fprintf(stderr, "[spear] %.*s:%d: %.*s\n", int(file.size()), file.data(), line,
                     int(message.size()), message.data());
    }
    listeners().tell(file, line, message);
}

} // namespace sp::base
