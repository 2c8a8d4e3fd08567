#include <gtest/gtest.h>

#include "core/base/error.h"
#include "core/engine/engine.h"
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
