#include "core/reflect/object_base.h"

#include <mutex>
#include <vector>

#include "core/base/error.h"
#include "core/reflect/type_info.h"

namespace sp::reflect {

namespace {
struct Slot {
    ObjectBase* object = nullptr;
    uint32_t generation = 0;
    // The last destroyed occupant, for stale-handle messages (kept when the slot is reused).
    std::string lastDebugName;
    uint32_t lastGeneration = UINT32_MAX;
};

struct Table {
    std::mutex mutex;
    std::vector<Slot> slots{Slot{}}; // slot 0 is the null handle
    std::vector<uint32_t> freeSlots;
    size_t live = 0;
};

Table& table() {
    static Table instance;
    return instance;
}
} // namespace

ObjectBase::ObjectBase() : handle_(ObjectTable::insert(this)) {}

ObjectBase::~ObjectBase() {
    ObjectTable::erase(handle_);
}

std::string ObjectBase::GetDebugName() const {
    return GetObjectClass().name;
}

void ObjectBase::SetDataDefinedClass(const TypeInfo& type) {
    SP_CHECK(type.isDataDefined() && &type.nativeClass() == &GetClass(), InvalidArgument,
             "ObjectBase::SetDataDefinedClass(): class '", type.name, "' is not a data-defined class over ",
             GetClass().name);
    dataDefinedClass_ = &type;
}

bool ObjectBase::IsA(const TypeInfo& type) const {
    return GetObjectClass().isChildOf(type);
}

ObjectHandle ObjectTable::insert(ObjectBase* object) {
    Table& t = table();
    std::lock_guard lock(t.mutex);
    uint32_t index;
    if (!t.freeSlots.empty()) {
        index = t.freeSlots.back();
        t.freeSlots.pop_back();
    } else {
        index = uint32_t(t.slots.size());
        t.slots.emplace_back();
    }
    Slot& slot = t.slots[index];
    slot.object = object;
    ++t.live;
    return {index, slot.generation};
}

void ObjectTable::rememberName(const ObjectBase& object) {
    std::string name = object.GetDebugName();
    Table& t = table();
    std::lock_guard lock(t.mutex);
    Slot& slot = t.slots[object.GetHandle().index];
    slot.lastDebugName = std::move(name);
    slot.lastGeneration = object.GetHandle().generation;
}

void ObjectTable::erase(ObjectHandle handle) {
    Table& t = table();
    std::lock_guard lock(t.mutex);
    Slot& slot = t.slots[handle.index];
    slot.object = nullptr;
    ++slot.generation;
    t.freeSlots.push_back(handle.index);
    --t.live;
}

std::vector<ObjectBase*> ObjectTable::liveObjects() {
    Table& t = table();
    std::lock_guard lock(t.mutex);
    std::vector<ObjectBase*> objects;
    objects.reserve(t.live);
    for (const Slot& slot : t.slots)
        if (slot.object)
            objects.push_back(slot.object);
    return objects;
}

ObjectBase* ObjectTable::find(ObjectHandle handle) {
    Table& t = table();
    std::lock_guard lock(t.mutex);
    if (handle.index == 0 || handle.index >= t.slots.size())
        return nullptr;
    const Slot& slot = t.slots[handle.index];
    return slot.generation == handle.generation ? slot.object : nullptr;
}

ObjectBase& ObjectTable::resolve(ObjectHandle handle, std::string_view context) {
    SP_CHECK(!handle.isNull(), InvalidArgument, context, ": the object is None");
    if (ObjectBase* object = find(handle))
        return *object;
    Table& t = table();
    std::string name;
    {
        std::lock_guard lock(t.mutex);
        if (handle.index < t.slots.size() && t.slots[handle.index].lastGeneration == handle.generation)
            name = t.slots[handle.index].lastDebugName;
    }
    SP_THROW(StaleObject, context, ": ", name.empty() ? std::string("object") : name, " (handle ",
             toString(handle), ") was destroyed");
}

size_t ObjectTable::liveCount() {
    Table& t = table();
    std::lock_guard lock(t.mutex);
    return t.live;
}

} // namespace sp::reflect
