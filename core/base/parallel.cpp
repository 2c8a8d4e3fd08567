#include "core/base/parallel.h"

#include <unistd.h>

#include <algorithm>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <thread>
#include <utility>
#include <vector>

namespace sp {
namespace {

// Set on the pool's workers and on a caller while its job runs, so that a task asking for more parallelism
// runs it inline instead of waiting for the turn its own job holds.
thread_local bool insideJob = false;

// Workers started when a job first needs them and joined at exit. A job is `count` tasks; the caller takes
// tasks too and returns when every task is done.
class Pool {
  public:
    static Pool& instance() {
        static Pool pool;
        return pool;
    }

    ~Pool() {
        {
            std::lock_guard lock(mutex_);
            stopping_ = true;
        }
        wake_.notify_all();
        if (owner_ == ::getpid()) // a forked child holds copies of the handles, not the threads
            for (std::thread& worker : workers_)
                worker.join();
        else
            for (std::thread& worker : workers_)
                worker.detach();
    }

    // False when this process cannot use the workers (forked since they started): the caller runs inline.
    bool run(int count, int threads, const std::function<void(int)>& task) {
        std::lock_guard turn(turn_); // one job at a time
        if (workers_.empty())
            owner_ = ::getpid();
        if (owner_ != ::getpid())
            return false;
        while (int(workers_.size()) < threads - 1)
            workers_.emplace_back([this] { work(); });
        {
            std::lock_guard lock(mutex_);
            task_ = &task;
            count_ = count;
            next_ = 0;
            done_ = 0;
            failure_ = nullptr;
            // Only as many workers as the job asked for join it: the others may be waking for an older job.
            wanted_ = threads - 1;
            ++job_;
        }
        wake_.notify_all();
        insideJob = true;
        runTasks();
        insideJob = false;
        std::unique_lock lock(mutex_);
        finished_.wait(lock, [this] { return done_ == count_; });
        task_ = nullptr;
        if (failure_)
            std::rethrow_exception(std::exchange(failure_, nullptr));
        return true;
    }

  private:
    Pool() = default;

    void work() {
        insideJob = true;
        std::uint64_t seen = 0;
        for (;;) {
            {
                std::unique_lock lock(mutex_);
                wake_.wait(lock, [&] { return stopping_ || (job_ != seen && wanted_ > 0); });
                if (stopping_)
                    return;
                seen = job_;
                --wanted_;
            }
            runTasks();
        }
    }

    // Takes tasks of the current job until none is left.
    void runTasks() {
        for (;;) {
            int index = 0;
            const std::function<void(int)>* task = nullptr;
            {
                std::lock_guard lock(mutex_);
                if (task_ == nullptr || next_ == count_)
                    return;
                index = next_++;
                task = task_;
            }
            std::exception_ptr failure;
            try {
                (*task)(index);
            } catch (...) {
                failure = std::current_exception();
            }
            std::lock_guard lock(mutex_);
            if (failure && !failure_)
                failure_ = failure;
            if (++done_ == count_)
                finished_.notify_one();
        }
    }

    std::mutex turn_;
    std::mutex mutex_;
    std::condition_variable wake_;
    std::condition_variable finished_;
    std::vector<std::thread> workers_;
    pid_t owner_ = 0;
    bool stopping_ = false;
    std::uint64_t job_ = 0;
    const std::function<void(int)>* task_ = nullptr;
    int count_ = 0;
    int next_ = 0;
    int done_ = 0;
    int wanted_ = 0;
    std::exception_ptr failure_;
};

void runInline(int count, const std::function<void(int)>& task) {
    std::exception_ptr failure;
    for (int i = 0; i < count; ++i) {
        try {
            task(i);
        } catch (...) {
            if (!failure)
                failure = std::current_exception();
        }
    }
    if (failure)
        std::rethrow_exception(failure);
}

} // namespace

void parallelFor(int count, int threads, const std::function<void(int)>& task) {
    threads = std::min(threads, count);
    if (threads <= 1 || insideJob || !Pool::instance().run(count, threads, task))
        runInline(count, task);
}

void parallelRanges(std::size_t count, std::size_t granularity, std::size_t least, int parts, int threads,
                    const std::function<void(std::size_t, std::size_t)>& task) {
    granularity = std::max<std::size_t>(granularity, 1);
    const std::size_t most = count / std::max<std::size_t>(least, 1);
    const std::size_t ranges =
        std::max<std::size_t>(1, std::min<std::size_t>(std::size_t(std::max(parts, 1)), most));
    if (ranges == 1) {
        if (count > 0)
            task(0, count);
        return;
    }
    const std::size_t size = ((count + ranges - 1) / ranges + granularity - 1) / granularity * granularity;
    parallelFor(int(ranges), threads, [&](int range) {
        const std::size_t begin = std::min(count, size * std::size_t(range));
        const std::size_t end = std::size_t(range) + 1 == ranges ? count : std::min(count, begin + size);
        if (begin < end)
            task(begin, end);
    });
}

int hardwareThreads() {
    return std::max(1, int(std::thread::hardware_concurrency()));
}

} // namespace sp
