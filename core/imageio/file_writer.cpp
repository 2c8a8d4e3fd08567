#include "core/imageio/file_writer.h"

#include <algorithm>
#include <exception>
#include <utility>

namespace sp::imageio {

FileWriter::FileWriter(int threads, int maxPending) : maxPending_(std::max(1, maxPending)) {
    for (int i = 0; i < std::max(1, threads); ++i)
        threads_.emplace_back([this] { work(); });
}

FileWriter::~FileWriter() {
    waitAll();
    {
        std::lock_guard lock(mutex_);
        stopping_ = true;
    }
    changed_.notify_all();
    for (std::thread& thread : threads_)
        thread.join();
}

std::uint64_t FileWriter::submit(Task task) {
    std::unique_lock lock(mutex_);
    changed_.wait(lock, [&] { return unfinished_ < maxPending_; });
    const std::uint64_t ticket = ++submitted_;
    ++unfinished_;
    queue_.emplace_back(ticket, std::move(task));
    lock.unlock();
    changed_.notify_all();
    return ticket;
}

std::vector<FileWriter::Finished> FileWriter::takeFinished() {
    std::lock_guard lock(mutex_);
    return std::exchange(finished_, {});
}

void FileWriter::waitAll() {
    std::unique_lock lock(mutex_);
    changed_.wait(lock, [&] { return unfinished_ == 0; });
}

int FileWriter::pending() const {
    std::lock_guard lock(mutex_);
    return unfinished_;
}

void FileWriter::work() {
    for (;;) {
        std::unique_lock lock(mutex_);
        changed_.wait(lock, [&] { return stopping_ || !queue_.empty(); });
        if (queue_.empty())
            return; // stopping, and nothing left
        auto [ticket, task] = std::move(queue_.front());
        queue_.pop_front();
        lock.unlock();
        Finished result{ticket, {}};
        try {
            task();
        } catch (const std::exception& error) {
            result.error = error.what();
            if (result.error.empty())
                result.error = "unknown error";
        } catch (...) {
            result.error = "unknown error";
        }
        lock.lock();
        finished_.push_back(std::move(result));
        --unfinished_;
        lock.unlock();
        changed_.notify_all();
    }
}

} // namespace sp::imageio
