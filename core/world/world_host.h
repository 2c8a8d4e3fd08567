#pragma once
// WorldHost: what a world asks of the engine that owns it (sp::engine::Engine implements it). The world
// library knows only this, so that the engine, which registers every reflected type (the world's, the
// sensors', the SpFuncs') and links the libraries above the world (scene files, the gameplay framework),
// can sit above it without a dependency cycle.

#include <functional>
#include <memory>
#include <string>
#include <string_view>

class UWorld;

namespace sp::world {

class WorldHost {
  public:
    virtual ~WorldHost() = default;
    // Throws InvalidState naming `context` when no frame is open: engine objects are used inside frames.
    virtual void checkInFrame(std::string_view context) const = 0;
    // The editor's play/stop (an editor world's UWorld.play()/stop() forward here).
    virtual void play() = 0;
    virtual void stop() = 0;
    virtual bool IsPlaying() const = 0;
    // Scene files are read and written by the engine, which links the library for them (sp::scene, above
    // this one), as UE's UEngine loads maps: UWorld.load_scene and save_scene forward here. (Blueprints
    // load through the registry's class loader, which the engine installs.) `function` names the caller.
    virtual void loadScene(UWorld& world, const std::string& path, const std::string& function) = 0;
    virtual void saveScene(const UWorld& world, const std::string& path, const std::string& function) = 0;
    // An object the host's worlds share under `key` (the renderer's GL context, say): the first world to
    // ask makes it with `make`, later ones get the same object while any world still holds it. A host that
    // shares nothing returns what `make` makes.
    virtual std::shared_ptr<void> shared(std::string_view key,
                                         const std::function<std::shared_ptr<void>()>& make) {
        (void)key;
        return make();
    }
};

} // namespace sp::world
