#include <gtest/gtest.h>

#include <functional>
#include <memory>

#include "core/base/error.h"
#include "core/engine/engine.h"
#include "core/sensors/camera_sensor_actor.h"
#include "core/sensors/render_subsystem.h"
#include "core/world/static_mesh_actor.h"
#include "core/world/static_mesh_component.h"
#include "core/world/world_subsystem.h"

using sp::engine::Engine;

namespace {
// A subsystem whose tick fails, standing for a world whose actors or physics throw.
struct Failing : sp::world::WorldSubsystem {
    static constexpr int kTickOrder = 0;
    explicit Failing(UWorld&) {}
    void Tick(double) override { throw sp::InvalidState("a failing world"); }
};
} // namespace

TEST(Engine, FrameStateMachine) {
    Engine engine;
    EXPECT_FALSE(engine.IsInFrame());
    EXPECT_THROW(engine.checkInFrame("f()"), sp::InvalidState);
    engine.beginFrame();
    EXPECT_TRUE(engine.IsInFrame());
    EXPECT_THROW(engine.beginFrame(), sp::InvalidState);
    engine.executeFrame();
    EXPECT_FALSE(engine.IsInFrame());
    try {
        engine.beginFrame();
        FAIL();
    } catch (const sp::InvalidState& e) {
        EXPECT_STREQ(
            e.what(),
            "begin_frame(): the previous frame has not been closed; use 'with instance.end_frame():' first");
    }
    engine.beginEndFrame();
    EXPECT_TRUE(engine.IsInFrame());
    engine.endFrame();
    EXPECT_EQ(engine.GetFrameState(), Engine::FrameState::Idle);
    EXPECT_EQ(engine.GetFrameCount(), 1);
    EXPECT_EQ(engine.GetGameWorld().get_frame_count(), 1);
}

TEST(Engine, AbortEndsTheFrameAndTicks) {
    Engine engine;
    engine.beginFrame();
    engine.abortFrame();
    EXPECT_EQ(engine.GetFrameState(), Engine::FrameState::Idle);
    EXPECT_EQ(engine.GetFrameCount(), 1);
    EXPECT_THROW(Engine(Engine::Settings{0.0}), sp::InvalidArgument);
}

TEST(Engine, CreatedWorldsTickWithTheGameWorldAndAreIsolated) {
    Engine engine;
    UWorld& a = engine.CreateWorld("EnvA");
    UWorld& b = engine.CreateWorld("EnvB");
    ASSERT_EQ(engine.GetWorlds(), (std::vector<UWorld*>{&engine.GetGameWorld(), &a, &b}));
    EXPECT_EQ(a.GetName(), "EnvA");
    engine.beginFrame();
    AActor* only = a.spawn_actor(&AActor::StaticClass(), {}, {}, "Only");
    engine.executeFrame();
    engine.beginEndFrame();
    engine.endFrame();
    EXPECT_EQ(a.find_actor_by_name("Only"), only);
    EXPECT_EQ(b.find_actor_by_name("Only"), nullptr);
    EXPECT_EQ(engine.GetGameWorld().find_actor_by_name("Only"), nullptr);
    for (UWorld* world : engine.GetWorlds())
        EXPECT_EQ(world->get_frame_count(), 1);

    engine.DestroyWorld(a);
    EXPECT_EQ(engine.GetWorlds(), (std::vector<UWorld*>{&engine.GetGameWorld(), &b}));
}

TEST(Engine, WorldNamesAreUniqueAndOnlyCreatedWorldsAreDestroyed) {
    Engine engine;
    engine.CreateWorld("Env");
    try {
        engine.CreateWorld("Env");
        FAIL();
    } catch (const sp::InvalidArgument& e) {
        EXPECT_STREQ(e.what(), "create_world(): a world named 'Env' exists already");
    }
    EXPECT_THROW(engine.CreateWorld(""), sp::InvalidArgument);
    EXPECT_THROW(engine.CreateWorld(engine.GetGameWorld().GetName()), sp::InvalidArgument);
    EXPECT_THROW(engine.DestroyWorld(engine.GetGameWorld()), sp::InvalidArgument);
}

