#pragma once
// WorldSubsystem: an engine service that lives as long as one world and ticks after its actors
// (physics, rendering, sensors). Components reach their world's subsystem with
// GetWorld()->GetSubsystem<T>(), which creates it on first use; subsystems tick in ascending
// T::kTickOrder, so physics runs before rendering whatever order they were first used in.

class UWorld;

namespace sp::world {

class WorldSubsystem {
  public:
    virtual ~WorldSubsystem() = default;
    // Called once per frame after every actor has ticked.
    virtual void Tick(double /*deltaSeconds*/) {}
};

// Tick orders of the engine's own subsystems (plugins may slot in between).
namespace tick_order {
inline constexpr int kPhysics = 100;
inline constexpr int kRendering = 200;
} // namespace tick_order

} // namespace sp::world
