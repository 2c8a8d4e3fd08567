#include <gtest/gtest.h>

#include <cstdlib>

#include "core/base/error.h"
#include "core/render/gl_context.h"

namespace sp::render {
namespace {

TEST(GlContextGlTest, ReportsAnOpenGl45CoreContext) {
    GlContext context;
    const ContextReport& report = context.report();
    EXPECT_TRUE(report.kind == "device" || report.kind == "surfaceless") << report.kind;
    EXPECT_FALSE(report.renderer.empty());
    EXPECT_FALSE(report.vendor.empty());
    EXPECT_NE(report.version.find("4."), std::string::npos) << report.version;
    if (report.kind == "surfaceless") {
        EXPECT_EQ(report.deviceIndex, -1);
    }
}

TEST(GlContextGlTest, SurfacelessCanBeForced) {
    GlContextOptions options;
    options.device = "surfaceless";
    GlContext context(options);
    EXPECT_EQ(context.report().kind, "surfaceless");
}

TEST(GlContextGlTest, BadDeviceChoiceIsInvalidArgument) {
    GlContextOptions options;
    options.device = "gpu0";
    try {
        GlContext context(options);
        FAIL();
    } catch (const InvalidArgument& e) {
        EXPECT_NE(std::string(e.what()).find(
                      "SPEAR_EGL_DEVICE must be 'auto', 'surfaceless' or a device index, got 'gpu0'"),
                  std::string::npos);
    }
    options.device = "999";
    EXPECT_THROW(GlContext context(options), InvalidArgument);
}

} // namespace
} // namespace sp::render

namespace sp::render {
namespace {

TEST(GlContextGlTest, EnvironmentVariableSelectsTheDisplay) {
    ::setenv("SPEAR_EGL_DEVICE", "surfaceless", 1);
    GlContext context;
    EXPECT_EQ(context.report().kind, "surfaceless");
    ::setenv("SPEAR_EGL_DEVICE", "bogus", 1);
    EXPECT_THROW(GlContext{}, InvalidArgument);
    ::unsetenv("SPEAR_EGL_DEVICE");
}

} // namespace
} // namespace sp::render