TEST(Engine, EveryWorldTicksWhenOneThrowsAndTheFirstErrorPropagates) {
    Engine engine;
    UWorld& failing = engine.CreateWorld("Failing");
    UWorld& healthy = engine.CreateWorld("Healthy");
    failing.GetSubsystem<Failing>();
    engine.beginFrame();
    EXPECT_THROW(engine.executeFrame(), sp::InvalidState);
    EXPECT_EQ(engine.GetFrameState(), Engine::FrameState::FrameExecuted); // the frame still ended
    engine.beginEndFrame();
    engine.endFrame();
    EXPECT_EQ(engine.GetGameWorld().get_frame_count(), 1);
    EXPECT_EQ(healthy.get_frame_count(), 1); // ticked after the failing world
}

TEST(Engine, SharedObjectsLiveWhileAWorldHoldsThem) {
    Engine engine;
    int made = 0;
    auto make = [&] {
        ++made;
        return std::static_pointer_cast<void>(std::make_shared<int>(made));
    };
    std::shared_ptr<void> first = engine.shared("key", make);
    EXPECT_EQ(engine.shared("key", make), first);
    EXPECT_NE(engine.shared("other", make), first) << "another key, another object (dropped at once)";
    EXPECT_EQ(made, 2);
    first.reset();
    EXPECT_EQ(*std::static_pointer_cast<int>(engine.shared("key", make)), 3)
        << "made again once none held it";
}

// Needs EGL (llvmpipe in CI).
TEST(EngineGl, WorldsShareOneRendererAndKeepTheirOwnStatistics) {
    Engine engine;
    UWorld& a = engine.CreateWorld("EnvA");
    UWorld& b = engine.CreateWorld("EnvB");
    auto frame = [&](const std::function<void()>& work) {
        engine.beginFrame();
        work();
        engine.executeFrame();
        engine.beginEndFrame();
        engine.endFrame();
    };
    frame([&] {
        for (UWorld* world : {&a, &b}) {
            auto* camera = static_cast<ACameraSensorActor*>(
                world->spawn_actor(&ACameraSensorActor::StaticClass(), {-4, 0, 0}, {}, "Camera"));
            camera->CameraSensor->Width = camera->CameraSensor->Height = 16;
            auto* cube = static_cast<AStaticMeshActor*>(
                world->spawn_actor(&AStaticMeshActor::StaticClass(), {}, {}, "Cube"));
            cube->StaticMeshComponent->SetStaticMesh("/Engine/BasicShapes/Cube");
        }
    });
    frame([] {});
    auto& renderA = a.GetSubsystem<sp::sensors::RenderSubsystem>();
    auto& renderB = b.GetSubsystem<sp::sensors::RenderSubsystem>();
    ASSERT_NE(renderA.renderer(), nullptr);
    EXPECT_EQ(renderA.renderer(), renderB.renderer()) << "one GL context and renderer for the engine";
    EXPECT_EQ(renderA.stats().Frames, 2);
    EXPECT_EQ(renderB.stats().Frames, 2);
    EXPECT_GE(renderA.stats().MeshUploads, 1);
    EXPECT_EQ(renderB.stats().MeshUploads, 0) << "the cube is uploaded once, by the world that drew it first";
    EXPECT_EQ(renderA.stats().DrawnInstances, 2);
    EXPECT_EQ(renderB.stats().DrawnInstances, 2);

    engine.DestroyWorld(a); // releases its scene from the shared renderer; b renders on
    frame([] {});
    EXPECT_EQ(renderB.stats().Frames, 3);
    UWorld& c = engine.CreateWorld("EnvC");
    frame([&] { c.spawn_actor(&ACameraSensorActor::StaticClass(), {}, {}, "Camera"); });
    EXPECT_EQ(c.GetSubsystem<sp::sensors::RenderSubsystem>().renderer(), renderB.renderer());
    EXPECT_EQ(c.GetSubsystem<sp::sensors::RenderSubsystem>().stats().Frames, 1);
}
