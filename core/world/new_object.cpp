#include "core/world/new_object.h"

#include "core/base/error.h"
#include "core/world/actor.h"

namespace sp::world {

std::unique_ptr<UObject> newObject(const reflect::TypeInfo& type, std::string name, UWorld* world) {
    const reflect::TypeInfo& native = type.nativeClass();
    SP_CHECK(native.create, InvalidArgument, "class '", type.name, "' is abstract and cannot be created");
    std::unique_ptr<UObject> object(static_cast<UObject*>(native.create()));
    if (&native != &type)
        object->SetDataDefinedClass(type);
    object->InitObject(std::move(name), world);
    if (auto* actor = dynamic_cast<AActor*>(object.get()))
        actor->SetWorldForComponents();
    type.initializeObject(*object);
    return object;
}

} // namespace sp::world
