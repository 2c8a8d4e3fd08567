#pragma once
// WorldSubsystem: an engine service that lives as long as one world and ticks after its actors
// (physics, rendering, sensors). Components reach their world's subsystem with
// GetWorld()->GetSubsystem<T>(), which creates it on first use; subsystems tick in ascending
// T::kTickOrder, so physics runs before rendering whatever order they were first used in.

class AActor;
class UActorComponent;
class UWorld;

namespace sp::world {

class WorldSubsystem {
  public:
    virtual ~WorldSubsystem() = default;
    // Called once per frame after every actor has ticked.
    virtual void Tick(double /*deltaSeconds*/) {}
    // A subsystem whose frame holds work that touches nothing outside its own world (a physics step) splits
    // it out, so that an engine with several worlds runs every world's such work at once on several threads:
    // Tick() then does the part before, StepConcurrently() the work, FinishTick() the part after. A world
    // ticking on its own runs the three in a row. At most one subsystem of a world has such a step.
    virtual bool HasConcurrentStep() const { return false; }
    virtual void StepConcurrently(double /*deltaSeconds*/) {}
    virtual void FinishTick(double /*deltaSeconds*/) {}
    // Called once per frame after every world of the host ticked (for a world without a host, right after
    // its own tick): for work cheaper done for all worlds at once, such as the render subsystems' one batch
    // of every world's cameras.
    virtual void OnWorldsTicked() {}

    // The world's actors and components as they begin play (spawned, loaded, added to an actor in play) and
    // end it (destroyed, unloaded), so that a subsystem mirrors the world by registration rather than by
    // walking every actor each frame. A subsystem made after some began play is told of those first, in the
    // world's order: each actor, then its components. An actor is told of before its components when play
    // begins, after them when it ends.
    virtual void OnActorBeginPlay(AActor& /*actor*/) {}
    virtual void OnActorEndPlay(AActor& /*actor*/) {}
    virtual void OnComponentBeginPlay(UActorComponent& /*component*/) {}
    virtual void OnComponentEndPlay(UActorComponent& /*component*/) {}
};

// Tick orders of the engine's own subsystems (plugins may slot in between).
namespace tick_order {
inline constexpr int kPhysics = 100;
inline constexpr int kRendering = 200;
} // namespace tick_order

} // namespace sp::world
