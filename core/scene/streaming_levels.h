#pragma once
// Streaming levels: sub-scenes that a scene file declares (UWorld::GetStreamingLevels) and whose actors join
// and leave a world while it plays, the rest of the world untouched (UGameplayStatics.LoadStreamLevel,
// UnloadStreamLevel; the editor's play copies the loaded ones).

#include <string>

class UWorld;

namespace sp::scene {

// Loads a declared level (or, for a name no level has, the scene file at that path, as a level of that
// name): its actors join the world, its references resolve within it, and its names may not be in use.
// Nothing happens for a loaded level. `function` names the caller in messages.
void loadStreamLevel(UWorld& world, const std::string& name, const std::string& function);
// Destroys the actors a level loaded (their handles go stale, naming the level).
void unloadStreamLevel(UWorld& world, const std::string& name, const std::string& function);

} // namespace sp::scene
