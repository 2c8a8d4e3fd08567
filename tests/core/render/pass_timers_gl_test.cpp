// PassTimers: a GPU pass gets a timer query whose result is collected once the driver has it; the readback
// is timed on the CPU alone (no query: on llvmpipe one made the rasteriser threads run a scene of their own
// around each read), so its totals have CPU time and no query samples.

#include "core/render/pass_timers.h"

#include <epoxy/gl.h>
#include <gtest/gtest.h>

#include <chrono>
#include <thread>

#include "core/render/gl_context.h"

namespace sp::render {
namespace {

TEST(PassTimersGlTest, TheReadbackIsTimedOnTheCpuAloneAndOtherPassesGetQueries) {
    GlContext context;
    PassTimers timers;
    // Some GPU work for the passes to time: clearing a small buffer (a context without a surface has no
    // default framebuffer to clear).
    GLuint buffer = 0;
    glCreateBuffers(1, &buffer);
    glNamedBufferData(buffer, 4096, nullptr, GL_STATIC_DRAW);
    const auto work = [&] { glClearNamedBufferData(buffer, GL_R8, GL_RED, GL_UNSIGNED_BYTE, nullptr); };
    EXPECT_FALSE(timedOnGpu(Pass::Readback));
    EXPECT_TRUE(timedOnGpu(Pass::Surface));

    timers.begin(Pass::Surface);
    work();
    timers.end();
    timers.begin(Pass::Readback);
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
    timers.end();
    glFinish();
    timers.collect();

    const PassTime& readback = timers.totals()[static_cast<std::size_t>(Pass::Readback)];
    EXPECT_EQ(readback.samples, 0u);
    EXPECT_EQ(readback.gpuMs, 0.0);
    EXPECT_GE(readback.cpuMs, 2.0);
    // The surface pass's query is collected once finished (a result longer than the time since the pass
    // began, as llvmpipe gives a new context's first query, is dropped, so at most one sample).
    const PassTime& surface = timers.totals()[static_cast<std::size_t>(Pass::Surface)];
    EXPECT_LE(surface.samples, 1u);
    EXPECT_GE(surface.gpuMs, 0.0);
    EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));

    // A query of a pass that follows a readback is collected too: the open readback holds no query back.
    for (int i = 0; i < 3; ++i) {
        timers.begin(Pass::Surface);
        work();
        timers.end();
        timers.begin(Pass::Readback);
        timers.end();
    }
    glFinish();
    timers.begin(Pass::Readback);
    timers.collect(); // while a readback is open
    timers.end();
    EXPECT_GE(surface.samples, 3u);
    EXPECT_EQ(readback.samples, 0u);
    glDeleteBuffers(1, &buffer);
}

} // namespace
} // namespace sp::render
