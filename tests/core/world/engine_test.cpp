#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <functional>
#include <memory>
#include <string>
#include <vector>

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

TEST(Engine, AnInspectionUsesObjectsBetweenFramesWithoutTicking) {
    Engine engine;
    {
        Engine::Inspection inspection(engine);
        EXPECT_NO_THROW(engine.checkInFrame("f()"));
        {
            Engine::Inspection nested(engine);
            EXPECT_NO_THROW(engine.checkInFrame("f()"));
        }
        EXPECT_NO_THROW(engine.checkInFrame("f()")); // the outer one is still open
        engine.beginFrame();
        engine.executeFrame(); // between the blocks of another client's frame too
        EXPECT_NO_THROW(engine.checkInFrame("f()"));
        engine.beginEndFrame();
        engine.endFrame();
    }
    EXPECT_THROW(engine.checkInFrame("f()"), sp::InvalidState);
    EXPECT_EQ(engine.GetFrameCount(), 1); // looking ticked nothing: only the frame that ran
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

namespace {
// Four worlds of bodies pushed about on a floor, stepped 90 frames with `threads` physics threads; returns
// every body's final pose, world by world.
std::vector<FTransform> pushedBodies(int threads) {
    Engine::Settings settings;
    settings.physicsThreads = threads;
    Engine engine(settings);
    std::vector<UStaticMeshComponent*> bodies;
    engine.beginFrame();
    for (int w = 0; w < 4; ++w) {
        UWorld& world = engine.CreateWorld("Env" + std::to_string(w));
        auto* floor = static_cast<AStaticMeshActor*>(
            world.spawn_actor(&AStaticMeshActor::StaticClass(), {}, {}, "Floor"));
        floor->StaticMeshComponent->SetStaticMesh("/Engine/BasicShapes/Plane");
        floor->SetActorScale3D({20, 20, 1});
        for (int k = 0; k < 6; ++k) {
            auto* body = static_cast<AStaticMeshActor*>(
                world.spawn_actor(&AStaticMeshActor::StaticClass(), {0.7 * k - 2.0, 0.3 * w, 0.5 + 0.4 * k},
                                  {}, "Body" + std::to_string(k)));
            body->StaticMeshComponent->SetStaticMesh(k % 2 ? "/Engine/BasicShapes/Sphere"
                                                           : "/Engine/BasicShapes/Cube");
            body->StaticMeshComponent->SetSimulatePhysics(true);
            bodies.push_back(body->StaticMeshComponent);
        }
    }
    engine.executeFrame();
    engine.beginEndFrame();
    engine.endFrame();
    for (int frame = 0; frame < 90; ++frame) {
        engine.beginFrame();
        for (size_t i = 0; i < bodies.size(); ++i)
            bodies[i]->AddForce(
                {3.0 * std::cos(0.1 * frame + double(i)), 3.0 * std::sin(0.1 * frame + double(i)), 0});
        engine.executeFrame();
        engine.beginEndFrame();
        engine.endFrame();
    }
    std::vector<FTransform> poses;
    for (UStaticMeshComponent* body : bodies)
        poses.push_back(body->GetComponentTransform());
    return poses;
}

// A subsystem with a concurrent step that fails, standing for a physics step that throws.
struct FailingStep : sp::world::WorldSubsystem {
    static constexpr int kTickOrder = 0;
    explicit FailingStep(UWorld&) {}
    bool HasConcurrentStep() const override { return true; }
    void StepConcurrently(double) override { throw sp::InvalidState("a failing step"); }
};
} // namespace

TEST(Engine, WorldsStepPhysicsAtOnceWithTheResultsOfOneThread) {
    const std::vector<FTransform> serial = pushedBodies(1);
    const std::vector<FTransform> parallel = pushedBodies(4);
    ASSERT_EQ(serial.size(), parallel.size());
    for (size_t i = 0; i < serial.size(); ++i)
        EXPECT_TRUE(serial[i] == parallel[i]) << "body " << i; // bit for bit: a world steps alone
    EXPECT_NE(serial[0].Translation.X, -2.0) << "the bodies moved";
}

TEST(Engine, AFailingConcurrentStepEndsOnlyItsWorldsFrame) {
    Engine::Settings settings;
    settings.physicsThreads = 4;
    Engine engine(settings);
    UWorld& failing = engine.CreateWorld("Failing");
    UWorld& healthy = engine.CreateWorld("Healthy");
    failing.GetSubsystem<FailingStep>();
    engine.beginFrame();
    try {
        engine.executeFrame();
        FAIL() << "expected the step's error";
    } catch (const sp::InvalidState& e) {
        EXPECT_STREQ(e.what(), "a failing step");
    }
    engine.beginEndFrame();
    engine.endFrame();
    EXPECT_EQ(failing.get_frame_count(), 0);
    EXPECT_EQ(healthy.get_frame_count(), 1);
    EXPECT_EQ(engine.GetGameWorld().get_frame_count(), 1);
    try {
        Engine::Settings bad;
        bad.physicsThreads = -1;
        Engine refused(bad);
        FAIL();
    } catch (const sp::InvalidArgument& e) {
        EXPECT_STREQ(e.what(), "Engine(): physicsThreads must be >= 0, got -1");
    }
}

TEST(Engine, PhysicsThreadsComeFromTheEnvironmentAndAreCheckedThere) {
    ::setenv("SPEAR_PHYSICS_THREADS", "3", 1);
    EXPECT_EQ(Engine().GetSettings().physicsThreads, 3);
    for (const char* bad : {"0", "two", "2x", ""}) {
        ::setenv("SPEAR_PHYSICS_THREADS", bad, 1);
        try {
            Engine refused;
            ADD_FAILURE() << "accepted '" << bad << "'";
        } catch (const sp::InvalidArgument& e) {
            EXPECT_EQ(std::string(e.what()),
                      std::string("Engine(): SPEAR_PHYSICS_THREADS must be a whole number >= 1, got '") +
                          bad + "'");
        }
    }
    ::unsetenv("SPEAR_PHYSICS_THREADS");
    EXPECT_GE(Engine().GetSettings().physicsThreads, 1);
    Engine::Settings given;
    given.physicsThreads = 5; // a setting made in code wins over the environment
    ::setenv("SPEAR_PHYSICS_THREADS", "2", 1);
    EXPECT_EQ(Engine(given).GetSettings().physicsThreads, 5);
    ::unsetenv("SPEAR_PHYSICS_THREADS");
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
