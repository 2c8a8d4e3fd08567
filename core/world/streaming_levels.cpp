// UWorld's streaming levels (declared in world.h): sub-scenes whose actors join and leave the world
// while it plays, the rest of the world untouched.

#include <algorithm>
#include <filesystem>

#include "core/base/error.h"
#include "core/world/scene_io.h"
#include "core/world/world.h"

namespace {

std::vector<UWorld::StreamingLevel>::iterator findLevel(std::vector<UWorld::StreamingLevel>& levels,
                                                        const std::string& name) {
    return std::find_if(levels.begin(), levels.end(), [&](const auto& level) { return level.name == name; });
}

std::string levelNames(const std::vector<UWorld::StreamingLevel>& levels) {
    std::string names;
    for (const UWorld::StreamingLevel& level : levels)
        names += (names.empty() ? "'" : ", '") + level.name + "'";
    return names.empty() ? "none" : names;
}

} // namespace

void UWorld::LoadStreamLevel(const std::string& name, const std::string& function) {
    SP_CHECK(!name.empty(), sp::InvalidArgument, function, ": LevelName is empty");
    const bool declared = findLevel(levels_, name) != levels_.end();
    if (!declared) { // the name is a scene file's path; kept absolute, so that a saved scene finds it again
        const std::string path = std::filesystem::absolute(name).lexically_normal().string();
        levels_.push_back({name, path, path, false});
    }
    if (findLevel(levels_, name)->loaded)
        return;
    const std::string path = findLevel(levels_, name)->path;
    try {
        std::vector<std::unique_ptr<AActor>> actors = sp::world::stageLevel(
            *this, sp::world::readSceneFile(path, function),
            function + ": streaming level '" + name + "' ('" + path + "')", sp::world::sceneFolder(path));
        for (const auto& actor : actors)
            actor->SetStreamingLevelName(name);
        AddActors(std::move(actors));
    } catch (...) {
        if (!declared) // a path that could not be loaded is forgotten, as if never asked for
            levels_.erase(findLevel(levels_, name));
        throw;
    }
    findLevel(levels_, name)->loaded = true;
}

void UWorld::UnloadStreamLevel(const std::string& name, const std::string& function) {
    const auto level = findLevel(levels_, name);
    SP_CHECK(level != levels_.end(), sp::InvalidArgument, function, ": no streaming level '", name,
             "' in this world (levels: ", levelNames(levels_), ")");
    if (!level->loaded)
        return;
    level->loaded = false;
    for (AActor* actor : find_actors())
        if (actor->GetStreamingLevelName() == name)
            destroy_actor(actor);
}
