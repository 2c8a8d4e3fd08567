#include "core/reflect/registry.h"
#include "core/world/blueprint.h"
#include "core/world/engine.h"
#include "generated/engine/cpp/engine_types.gen.h"

namespace sp::world {

void registerEngineTypes() {
    spear_register_engine_types();
    // Generated blueprint classes carry their asset, so that they can be used before load_class().
    reflect::Registry::get().setClassLoader(&loadBlueprint);
}

} // namespace sp::world
