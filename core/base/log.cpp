#include "core/base/log.h"

#include <atomic>
#include <cstdio>
#include <mutex>

namespace sp::base {

namespace {
std::atomic<LogSink> gLogSink{nullptr};
} // namespace

void setLogSink(LogSink sink) {
    gLogSink.store(sink);
}

void writeLogLine(std::string_view file, int line, std::string_view message) {
    static std::mutex mutex;
    // Only the file's base name: full build paths make logs noisy and machine-specific.
    if (auto slash = file.rfind('/'); slash != std::string_view::npos)
        file.remove_prefix(slash + 1);
    if (const LogSink sink = gLogSink.load()) {
        sink(file, line, message);
        return;
    }
    std::lock_guard lock(mutex);
    std::fprintf(stderr, "[spear] %.*s:%d: %.*s\n", int(file.size()), file.data(), line, int(message.size()),
                 message.data());
}

} // namespace sp::base
