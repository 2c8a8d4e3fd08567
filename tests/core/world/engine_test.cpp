#include <gtest/gtest.h>

#include "core/base/error.h"
#include "core/world/engine.h"

using sp::world::Engine;

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
