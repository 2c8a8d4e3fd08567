#pragma once
// Runs a few independent tasks at once on a process-wide pool of worker threads: the worlds' physics steps of
// one frame, the parts of a large readback copy. Work that takes microseconds is not worth it: waking a
// worker costs tens of them.

#include <cstddef>
#include <functional>

namespace sp {

// Runs task(0) ... task(count - 1) on up to `threads` threads, the calling thread among them, and returns
// when all are done; the first exception a task threw is rethrown then (the other tasks still run). One job
// runs at a time (concurrent callers take turns). A call from inside a task, a single thread or task, or a
// process forked since the workers started (whose copies of them do not run) runs the tasks in order on the
// calling thread.
void parallelFor(int count, int threads, const std::function<void(int)>& task);

// Runs task(begin, end) over [0, count) cut into up to `parts` ranges through parallelFor(): each range
// starts at a multiple of `granularity` (a SIMD width, a page) and, where count allows, holds at least
// `least` items, so that a small count is one range on the calling thread.
void parallelRanges(std::size_t count, std::size_t granularity, std::size_t least, int parts, int threads,
                    const std::function<void(std::size_t, std::size_t)>& task);

// This machine's hardware threads (at least 1).
int hardwareThreads();

} // namespace sp
