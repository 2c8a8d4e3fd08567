#pragma once
// WorldHost: what a world asks of the engine that owns it (sp::engine::Engine implements it). The world
// library knows only this, so that the engine, which registers every reflected type (the world's, the
// sensors', the SpFuncs'), can sit above it without a dependency cycle.

#include <functional>
#include <memory>
#include <string_view>

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
