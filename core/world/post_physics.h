#pragma once
// PostPhysicsSubsystem: actors that follow the physics step (a car's wheel meshes, a character's capsule)
// register here in BeginPlay and get PostPhysicsTick() after every step, before anything renders, so that
// a frame's images show them where that step left them.

#include <algorithm>
#include <vector>

#include "core/world/actor.h"
#include "core/world/world_subsystem.h"

namespace sp::world {

class PostPhysicsSubsystem : public WorldSubsystem {
  public:
    static constexpr int kTickOrder = tick_order::kPhysics + 1;
    explicit PostPhysicsSubsystem(UWorld& /*world*/) {}

    void Tick(double /*deltaSeconds*/) override {
        for (AActor* actor : actors_)
            actor->PostPhysicsTick();
    }
    void add(AActor& actor) { actors_.push_back(&actor); }
    void remove(const AActor& actor) { std::erase(actors_, &actor); }

  private:
    std::vector<AActor*> actors_; // in play, in the order they began
};

} // namespace sp::world
