#pragma once
// ListenerList: the callbacks that hear something a process reports (its log lines, its progress) besides the
// one sink that shows it. Called from the reporting thread, under the list's lock (a listener must not add or
// remove listeners, nor report itself); a list nobody listens to costs one atomic load.

#include <atomic>
#include <functional>
#include <map>
#include <mutex>

namespace sp::base {

template <class... Args> class ListenerList {
  public:
    using Listener = std::function<void(Args...)>;

    int add(Listener listener) {
        std::lock_guard lock(mutex_);
        const int id = next_++;
        all_.emplace(id, std::move(listener));
        any_.store(true);
        return id;
    }

    void remove(int id) {
        std::lock_guard lock(mutex_);
        all_.erase(id);
        any_.store(!all_.empty());
    }

    void tell(Args... args) {
        if (!any_.load())
            return;
        std::lock_guard lock(mutex_);
        for (const auto& [id, listener] : all_)
            listener(args...);
    }

  private:
    std::mutex mutex_;
    std::map<int, Listener> all_;
    int next_ = 1;
    std::atomic<bool> any_{false};
};

} // namespace sp::base
