#include "core/scene/streaming_levels.h"

#include <algorithm>
#include <filesystem>

#include "core/base/error.h"
#include "core/scene/scene_io.h"
#include "core/world/world.h"

namespace sp::scene {

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

void loadStreamLevel(UWorld& world, const std::string& name, const std::string& function) {
    std::vector<UWorld::StreamingLevel>& levels = world.GetStreamingLevels();
    SP_CHECK(!name.empty(), sp::InvalidArgument, function, ": LevelName is empty");
    const bool declared = findLevel(levels, name) != levels.end();
    if (!declared) { // the name is a scene file's path; kept absolute, so that a saved scene finds it again
        const std::string path = std::filesystem::absolute(name).lexically_normal().string();
        levels.push_back({name, path, path, false});
    }
    if (findLevel(levels, name)->loaded)
        return;
    const std::string path = findLevel(levels, name)->path;
    try {
        std::vector<std::unique_ptr<AActor>> actors =
            stageLevel(world, readSceneFile(path, function),
                       function + ": streaming level '" + name + "' ('" + path + "')", sceneFolder(path));
        for (const auto& actor : actors)
            actor->SetStreamingLevelName(name);
        world.AddActors(std::move(actors));
    } catch (...) {
        if (!declared) // a path that could not be loaded is forgotten, as if never asked for
            levels.erase(findLevel(levels, name));
        throw;
    }
    findLevel(levels, name)->loaded = true;
}

void unloadStreamLevel(UWorld& world, const std::string& name, const std::string& function) {
    std::vector<UWorld::StreamingLevel>& levels = world.GetStreamingLevels();
    const auto level = findLevel(levels, name);
    SP_CHECK(level != levels.end(), sp::InvalidArgument, function, ": no streaming level '", name,
             "' in this world (levels: ", levelNames(levels), ")");
    if (!level->loaded)
        return;
    level->loaded = false;
    for (AActor* actor : world.find_actors())
        if (actor->GetStreamingLevelName() == name)
            world.destroy_actor(actor);
}

} // namespace sp::scene
