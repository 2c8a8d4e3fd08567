#include "core/world/object_access.h"

#include "core/base/error.h"
#include "core/world/world.h"

namespace sp::world {

void checkObjectAccess(const reflect::ObjectBase& object, std::string_view context) {
    const auto* uobject = dynamic_cast<const UObject*>(&object);
    if (!uobject || !uobject->GetWorld() || !uobject->GetWorld()->GetHost())
        return;
    uobject->GetWorld()->GetHost()->checkInFrame(context);
}

UWorld& worldOfContext(UObject* context, std::string_view function) {
    SP_CHECK(context, InvalidArgument, function, ": WorldContextObject is None");
    checkObjectAccess(*context, function);
    auto* world = dynamic_cast<UWorld*>(context);
    if (!world)
        world = context->GetWorld();
    SP_CHECK(world, InvalidArgument, function, ": WorldContextObject ", context->GetDebugName(),
             " is not in a world");
    return *world;
}

} // namespace sp::world
