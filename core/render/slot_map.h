#pragma once
// Dense storage addressed by generation-checked handles (see handles.h). Removing an element bumps its
// slot's generation, so every outstanding handle to it becomes stale; lookups of stale handles throw
// sp::StaleObject naming the calling function and the handle.

#include <cstdint>
#include <optional>
#include <vector>

#include "core/base/error.h"

namespace sp::render {

template <typename T, typename Id> class SlotMap {
  public:
    Id insert(T value) {
        std::uint32_t index;
        if (!free_.empty()) {
            index = free_.back();
            free_.pop_back();
        } else {
            index = static_cast<std::uint32_t>(slots_.size());
            slots_.emplace_back();
        }
        Slot& slot = slots_[index];
        slot.value = std::move(value);
        ++size_;
        return Id{index, slot.generation};
    }

    bool contains(Id id) const {
        return id.index < slots_.size() && slots_[id.index].value &&
               slots_[id.index].generation == id.generation;
    }

    // Returns the element or throws sp::StaleObject "<function>(): <id> was removed or never existed".
    const T& get(Id id, const char* function) const {
        SP_CHECK(contains(id), StaleObject, function, "(): ", id, " was removed or never existed");
        return *slots_[id.index].value;
    }
    T& get(Id id, const char* function) {
        SP_CHECK(contains(id), StaleObject, function, "(): ", id, " was removed or never existed");
        return *slots_[id.index].value;
    }

    void remove(Id id, const char* function) {
        SP_CHECK(contains(id), StaleObject, function, "(): ", id, " was removed or never existed");
        Slot& slot = slots_[id.index];
        slot.value.reset();
        ++slot.generation;
        free_.push_back(id.index);
        --size_;
    }

    std::size_t size() const { return size_; }

    // Calls fn(id, value) for every live element, in slot order (deterministic).
    template <typename Fn> void forEach(Fn&& fn) const {
        for (std::uint32_t i = 0; i < slots_.size(); ++i)
            if (slots_[i].value)
                fn(Id{i, slots_[i].generation}, *slots_[i].value);
    }

  private:
    struct Slot {
        std::optional<T> value;
        std::uint32_t generation = 1;
    };
    std::vector<Slot> slots_;
    std::vector<std::uint32_t> free_;
    std::size_t size_ = 0;
};

} // namespace sp::render
