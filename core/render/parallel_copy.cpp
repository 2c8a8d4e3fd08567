#include "core/render/parallel_copy.h"

#include <algorithm>
#include <cstring>

#include "core/base/parallel.h"

namespace sp::render {
namespace {

// Below this a copy is not split: waking a worker costs tens of microseconds.
constexpr std::size_t kSplitBytes = std::size_t(2) << 20;
// Parts start on 4 KiB boundaries, so that no two threads write one page.
constexpr std::size_t kPartAlignment = 4096;

} // namespace

void parallelCopy(void* destination, const void* source, std::size_t bytes, int threads) {
    if (threads <= 1 || bytes < kSplitBytes) {
        std::memcpy(destination, source, bytes);
        return;
    }
    parallelRanges(bytes, kPartAlignment, kSplitBytes / 2, threads, threads,
                   [&](std::size_t begin, std::size_t end) {
                       std::memcpy(static_cast<char*>(destination) + begin,
                                   static_cast<const char*>(source) + begin, end - begin);
                   });
}

int defaultCopyThreads() {
    return std::clamp(hardwareThreads() / 4, 1, 4);
}

} // namespace sp::render
