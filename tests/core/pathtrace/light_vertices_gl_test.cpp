// Light-vertex connections (Settings::lightConnections): a room whose light is mostly a lamp's hot spot on
// the ceiling converges many times faster, to the same image; spot lights, lamps that cast no shadows and
// things that cast none keep the image it converges to.

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

#include "closed_room.h"
#include "core/pathtrace/path_tracer.h"
#include "core/render/primitives.h"
#include "gl_fixture.h"
#include "test_scenes.h"

namespace sp::pathtrace {
namespace {

class LightVerticesTest : public render::test::GlTest {};

// The closed room (closed_room.h) with its lamp 10 cm under the ceiling: most of the room's light is the
// lamp's hot spot on the ceiling, which the walls' and floor's bounce rays meet by chance.
// `id`: where to put the lamp's id.
render::Scene lampUnderTheCeiling(render::LightId* id = nullptr) {
    render::Scene scene;
    const render::LightId lamp = test::buildClosedRoom(scene, false);
    if (id)
        *id = lamp;
    render::Light light = scene.light(lamp);
    light.position.z() = 2.4;
    scene.setLight(lamp, light);
    return scene;
}

// The light that reached the pixels' first surfaces by bouncing: the image less the lights' direct light,
// which connections do not change (and whose sharp, bright hot spot, seen directly, would dominate a measure
// of the whole image with its pixels' jitter).
double indirect(const Accumulation& image, int x, int y, int c) {
    return double(image.mean(x, y, c)) - double(image.mean(image.directSum, x, y, c));
}

double indirectRelativeRmse(const Accumulation& image, const Accumulation& reference) {
    double error = 0.0, sum = 0.0;
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x)
            for (int c = 0; c < 3; ++c) {
                error += std::pow(indirect(image, x, y, c) - indirect(reference, x, y, c), 2);
                sum += indirect(reference, x, y, c);
            }
    const double n = double(image.width) * image.height * 3;
    return std::sqrt(error / n) / (sum / n);
}

// The mean of each half (left, right) of the image's indirect light: where an estimate was biased, a half
// would show it.
std::array<double, 2> indirectHalves(const Accumulation& image) {
    std::array<double, 2> sums{0.0, 0.0};
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x)
            for (int c = 0; c < 3; ++c)
                sums[x < image.width / 2 ? 0 : 1] += indirect(image, x, y, c);
    const double n = double(image.width / 2) * image.height * 3;
    return {sums[0] / n, sums[1] / n};
}

Settings kWith(int samples) {
    return Settings(samples, 4, 0.0f, false, true);
}
Settings kWithout(int samples) {
    return Settings(samples, 4, 0.0f, false, false);
}

// Converged with and without connections, the two images' halves agree within `tolerance` (relative; they
// agreed within 0.6 % at 4096 samples when written, and a connection counted at full weight beside the bounce
// that finds the same light, a missing multiple importance sampling weight, is 30 to 75 % off).
void expectTheSameImage(const render::Scene& scene, const render::Camera& camera, int samples,
                        double tolerance, const char* what) {
    PathTracer tracer;
    Accumulation with, without;
    tracer.render(scene, camera, kWith(samples), with);
    tracer.render(scene, camera, kWithout(samples), without);
    const auto a = indirectHalves(with), b = indirectHalves(without);
    for (int h = 0; h < 2; ++h) {
        ASSERT_GT(b[std::size_t(h)], 0.0) << what;
        EXPECT_NEAR(a[std::size_t(h)], b[std::size_t(h)], tolerance * b[std::size_t(h)])
            << what << ", half " << h;
    }
}

TEST_F(LightVerticesTest, ARoomLitByALampUnderTheCeilingConvergesManyTimesFaster) {
    const render::Scene scene = lampUnderTheCeiling();
    const render::Camera camera = test::closedRoomCamera();
    render::Camera other = camera; // the same view with other random numbers: an independent reference
    other.params.farClip = 999.0;
    PathTracer tracer;
    Accumulation reference, with, without;
    tracer.render(scene, other, kWith(2048), reference);
    tracer.render(scene, camera, kWith(64), with);
    tracer.render(scene, camera, kWithout(64), without);
    const double joined = indirectRelativeRmse(with, reference),
                 alone = indirectRelativeRmse(without, reference);
    std::cout << "indirect light, 64 spp against 2048: relative RMSE " << alone << " without connections, "
              << joined << " with\n";
    EXPECT_LT(joined, 0.3 * alone);           // 0.12x when written: as many as 70 times the samples
    EXPECT_TRUE(Settings().lightConnections); // on by default
}

TEST_F(LightVerticesTest, TheImageConvergesToIsTheSame) {
    // The bare lamp; the same lamp as a spot light aimed at the floor (its rays drawn inside its cone);
    // a lamp that casts no shadows beside one that does (the first is never joined); a box that casts no
    // shadows under the lamp (lamp rays pass through it, as shadow rays do, so it is never joined); a
    // camera without shadows (no connections at all).
    const render::Camera camera =
        render::test::cameraLookingAt({-1.8, -1.3, 1.8}, {1.0, 0.8, 0.6}, 24, 16, 90.0);
    { expectTheSameImage(lampUnderTheCeiling(), camera, 2048, 0.02, "bare lamp"); }
    {
        render::LightId lamp;
        render::Scene scene = lampUnderTheCeiling(&lamp);
        render::Light spot = scene.light(lamp);
        spot.type = render::LightType::Spot;
        spot.direction = Eigen::Vector3d(0.3, 0.2, -1.0).normalized();
        spot.innerConeDeg = 20.0f;
        spot.outerConeDeg = 35.0f;
        scene.setLight(lamp, spot);
        expectTheSameImage(scene, camera, 2048, 0.02, "spot light");
    }
    {
        render::LightId lamp;
        render::Scene scene = lampUnderTheCeiling(&lamp);
        render::Light second = scene.light(lamp);
        second.position = {-1.2, -0.5, 1.5};
        second.castShadows = false;
        scene.addLight(second);
        render::Instance box{scene.addMesh(render::primitives::box({0.6f, 0.6f, 0.6f})),
                             {scene.addMaterial(render::test::makeMaterial({0.8f, 0.3f, 0.2f}, 0.7f, 0.0f))},
                             {9}};
        box.transform = Eigen::Translation3d(0.5, 0.3, 0.3);
        box.castShadows = false;
        scene.addInstance(box);
        expectTheSameImage(scene, camera, 2048, 0.02, "a shadowless lamp and box");
    }
    {
        render::Camera shadowless = camera;
        shadowless.params.shadows = false;
        const render::Scene scene = lampUnderTheCeiling();
        PathTracer tracer;
        Accumulation with, without;
        tracer.render(scene, shadowless, kWith(16), with);
        tracer.render(scene, shadowless, kWithout(16), without);
        EXPECT_EQ(with.sum, without.sum); // no connections drawn: the same random numbers, the same sums
    }
}

} // namespace
} // namespace sp::pathtrace
