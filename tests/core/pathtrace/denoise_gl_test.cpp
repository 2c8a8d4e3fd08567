// The denoiser (denoise.h): on the path tracer's own images it brings 64 samples per pixel closer to a
// converged reference, and it never blurs across instances; bad guides are refused naming them.

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

#include "closed_room.h"
#include "core/base/error.h"
#include "core/pathtrace/denoise.h"
#include "core/pathtrace/path_tracer.h"
#include "core/render/primitives.h"
#include "gl_fixture.h"
#include "test_scenes.h"

namespace sp::pathtrace {
namespace {

// Relative RMSE of `image` against the reference's means over the pixels that show geometry.
double relativeRmse(const std::vector<float>& image, const Accumulation& reference) {
    double error = 0.0, sum = 0.0;
    std::size_t n = 0;
    for (int y = 0; y < reference.height; ++y)
        for (int x = 0; x < reference.width; ++x) {
            const std::size_t p = std::size_t(y) * std::size_t(reference.width) + std::size_t(x);
            if (reference.ids[p] == 0)
                continue;
            for (int c = 0; c < 3; ++c) {
                const double r = reference.mean(x, y, c);
                error += std::pow(double(image[p * 3 + std::size_t(c)]) - r, 2);
                sum += r;
                ++n;
            }
        }
    return std::sqrt(error / double(n)) / (sum / double(n));
}

std::vector<float> means(const Accumulation& image) {
    std::vector<float> out(std::size_t(image.width) * std::size_t(image.height) * 3);
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x)
            for (int c = 0; c < 3; ++c)
                out[(std::size_t(y) * std::size_t(image.width) + std::size_t(x)) * 3 + std::size_t(c)] =
                    image.mean(x, y, c);
    return out;
}

// Two boxes of different colours on a floor under a sun and a sky: indirect light, soft shadows, edges.
render::Scene twoBoxes() {
    render::Scene scene;
    const auto floor = scene.addMaterial(render::test::makeMaterial({0.7f, 0.7f, 0.7f}, 0.9f, 0.0f));
    const auto red = scene.addMaterial(render::test::makeMaterial({0.8f, 0.1f, 0.1f}, 0.6f, 0.0f));
    const auto blue = scene.addMaterial(render::test::makeMaterial({0.1f, 0.2f, 0.8f}, 0.6f, 0.0f));
    scene.addInstance({scene.addMesh(render::primitives::plane(10.0f, 10.0f)), {floor}, {1}});
    const auto box = scene.addMesh(render::primitives::box());
    render::Instance a{box, {red}, {2}}, b{box, {blue}, {3}};
    a.transform = Eigen::Translation3d(0.0, -0.55, 0.5);
    b.transform = Eigen::Translation3d(0.0, 0.55, 0.5);
    scene.addInstance(a);
    scene.addInstance(b);
    render::Light sun;
    sun.direction = Eigen::Vector3d(0.3, 0.5, -1.0).normalized();
    scene.addLight(sun);
    scene.setEnvironment({{0.3f, 0.35f, 0.45f}, {0.3f, 0.35f, 0.45f}});
    return scene;
}

class DenoiseTest : public render::test::GlTest {};

// The shared closed room (closed_room.h) with a red block in it: most of its light is indirect, the path
// tracer's noise.
render::Scene closedRoom() {
    render::Scene scene;
    test::buildClosedRoom(scene, false);
    const auto red = scene.addMaterial(render::test::makeMaterial({0.7f, 0.15f, 0.1f}, 0.8f, 0.0f));
    render::Instance block{scene.addMesh(render::primitives::box({0.8f, 0.8f, 0.8f})), {red}, {2}};
    block.transform = Eigen::Translation3d(0.6, 0.4, 0.4);
    scene.addInstance(block);
    return scene;
}

TEST_F(DenoiseTest, FewSamplesComeCloserToTheConvergedImage) {
    PathTracer tracer;
    // Indoors, where the noise is: less than half the error. Outdoors under a sun, where the lights' direct
    // light (kept as it is) dominates and the error left is at edges: no more than before.
    const struct {
        const char* name;
        render::Scene scene;
        render::Camera camera;
        double most;
    } cases[] = {
        {"closed room", closedRoom(), test::closedRoomCamera(), 0.5},
        {"two boxes outdoors", twoBoxes(),
         render::test::cameraLookingAt({-3.5, -1.0, 2.0}, {0.0, 0.0, 0.4}, 48, 36, 60.0), 1.0},
    };
    for (const auto& c : cases) {
        Accumulation noisy, reference;
        // Without light-vertex connections, which take most of the closed room's noise away before any
        // filter (light_vertices_gl_test.cpp): the filter's own effect on a noisy image.
        tracer.render(c.scene, c.camera, {16, 3, 0.0f, false, false}, noisy);
        tracer.render(c.scene, c.camera, {1024, 3}, reference);
        const double raw = relativeRmse(means(noisy), reference);
        const double filtered = relativeRmse(denoise(noisy), reference);
        std::cout << c.name << ", 16 spp against 1024: relative RMSE " << raw << " raw, " << filtered
                  << " denoised\n";
        EXPECT_LT(filtered, c.most * raw) << c.name;
    }
}

TEST_F(DenoiseTest, AConvergedImageIsLeftNearlyAsItIs) {
    // The filter's tolerance is the noise each pixel's samples show: at 2,048 samples the room's lighting
    // differences are far beyond it, and the filtered image stays within a fraction of a percent of the
    // unfiltered one (0.006 relative RMSE when written), where a tolerance relative to the luminance alone
    // blurred the lighting itself (0.044).
    PathTracer tracer;
    Accumulation converged;
    tracer.render(closedRoom(), test::closedRoomCamera(), {2048, 3}, converged);
    const double change = relativeRmse(denoise(converged), converged);
    std::cout << "closed room at 2048 spp: the filter changes it by " << change << " (relative RMSE)\n";
    EXPECT_LT(change, 0.01);
}

TEST_F(DenoiseTest, NothingIsBlurredAcrossInstances) {
    // Two flat halves with different ids, one bright and one dark, each noisy: every pixel's result stays
    // within its own half's range.
    const int width = 32, height = 16;
    std::vector<float> color(std::size_t(width * height * 3)), albedo(color.size(), 1.0f),
        normal(color.size()), depth(std::size_t(width * height), 2.0f);
    std::vector<std::uint32_t> ids(std::size_t(width * height));
    std::uint64_t state = 12345;
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const std::size_t p = std::size_t(y * width + x);
            ids[p] = x < width / 2 ? 1 : 2;
            state = state * 6364136223846793005ull + 1442695040888963407ull;
            const float noise = float(state >> 40) / float(1 << 24); // [0, 1)
            for (int c = 0; c < 3; ++c) {
                color[p * 3 + std::size_t(c)] = (ids[p] == 1 ? 10.0f : 1.0f) * (0.5f + noise);
                normal[p * 3 + std::size_t(c)] = c == 2 ? 1.0f : 0.0f;
            }
        }
    const std::vector<float> out = denoise(color, {width, height, albedo, normal, depth, ids});
    for (std::size_t p = 0; p < ids.size(); ++p) {
        const float low = ids[p] == 1 ? 5.0f : 0.5f, high = ids[p] == 1 ? 15.0f : 1.5f;
        EXPECT_GE(out[p * 3], low) << p;
        EXPECT_LE(out[p * 3], high) << p;
    }
}

