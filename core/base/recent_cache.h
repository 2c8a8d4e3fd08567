#pragma once
// A process-wide cache of values made from files or content, kept while they are among the most recently used
// up to a byte budget: an imported mesh file, a mesh's levels of detail. Thread-safe; values are shared and
// immutable, so a caller holding one keeps it whatever the cache drops.

#include <cstddef>
#include <list>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <utility>

namespace sp::base {

template <typename Value> class RecentCache {
  public:
    explicit RecentCache(std::size_t budgetBytes) : budget_(budgetBytes) {}

    // The value under `key`, made most recently used; null when there is none.
    std::shared_ptr<const Value> find(const std::string& key) {
        const std::lock_guard<std::mutex> lock(mutex_);
        const auto it = entries_.find(key);
        if (it == entries_.end())
            return nullptr;
        recent_.splice(recent_.begin(), recent_, it->second.at);
        return it->second.value;
    }

    // Keeps `value` (of `bytes`) under `key`, replacing what was there, then drops the least recently used
    // values past the budget (the newest stays, however large). Returns `value`.
    std::shared_ptr<const Value> insert(const std::string& key, std::shared_ptr<const Value> value,
                                        std::size_t bytes) {
        const std::lock_guard<std::mutex> lock(mutex_);
        if (const auto it = entries_.find(key); it != entries_.end())
            erase(it);
        recent_.push_front(key);
        entries_.emplace(key, Entry{value, bytes, recent_.begin()});
        bytes_ += bytes;
        while (bytes_ > budget_ && recent_.size() > 1)
            erase(entries_.find(recent_.back()));
        return value;
    }

    std::size_t bytes() const {
        const std::lock_guard<std::mutex> lock(mutex_);
        return bytes_;
    }

  private:
    struct Entry {
        std::shared_ptr<const Value> value;
        std::size_t bytes;
        std::list<std::string>::iterator at;
    };
    using Entries = std::map<std::string, Entry, std::less<>>;

    void erase(typename Entries::iterator it) {
        bytes_ -= it->second.bytes;
        recent_.erase(it->second.at);
        entries_.erase(it);
    }

    mutable std::mutex mutex_;
    std::size_t budget_;
    std::size_t bytes_ = 0;
    std::list<std::string> recent_; // most recently used first
    Entries entries_;
};

} // namespace sp::base
