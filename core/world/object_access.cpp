#include "core/world/object_access.h"

#include "core/world/engine.h"

namespace sp::world {

void checkObjectAccess(const reflect::ObjectBase& object, std::string_view context) {
    const auto* uobject = dynamic_cast<const UObject*>(&object);
    if (!uobject || !uobject->GetWorld() || !uobject->GetWorld()->GetEngine())
        return;
    uobject->GetWorld()->GetEngine()->checkInFrame(context);
}

} // namespace sp::world
