#include "core/imageio/file_writer.h"

#include <algorithm>
#include <exception>
#include <utility>

namespace sp::imageio {

FileWriter::FileWriter(int threads, int maxPending, std::size_t maxBytes)
    : maxPending_(std::max(1, maxPending)), maxBytes_(maxBytes) {
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

std::uint64_t FileWriter::submit(std::size_t bytes, Task task) {
    std::unique_lock lock(mutex_);
    changed_.wait(lock, [&] {
        return unfinished_ == 0 || (unfinished_ < maxPending_ && bytesHeld_ + bytes <= maxBytes_);
    });
    const std::uint64_t ticket = submitted_ + 1;
    queue_.push_back({ticket, bytes, std::move(task)}); // first: if it throws, nothing is counted
    submitted_ = ticket;
    ++unfinished_;
    bytesHeld_ += bytes;
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
        Queued next = std::move(queue_.front());
        queue_.pop_front();
        lock.unlock();
        Finished result{next.ticket, {}};
        try {
            next.task();
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
        bytesHeld_ -= next.bytes;
        lock.unlock();
        changed_.notify_all();
    }
}

} // namespace sp::imageio