TEST_F(DenoiseTest, AFireflyIsRemovedAndABrightFeatureOfTwoPixelsKept) {
    // Even light of 1, a single pixel of 200 (one rare path's sample) and a stripe two pixels wide of 8.
    const int width = 24, height = 24;
    std::vector<float> color(std::size_t(width * height * 3), 1.0f), albedo(color.size(), 0.5f),
        normal(color.size()), depth(std::size_t(width * height), 2.0f);
    std::vector<std::uint32_t> ids(std::size_t(width * height), 1);
    const auto at = [&](int x, int y) { return std::size_t(y * width + x) * 3; };
    for (std::size_t p = 0; p < ids.size(); ++p)
        normal[p * 3 + 2] = 1.0f;
    for (int c = 0; c < 3; ++c) {
        color[at(5, 5) + std::size_t(c)] = 200.0f;
        for (int x = 0; x < width; ++x)
            for (int y : {15, 16})
                color[at(x, y) + std::size_t(c)] = 8.0f;
    }
    const std::vector<float> out = denoise(color, {width, height, albedo, normal, depth, ids});
    for (int y = 2; y <= 8; ++y)
        for (int x = 2; x <= 8; ++x)
            EXPECT_LT(out[at(x, y)], 1.5f) << x << ", " << y; // no speck, and not spread around it either
    for (int x = 0; x < width; ++x)
        for (int y : {15, 16})
            EXPECT_GT(out[at(x, y)], 6.0f) << x << ", " << y;
}

TEST_F(DenoiseTest, GuidesOfTheWrongSizeAreRefusedByName) {
    std::vector<float> color(12), albedo(12), normal(9), depth(4);
    std::vector<std::uint32_t> ids(4);
    try {
        denoise(color, {2, 2, albedo, normal, depth, ids});
        FAIL() << "no error";
    } catch (const InvalidArgument& e) {
        EXPECT_NE(std::string(e.what()).find("denoise(): normal has 9 values for 4 pixels of 3"),
                  std::string::npos)
            << e.what();
    }
}

} // namespace
} // namespace sp::pathtrace
