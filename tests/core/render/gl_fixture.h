#pragma once
// One EGL context and Renderer per test process (each test runs in its own process under CTest), plus
// small scene-building helpers shared by the GL tests.

#include <gtest/gtest.h>

#include <memory>

#include "core/render/gl_context.h"
#include "core/render/primitives.h"
#include "core/render/render_target.h"
#include "core/render/renderer.h"
#include "core/render/scene.h"

namespace sp::render::test {

class GlTest : public ::testing::Test {
  protected:
    static void SetUpTestSuite() {
        context_ = std::make_unique<GlContext>();
        renderer_ = std::make_unique<Renderer>(*context_);
    }
    static void TearDownTestSuite() {
        renderer_.reset();
        context_.reset();
    }
    Renderer& renderer() { return *renderer_; }

    // One frame of `modalities` of `scene` seen by `camera`, rendered and read at once (latency 0).
    Frame renderFrame(const Scene& scene, const Camera& camera, ModalitySet modalities) {
        RenderTarget target(renderer(), modalities, 0);
        Frame frame;
        target.render(scene, camera, frame);
        return frame;
    }

    // A camera at `position` looking along world direction `forward` (Z up).
    static Camera lookingAlong(const Eigen::Vector3d& position, const Eigen::Vector3d& forward, int width,
                               int height, double hfovDeg = 60.0) {
        Camera camera;
        const Eigen::Vector3d x = forward.normalized();
        const Eigen::Vector3d up =
            std::abs(x.z()) < 0.99 ? Eigen::Vector3d::UnitZ() : Eigen::Vector3d::UnitX();
        const Eigen::Vector3d y = up.cross(x).normalized();
        const Eigen::Vector3d z = x.cross(y);
        camera.pose.linear() << x, y, z;
        camera.pose.translation() = position;
        camera.params.width = width;
        camera.params.height = height;
        camera.params.hfovDeg = hfovDeg;
        return camera;
    }

    static inline std::unique_ptr<GlContext> context_;
    static inline std::unique_ptr<Renderer> renderer_;
};

} // namespace sp::render::test
