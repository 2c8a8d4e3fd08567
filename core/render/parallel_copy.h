#pragma once
// Copies of whole images out of mapped readback buffers, split across a few worker threads. One core
// copies about 10 GB/s out of the pinned memory a GPU driver reads back into, so a 1920x1080 RGBA8 frame
// (8 MB) costs it most of a millisecond, serially after the GPU has finished; a few cores share it.

#include <cstddef>

namespace sp::render {

// Copies `bytes` from `source` to `destination` (not overlapping) in up to `threads` parts, the calling
// thread taking one of them. Copies under a few megabytes, a single thread, or a process forked since the
// workers started (whose copies of them do not run) take one memcpy. Thread-safe: concurrent calls take
// turns at the workers.
void parallelCopy(void* destination, const void* source, std::size_t bytes, int threads);

// The threads worth splitting a readback copy across on this machine: a quarter of its hardware threads,
// at least 1 and at most 4 (so 1 on a 2-core machine, where the copy stays on the calling thread).
int defaultCopyThreads();

} // namespace sp::render
