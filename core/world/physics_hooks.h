#pragma once
// PhysicsHooks: actors that take part in the physics step (a car's wheel meshes, a character's capsule)
// register here in BeginPlay. The world's PhysicsSubsystem calls their PrePhysicsTick() just before it
// steps (after every actor ticked, so that what any actor did this frame is seen) and PostPhysicsTick()
// right after, before overlap events are computed and anything renders: a frame's images and events see
// them where that step left them.

#include <algorithm>
#include <vector>

#include "core/world/actor.h"
#include "core/world/world_subsystem.h"

namespace sp::world {

class PhysicsHooks : public WorldSubsystem {
  public:
    static constexpr int kTickOrder =
        tick_order::kPhysics - 1; // holds the actors; PhysicsSubsystem calls them
    explicit PhysicsHooks(UWorld& /*world*/) {}

    void add(AActor& actor) { actors_.push_back(&actor); }
    void remove(const AActor& actor) { std::erase(actors_, &actor); }

    void beforeStep() {
        for (AActor* actor : actors_)
            actor->PrePhysicsTick();
    }
    // Returns whether any actor was called (and so may have moved what physics must see again).
    bool afterStep() {
        for (AActor* actor : actors_)
            actor->PostPhysicsTick();
        return !actors_.empty();
    }

  private:
    std::vector<AActor*> actors_; // in play, in the order they began
};

} // namespace sp::world
