#include "core/render/parallel_copy.h"

#include <unistd.h>

#include <algorithm>
#include <condition_variable>
#include <cstring>
#include <mutex>
#include <thread>
#include <vector>

namespace sp::render {
namespace {

// Below this a copy is not split: waking a worker costs tens of microseconds.
constexpr std::size_t kSplitBytes = std::size_t(2) << 20;
// Parts start on 4 KiB boundaries, so that no two threads write one page.
constexpr std::size_t kPartAlignment = 4096;

// Workers started on the first split copy and joined at exit. A job is one copy cut into parts; the
// caller takes parts too and returns when every part is done.
class CopyPool {
  public:
    static CopyPool& instance() {
        static CopyPool pool;
        return pool;
    }

    ~CopyPool() {
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

    void copy(char* destination, const char* source, std::size_t bytes, int parts) {
        std::lock_guard turn(turn_); // one job at a time
        if (workers_.empty())
            owner_ = ::getpid();
        if (owner_ != ::getpid()) {
            std::memcpy(destination, source, bytes);
            return;
        }
        while (int(workers_.size()) < parts - 1)
            workers_.emplace_back([this] { work(); });
        {
            std::lock_guard lock(mutex_);
            destination_ = destination;
            source_ = source;
            bytes_ = bytes;
            parts_ = parts;
            next_ = 0;
            done_ = 0;
            ++job_;
        }
        wake_.notify_all();
        runParts();
        std::unique_lock lock(mutex_);
        finished_.wait(lock, [this] { return done_ == parts_; });
    }

  private:
    CopyPool() = default;

    void work() {
        std::uint64_t seen = 0;
        for (;;) {
            {
                std::unique_lock lock(mutex_);
                wake_.wait(lock, [&] { return stopping_ || job_ != seen; });
                if (stopping_)
                    return;
                seen = job_;
            }
            runParts();
        }
    }

    // Takes parts of the current job until none is left.
    void runParts() {
        for (;;) {
            int part = 0;
            {
                std::lock_guard lock(mutex_);
                if (next_ == parts_)
                    return;
                part = next_++;
            }
            const std::size_t size =
                (bytes_ / std::size_t(parts_) + kPartAlignment - 1) / kPartAlignment * kPartAlignment;
            const std::size_t begin = std::min(bytes_, size * std::size_t(part));
            const std::size_t end = part + 1 == parts_ ? bytes_ : std::min(bytes_, begin + size);
            std::memcpy(destination_ + begin, source_ + begin, end - begin);
            std::lock_guard lock(mutex_);
            if (++done_ == parts_)
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
    char* destination_ = nullptr;
    const char* source_ = nullptr;
    std::size_t bytes_ = 0;
    int parts_ = 0;
    int next_ = 0;
    int done_ = 0;
};

} // namespace

void parallelCopy(void* destination, const void* source, std::size_t bytes, int threads) {
    if (threads <= 1 || bytes < kSplitBytes) {
        std::memcpy(destination, source, bytes);
        return;
    }
    const int parts = int(std::min<std::size_t>(std::size_t(threads), bytes / (kSplitBytes / 2)));
    CopyPool::instance().copy(static_cast<char*>(destination), static_cast<const char*>(source), bytes,
                              parts);
}

int defaultCopyThreads() {
    const unsigned hardware = std::thread::hardware_concurrency();
    return std::clamp(int(hardware / 4), 1, 4);
}

} // namespace sp::render
