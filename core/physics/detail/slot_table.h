#pragma once
// Generation-checked storage behind BodyId: a freed slot is reused with its generation bumped, so an old
// id can always be told apart from the slot's new occupant.

#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

#include "core/base/error.h"
#include "core/physics/body_id.h"

namespace sp::physics::detail {

template <typename T> class SlotTable {
  public:
    // Stores value in a free slot (the most recently freed one first) and returns its id.
    BodyId insert(T value) {
        uint32_t index;
        if (free_.empty()) {
            SP_CHECK(slots_.size() < BodyId::kInvalidIndex, InvalidState,
                     "SlotTable::insert(): table is full");
            index = uint32_t(slots_.size());
            slots_.emplace_back();
        } else {
            index = free_.back();
            free_.pop_back();
        }
        slots_[index].value.emplace(std::move(value));
        ++size_;
        return BodyId{index, slots_[index].generation};
    }

    // Destroys the value of a valid id and makes the id stale.
    void erase(BodyId id) {
        Slot& slot = slots_[id.index];
        slot.value.reset();
        ++slot.generation;
        free_.push_back(id.index);
        --size_;
    }

    // The value, or nullptr when id is stale, unknown or invalid.
    T* find(BodyId id) {
        if (id.index >= slots_.size())
            return nullptr;
        Slot& slot = slots_[id.index];
        return slot.value && slot.generation == id.generation ? &*slot.value : nullptr;
    }
    const T* find(BodyId id) const { return const_cast<SlotTable*>(this)->find(id); }

    // The value; throws sp::StaleObject naming function and id when there is none.
    T& get(BodyId id, const char* function) {
        if (T* value = find(id))
            return *value;
        if (id.index < slots_.size() && id.generation < slots_[id.index].generation)
            SP_THROW(StaleObject, function, ": body ", id, " was removed");
        SP_THROW(StaleObject, function, ": body ", id, " does not exist in this world");
    }
    const T& get(BodyId id, const char* function) const {
        return const_cast<SlotTable*>(this)->get(id, function);
    }

    // The id of the live value in slot index (which must hold one).
    BodyId idAt(uint32_t index) const { return BodyId{index, slots_[index].generation}; }

    size_t size() const { return size_; }

    // Calls f(BodyId, T&) for every live value in slot order.
    template <typename F> void forEach(F&& f) {
        for (uint32_t i = 0; i < slots_.size(); ++i)
            if (slots_[i].value)
                f(BodyId{i, slots_[i].generation}, *slots_[i].value);
    }
    template <typename F> void forEach(F&& f) const {
        for (uint32_t i = 0; i < slots_.size(); ++i)
            if (slots_[i].value)
                f(BodyId{i, slots_[i].generation}, std::as_const(*slots_[i].value));
    }

  private:
    struct Slot {
        std::optional<T> value;
        uint32_t generation = 0;
    };
    std::vector<Slot> slots_;
    std::vector<uint32_t> free_;
    size_t size_ = 0;
};

} // namespace sp::physics::detail
