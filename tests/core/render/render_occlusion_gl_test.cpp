// Screen-space ambient occlusion (CameraParams::ambientOcclusionIntensity, screen_occlusion.h): an open floor
// is not occluded, the floor at a box's foot is, within the radius and not beyond it, the intensity scales
// it, the exact modalities stay bit for bit what they were, and large views take it at half resolution.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "core/render/image_buffer.h"
#include "core/render/primitives.h"
#include "core/render/screen_occlusion.h"
#include "gl_fixture.h"
#include "test_scenes.h"

namespace sp::render::test {
namespace {

class RenderOcclusionGlTest : public GlTest {};

constexpr std::uint32_t kFloorId = 1;

// A grey floor under a uniform sky (no lights: all of its light is the sky term the occlusion scales), and
// with `box`, a 1 m box standing on it at the origin.
void buildFloor(Scene& scene, bool box) {
    scene.setEnvironment(Environment({1.0f, 1.0f, 1.0f}, {0.0f, 0.0f, 0.0f}));
    scene.addInstance({scene.addMesh(primitives::plane(20, 20)),
                       {scene.addMaterial(makeMaterial({0.5f, 0.5f, 0.5f}, 1.0f, 0.0f))},
                       {kFloorId}});
    if (!box)
        return;
    Instance cube{scene.addMesh(primitives::box({1.0f, 1.0f, 1.0f})),
                  {scene.addMaterial(makeMaterial({0.5f, 0.5f, 0.5f}, 1.0f, 0.0f))},
                  {2}};
    cube.transform.translation() = Eigen::Vector3d(0.0, 0.0, 0.5);
    scene.addInstance(cube);
}

Camera view(int width, int height, float intensity) {
    Camera camera = cameraLookingAt({3.0, -2.5, 2.2}, {0.0, 0.0, 0.2}, width, height, 60.0);
    camera.params.ambientOcclusionIntensity = intensity;
    return camera;
}

const ModalitySet kModalities{
    Modality::DiffuseIllumination, Modality::Position, Modality::ObjectIds, Modality::Depth, Modality::Normal,
    Modality::MaterialAo};

// The floor's pixels' diffuse illumination with occlusion over that without, by the distance of the pixel's
// point from the box's footprint (|x|, |y| <= 0.5): the mean ratio of those nearer than `near` metres and the
// lowest ratio of those further than `far`.
struct Ratios {
    double nearMean = 0.0;
    double farLowest = 1e9;
    int nearCount = 0;
    int farCount = 0;
};
Ratios floorRatios(const Frame& without, const Frame& with, double near, double far) {
    const auto ids = without.get(Modality::ObjectIds).as<std::uint32_t>();
    const auto position = without.get(Modality::Position).as<float>();
    const auto a = without.get(Modality::DiffuseIllumination).as<std::uint16_t>(); // float16
    const auto b = with.get(Modality::DiffuseIllumination).as<std::uint16_t>();
    const std::size_t channels = std::size_t(without.get(Modality::DiffuseIllumination).channels());
    const std::size_t pChannels = std::size_t(without.get(Modality::Position).channels());
    Ratios r;
    for (std::size_t i = 0; i < ids.size(); ++i) {
        if (ids[i] != kFloorId)
            continue;
        const double x = position[pChannels * i], y = position[pChannels * i + 1];
        const double dx = std::max(std::abs(x) - 0.5, 0.0), dy = std::max(std::abs(y) - 0.5, 0.0);
        const double distance = std::hypot(dx, dy);
        const double ratio = double(halfToFloat(b[channels * i])) / double(halfToFloat(a[channels * i]));
        if (distance < near) {
            r.nearMean += ratio;
            ++r.nearCount;
        } else if (distance > far) {
            r.farLowest = std::min(r.farLowest, ratio);
            ++r.farCount;
        }
    }
    if (r.nearCount > 0)
        r.nearMean /= r.nearCount;
    return r;
}

TEST_F(RenderOcclusionGlTest, AnOpenFloorIsNotOccluded) {
    Scene scene;
    buildFloor(scene, false);
    const Frame without = renderFrame(scene, view(160, 120, 0.0f), kModalities);
    const Frame with = renderFrame(scene, view(160, 120, 1.0f), kModalities);
    const Ratios r = floorRatios(without, with, 0.0, -1.0); // every floor pixel is "far"
    ASSERT_GT(r.farCount, 10000);
    EXPECT_GT(r.farLowest, 0.99); // a plane hides none of its own hemisphere
}

TEST_F(RenderOcclusionGlTest, TheFloorAtABoxsFootIsDarkenedAndNotBeyondTheRadius) {
    Scene scene;
    buildFloor(scene, true);
    const Frame without = renderFrame(scene, view(160, 120, 0.0f), kModalities);
    const Frame with = renderFrame(scene, view(160, 120, 1.0f), kModalities);
    // The radius is 0.5 m: within 0.1 m of the box a vertical face hides about half of the hemisphere (less
    // the light a grey surface reflects back in); past 0.6 m nothing is hidden.
    ASSERT_DOUBLE_EQ(view(160, 120, 1.0f).params.ambientOcclusionRadius, 0.5);
    const Ratios r = floorRatios(without, with, 0.1, 0.6);
    ASSERT_GT(r.nearCount, 20);
    ASSERT_GT(r.farCount, 5000);
    EXPECT_LT(r.nearMean, 0.9);
    EXPECT_GT(r.nearMean, 0.5);
    EXPECT_GT(r.farLowest, 0.99);

    // A larger radius reaches further.
    Camera wide = view(160, 120, 1.0f);
    wide.params.ambientOcclusionRadius = 2.0f;
    const Ratios w = floorRatios(without, renderFrame(scene, wide, kModalities), 0.1, 0.6);
    EXPECT_LT(w.farLowest, 0.95);
}

TEST_F(RenderOcclusionGlTest, IntensityScalesTheOcclusion) {
    Scene scene;
    buildFloor(scene, true);
    const Frame without = renderFrame(scene, view(160, 120, 0.0f), kModalities);
    const double full =
        floorRatios(without, renderFrame(scene, view(160, 120, 1.0f), kModalities), 0.1, 0.6).nearMean;
    const double half =
        floorRatios(without, renderFrame(scene, view(160, 120, 0.5f), kModalities), 0.1, 0.6).nearMean;
    EXPECT_LT(full, half);
    EXPECT_LT(half, 1.0);
    EXPECT_NEAR(1.0 - half, 0.5 * (1.0 - full), 0.25 * (1.0 - full)); // the bounce term bends it a little
}

TEST_F(RenderOcclusionGlTest, ExactModalitiesStayExact) {
    Scene scene;
    buildFloor(scene, true);
    const Frame without = renderFrame(scene, view(160, 120, 0.0f), kModalities);
    const Frame with = renderFrame(scene, view(160, 120, 1.0f), kModalities);
    for (Modality m :
         {Modality::Position, Modality::ObjectIds, Modality::Depth, Modality::Normal, Modality::MaterialAo})
        EXPECT_EQ(without.get(m).bytes, with.get(m).bytes) << modalityName(m);
}

TEST_F(RenderOcclusionGlTest, LargeViewsTakeItAtHalfResolutionAndOnlyWhenAsked) {
    ASSERT_EQ(ScreenOcclusion::scaleFor(320, 240), 1);
    ASSERT_EQ(ScreenOcclusion::scaleFor(321, 240), 2);
    Scene scene;
    buildFloor(scene, true);
    renderer().resetStats();
    const Frame without = renderFrame(scene, view(800, 600, 0.0f), kModalities);
    EXPECT_EQ(renderer().stats().occlusionPasses, 0u);
    const Frame with = renderFrame(scene, view(800, 600, 1.0f), kModalities);
    EXPECT_EQ(renderer().stats().occlusionPasses, 1u);
    const Ratios r = floorRatios(without, with, 0.1, 0.6);
    ASSERT_GT(r.nearCount, 200);
    EXPECT_LT(r.nearMean, 0.9);
    EXPECT_GT(r.farLowest, 0.98);
    // Only the shaded modalities ask for it.
    renderFrame(scene, view(800, 600, 1.0f), {Modality::Depth, Modality::ObjectIds});
    EXPECT_EQ(renderer().stats().occlusionPasses, 1u);
}

} // namespace
} // namespace sp::render::test
