#pragma once
// Runs a few independent tasks at once on a process-wide pool of worker threads: the worlds' physics steps of
// one frame, the parts of a large readback copy. Work that takes microseconds is not worth it: waking a
// worker costs tens of them.

#include <functional>

namespace sp {

// Runs task(0) ... task(count - 1) on up to `threads` threads, the calling thread among them, and returns
// when all are done; the first exception a task threw is rethrown then (the other tasks still run). One job
// runs at a time (concurrent callers take turns). A call from inside a task, a single thread or task, or a
// process forked since the workers started (whose copies of them do not run) runs the tasks in order on the
// calling thread.
void parallelFor(int count, int threads, const std::function<void(int)>& task);

// This machine's hardware threads (at least 1).
int hardwareThreads();

} // namespace sp
