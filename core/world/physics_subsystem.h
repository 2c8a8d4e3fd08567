#pragma once
// PhysicsSubsystem: the world's rigid-body simulation. It owns a sp::physics::PhysicsWorld and one body
// per primitive component in play that has collision, which it learns of by registration as the render
// subsystem does (the world tells every subsystem of components beginning and ending play; see
// sp::world::WorldSubsystem). Components keep their physics settings as plain
// reflected properties; the subsystem brings the bodies in line with them ("sync") before every step,
// trace and physics call, so a property written by any path (setter, registry, scene file) takes effect.
//
// Per frame (after the actors ticked): sync -> step(dt) in fixed substeps -> write the simulated bodies'
// poses back into their components. Moving a Movable, non-simulated component moves its (kinematic)
// body at the next sync; moving a simulated one teleports it.

#include <cstdint>
#include <optional>
#include <unordered_map>
#include <utility>
#include <vector>

#include "core/physics/physics_world.h"
#include "core/world/hit_result.h"
#include "core/world/primitive_component.h"
#include "core/world/world_subsystem.h"

class UPrimitiveComponent;
class UWorld;

namespace sp::world {

class PhysicsSubsystem : public WorldSubsystem {
  public:
    static constexpr int kTickOrder = tick_order::kPhysics;

    explicit PhysicsSubsystem(UWorld& world);

    // Per frame: the registered actors' pre-physics hooks, sync, step, write-back, their post-physics
    // hooks (and a sync, as they move things), then the overlap events.
    ~PhysicsSubsystem() override;

    // A frame: Tick() runs the pre-physics hooks and syncs, StepConcurrently() steps the physics world by
    // deltaSeconds (touching only this world's bodies, so worlds step on several threads at once), and
    // FinishTick() writes the simulated poses back, runs the post-physics hooks and the overlap events.
    void Tick(double deltaSeconds) override;
    bool HasConcurrentStep() const override { return true; }
    void StepConcurrently(double deltaSeconds) override;
    void FinishTick(double deltaSeconds) override;

    // Registration, as the world tells of components entering and leaving play: each primitive component
    // gets a body (its first one makes the subsystem; see UPrimitiveComponent::BeginPlay).
    void OnComponentBeginPlay(UActorComponent& component) override;
    void OnComponentEndPlay(UActorComponent& component) override;
    bool isRegistered(const UPrimitiveComponent& component) const;
    // The physics subsystem of the component's world; InvalidState, naming UPrimitiveComponent.<function>(),
    // when the component is not in play.
    static PhysicsSubsystem& of(const UPrimitiveComponent& component, const char* function);

    // Brings every body in line with its component (shape, mobility, material, mass, pose).
    void syncAll();
    // Brings one component's body in line and returns it (invalid when the component has no collision).
    // Throws InvalidState when the component is not in play; `function` names the caller in messages.
    physics::BodyId syncComponent(const UPrimitiveComponent& component, const char* function);
    // Like syncComponent, but also requires a simulated body (for forces, impulses, velocities).
    physics::BodyId requireSimulatedBody(const UPrimitiveComponent& component, const char* function);

    // The closest hit of the segment start -> end, after a sync; fills hit and returns the component hit.
    UPrimitiveComponent* lineTrace(const FVector& start, const FVector& end, FHitResult& hit);

    // The components overlapping `component` now, after a sync (see
    // UPrimitiveComponent.GetOverlappingComponents); `function` names the caller in messages.
    std::vector<UPrimitiveComponent*> overlappingComponents(const UPrimitiveComponent& component,
                                                            const char* function);
    // The components that began (ended) overlapping `component` in the last step.
    std::vector<UPrimitiveComponent*> beganOverlaps(const UPrimitiveComponent& component,
                                                    const char* function);
    std::vector<UPrimitiveComponent*> endedOverlaps(const UPrimitiveComponent& component,
                                                    const char* function);

    // Every component in play with its body (invalid when it has none), in registration order, as of the
    // last sync (navigation builds from the static ones).
    std::vector<std::pair<UPrimitiveComponent*, physics::BodyId>> componentBodies() const;

    physics::PhysicsWorld& GetPhysicsWorld() { return physicsWorld_; }
    size_t GetBodyCount() const { return physicsWorld_.bodyCount(); }

  private:
    void registerComponent(UPrimitiveComponent& component);
    void unregisterComponent(UPrimitiveComponent& component);
    // What a body was built from: when any of it changes, the body is rebuilt.
    struct ShapeKey {
        ECollisionPrimitive primitive = ECollisionPrimitive::NoCollision;
        Eigen::Vector3d halfExtents = Eigen::Vector3d::Zero();
        Eigen::Vector3d scale = Eigen::Vector3d::Ones();
        bool isStatic = false;
        std::string mesh; // the mesh file, for ConvexHull and TriangleMesh
        bool operator==(const ShapeKey&) const = default;
    };
    struct Entry {
        UPrimitiveComponent* component = nullptr;
        physics::BodyId body;
        ShapeKey shape;
        // The component's world transform when the body was last placed or written back; a different
        // transform at sync means someone moved the component.
        FTransform syncedTransform;
        // Overlaps after the last step, and how they changed in it (bGenerateOverlapEvents only).
        std::vector<reflect::ObjectHandle> overlapping, began, ended;
    };

    Entry& entryFor(const UPrimitiveComponent& component, const char* function);
    void syncEntry(Entry& entry);
    void rebuildBody(Entry& entry, const ShapeKey& key);
    void syncProperties(Entry& entry);
    void writeBack();
    // The overlapping components of an entry's body as it is now, without a sync.
    std::vector<UPrimitiveComponent*> currentOverlaps(const Entry& entry);
    void updateOverlapEvents();

    UWorld& world_;
    physics::PhysicsWorld physicsWorld_;
    std::vector<Entry> entries_; // registration order: keeps sync (and so the simulation) deterministic
    std::unordered_map<const UPrimitiveComponent*, size_t> index_;
};

} // namespace sp::world
