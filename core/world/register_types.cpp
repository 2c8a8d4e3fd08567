#include "core/world/engine.h"
#include "generated/engine/cpp/engine_types.gen.h"

namespace sp::world {

void registerEngineTypes() {
    spear_register_engine_types();
}

} // namespace sp::world
