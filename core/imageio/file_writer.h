#pragma once
// FileWriter: writes files on background threads, so that encoding images (PNG, ZIP-compressed EXR) and
// waiting for the disk overlap with rendering the next frame instead of adding to it. A task is a group of
// files written in order by one thread (a frame's images, then the file that says the frame is whole);
// tasks run in parallel with each other. At most `maxPending` tasks, holding at most `maxBytes` between
// them, wait or run: submit() blocks beyond that (a task of any size may run alone), so memory stays bounded
// when the disk is slower than the renderer.

#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <functional>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace sp::imageio {

class FileWriter {
  public:
    using Task = std::function<void()>;
    struct Finished {
        std::uint64_t ticket = 0;
        std::string error; // the task's exception message; empty when it succeeded
    };

    FileWriter(int threads, int maxPending, std::size_t maxBytes);
    ~FileWriter(); // waits for every task submitted
    FileWriter(const FileWriter&) = delete;
    FileWriter& operator=(const FileWriter&) = delete;

    // Queues `task`, which holds `bytes` of data until it finishes, and returns its ticket (1, 2, ...);
    // blocks while that would exceed maxPending tasks or maxBytes.
    std::uint64_t submit(std::size_t bytes, Task task);
    // The tasks that finished since the last call, in the order they finished.
    std::vector<Finished> takeFinished();
    // Blocks until every submitted task has finished.
    void waitAll();
    // Tasks submitted and not finished.
    int pending() const;

  private:
    void work();

    mutable std::mutex mutex_;
    std::condition_variable changed_;
    struct Queued {
        std::uint64_t ticket;
        std::size_t bytes;
        Task task;
    };
    std::deque<Queued> queue_;
    std::vector<Finished> finished_;
    std::vector<std::thread> threads_;
    std::uint64_t submitted_ = 0;
    int unfinished_ = 0;
    std::size_t bytesHeld_ = 0;
    int maxPending_;
    std::size_t maxBytes_;
    bool stopping_ = false;
};

} // namespace sp::imageio
