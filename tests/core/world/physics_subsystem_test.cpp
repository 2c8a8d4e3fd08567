#include <gtest/gtest.h>

#include <cstring>

#include "core/base/error.h"
#include "core/engine/engine.h"
#include "core/world/physics_subsystem.h"
#include "core/world/static_mesh_actor.h"

namespace {
AStaticMeshActor* spawnMesh(UWorld& world, const char* mesh, FVector location, bool simulate) {
    auto* actor =
        static_cast<AStaticMeshActor*>(world.spawn_actor(&AStaticMeshActor::StaticClass(), location));
    actor->StaticMeshComponent->SetStaticMesh(mesh);
    actor->StaticMeshComponent->SetSimulatePhysics(simulate);
    return actor;
}

AStaticMeshActor* spawnFloor(UWorld& world) {
    AStaticMeshActor* floor = spawnMesh(world, "/Engine/BasicShapes/Cube", {0, 0, -0.5}, false);
    floor->StaticMeshComponent->SetRelativeScale3D({20, 20, 1});
    floor->StaticMeshComponent->SetMobility(EComponentMobility::Static);
    return floor;
}

void runFrames(sp::engine::Engine& engine, int frames) {
    for (int i = 0; i < frames; ++i) {
        engine.beginFrame();
        engine.executeFrame();
        engine.beginEndFrame();
        engine.endFrame();
    }
}
} // namespace

TEST(PhysicsSubsystemTest, BodiesFollowComponentsIntoAndOutOfPlay) {
    sp::engine::Engine engine;
    UWorld& world = engine.GetGameWorld();
    AStaticMeshActor* empty = spawnMesh(world, "", {}, false);
    auto& physics = world.GetSubsystem<sp::world::PhysicsSubsystem>();
    EXPECT_TRUE(physics.isRegistered(*empty->StaticMeshComponent));
    physics.syncAll();
    EXPECT_EQ(physics.GetBodyCount(), 0u); // no mesh, no body
    empty->StaticMeshComponent->SetStaticMesh("/Engine/BasicShapes/Cube");
    physics.syncAll();
    EXPECT_EQ(physics.GetBodyCount(), 1u);
    world.destroy_actor(empty);
    EXPECT_EQ(physics.GetBodyCount(), 0u);
}

TEST(PhysicsSubsystemTest, ACubeRestsOnTheFloorAndWritesItsPoseBack) {
    sp::engine::Engine engine;
    UWorld& world = engine.GetGameWorld();
    spawnFloor(world);
    AStaticMeshActor* cube = spawnMesh(world, "/Engine/BasicShapes/Cube", {0, 0, 3}, true);
    runFrames(engine, 180);
    EXPECT_NEAR(cube->GetActorLocation().Z, 0.5, 1e-3);
    EXPECT_FALSE(cube->StaticMeshComponent->IsAnyRigidBodyAwake()); // resting bodies sleep
}

TEST(PhysicsSubsystemTest, TwoEnginesGiveBitIdenticalPoses) {
    auto run = [] {
        sp::engine::Engine engine;
        UWorld& world = engine.GetGameWorld();
        spawnFloor(world);
        std::vector<AStaticMeshActor*> bodies;
        for (int i = 0; i < 5; ++i) {
            bodies.push_back(
                spawnMesh(world, "/Engine/BasicShapes/Cube", {0.1 * i, 0.0, 0.6 + 1.1 * i}, true));
            bodies.back()->SetActorRotation({0.0, 13.0 * i, 2.0 * i});
        }
        runFrames(engine, 90);
        std::vector<FTransform> poses;
        for (AStaticMeshActor* body : bodies)
            poses.push_back(body->GetActorTransform());
        return poses;
    };
    const std::vector<FTransform> a = run();
    const std::vector<FTransform> b = run();
    ASSERT_EQ(a.size(), b.size());
    EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(FTransform)), 0);
}

TEST(PhysicsSubsystemTest, LineTraceReportsActorComponentAndDistance) {
    sp::engine::Engine engine;
    UWorld& world = engine.GetGameWorld();
    AStaticMeshActor* box = spawnMesh(world, "/Engine/BasicShapes/Cube", {0, 0, 1}, false);
    FHitResult hit;
    AActor* actor = nullptr;
    UPrimitiveComponent* component = nullptr;
    ASSERT_TRUE(world.line_trace_single({0, 0, 5}, {0, 0, -5}, hit, actor, component));
    EXPECT_EQ(actor, box);
    EXPECT_EQ(component, box->StaticMeshComponent);
    EXPECT_NEAR(hit.Distance, 3.5, 1e-9);
    EXPECT_NEAR(hit.ImpactNormal.Z, 1.0, 1e-9);
    EXPECT_FALSE(world.line_trace_single({5, 5, 5}, {5, 5, -5}, hit, actor, component));
    EXPECT_EQ(actor, nullptr);
}

TEST(PhysicsSubsystemTest, StaticComponentsCannotMoveOrSimulateInPlay) {
    sp::engine::Engine engine;
    UWorld& world = engine.GetGameWorld();
    AStaticMeshActor* floor = spawnFloor(world);
    EXPECT_THROW(floor->SetActorLocation({0, 0, 1}), sp::InvalidState);
    EXPECT_THROW(floor->StaticMeshComponent->SetSimulatePhysics(true), sp::InvalidState);
    EXPECT_THROW(floor->StaticMeshComponent->AddForce({1, 0, 0}), sp::InvalidState);
}
