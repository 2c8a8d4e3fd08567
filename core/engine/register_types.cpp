#include "core/engine/engine.h"
#include "core/plugin/plugin_loader.h"
#include "core/reflect/object_base.h"
#include "core/reflect/registry.h"
#include "core/scene/blueprint.h"
#include "generated/engine/cpp/engine_types.gen.h"

namespace sp::engine {

void registerEngineTypes() {
    spear_register_engine_types();
    plugin::setEngineApiHash(spear_register_engine_types_api_hash());
    // Generated blueprint classes carry their asset, so that they can be used before load_class().
    reflect::Registry::get().setClassLoader(&scene::loadBlueprint);
    // Default objects live as long as their world; those of an unloading plugin's classes go first.
    plugin::setReleaseHook([](bool (*isPluginClass)(const reflect::TypeInfo&)) {
        // The worlds first: releasing destroys objects that a snapshot of the table would still list.
        std::vector<UWorld*> worlds;
        for (reflect::ObjectBase* object : reflect::ObjectTable::liveObjects())
            if (auto* world = dynamic_cast<UWorld*>(object))
                worlds.push_back(world);
        for (UWorld* world : worlds)
            world->ReleaseDefaultObjects(isPluginClass);
    });
}

} // namespace sp::engine
