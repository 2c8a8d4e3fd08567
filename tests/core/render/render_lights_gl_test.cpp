// A scene of many lights: each view shades those whose range reaches its frustum (a light past its range adds
// exactly nothing), at most shaders::kMaxLights of them, the nearest.

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/render/image_buffer.h"
#include "core/render/shaders.h"
#include "gl_fixture.h"
#include "test_scenes.h"

namespace sp::render::test {
namespace {

class RenderLightsGlTest : public GlTest {};

// A point light of finite range at `at`, its colour varying with where it is so that each one shows.
Light pointLight(const Eigen::Vector3d& at) {
    const auto cell = [&](int axis, int period) {
        return float(std::abs(int(std::lround(at[axis] * 20.0))) % period);
    };
    Light light;
    light.type = LightType::Point;
    light.position = at;
    light.intensity = 2.0f;
    light.color = {0.5f + 0.25f * cell(0, 3), 0.5f + 0.2f * cell(1, 4), 0.6f + 0.1f * cell(0, 5)};
    light.range = 3.0f;
    light.castShadows = false;
    return light;
}

// The shapes scene without its sun, lit by the point lights at `positions` (in that order).
void buildScene(Scene& scene, const std::vector<Eigen::Vector3d>& positions) {
    buildShapesScene(scene);
    scene.forEachLight([&](LightId id, const Light&) { scene.removeLight(id); }); // the sun
    for (const Eigen::Vector3d& at : positions)
        scene.addLight(pointLight(at));
}

bool same(const ImageBuffer& a, const ImageBuffer& b) {
    return a.bytes.size() == b.bytes.size() && std::equal(a.bytes.begin(), a.bytes.end(), b.bytes.begin());
}

TEST_F(RenderLightsGlTest, LightsWhoseRangeMissesTheViewAreLeftOutWithoutChangingTheImage) {
    // 40 lights on a 5 m grid, more than a program's 16; the camera, its far plane 6 m away, sees the middle.
    // A scene of the lights whose range reaches its frustum alone (found here by the test, with a wider
    // margin) renders the same images, bit for bit.
    std::vector<Eigen::Vector3d> all, near;
    for (int x = -4; x < 4; ++x)
        for (int y = -2; y <= 2; ++y) {
            const Eigen::Vector3d at(5.0 * x + 2.5, 5.0 * y, 1.5);
            all.push_back(at);
            if (std::abs(at.x()) < 5.0 && std::abs(at.y()) < 3.0)
                near.push_back(at);
        }
    ASSERT_GT(all.size(), std::size_t(shaders::kMaxLights));
    Scene everything, only;
    buildScene(everything, all);
    Camera camera = cameraLookingAt({0.0, -3.0, 4.0}, {0, 0, 0.3}, 128, 96, 50.0);
    camera.params.farClip = 6.0;
    // The near lights in the order the full scene has them, where the view can reach them.
    std::vector<Eigen::Vector3d> reached;
    const auto planes = camera.frustumPlanes();
    for (const Eigen::Vector3d& at : all)
        if (Scene::reachesInside(planes, at, 3.01))
            reached.push_back(at);
    ASSERT_LT(reached.size(), std::size_t(shaders::kMaxLights));
    ASSERT_GT(reached.size(), near.size() / 2);
    buildScene(only, reached);
    Frame frames[2];
    for (int i = 0; i < 2; ++i) {
        renderer().resetStats();
        RenderTarget target(renderer(),
                            {Modality::FinalColor, Modality::HdrColor, Modality::DiffuseIllumination}, 0);
        target.render(i == 0 ? everything : only, camera, frames[i]);
        EXPECT_EQ(renderer().stats().lightsLeftOut, 0u);
    }
    for (Modality m : {Modality::FinalColor, Modality::HdrColor, Modality::DiffuseIllumination})
        EXPECT_TRUE(same(frames[0].get(m), frames[1].get(m))) << modalityName(m);
    // And the lights show: without them the image is another.
    Scene dark;
    buildScene(dark, {});
    Frame unlit;
    RenderTarget target(renderer(), {Modality::FinalColor}, 0);
    target.render(dark, camera, unlit);
    EXPECT_FALSE(same(unlit.get(Modality::FinalColor), frames[0].get(Modality::FinalColor)));
}

TEST_F(RenderLightsGlTest, AViewReachedByMoreLightsThanAProgramShadesShadesTheNearest) {
    // 20 lights in a row along the view, all reaching it: the 16 nearest the camera are shaded (the same
    // image as a scene of those alone) and the 4 farthest are counted as left out.
    std::vector<Eigen::Vector3d> row;
    for (int i = 0; i < 20; ++i)
        row.push_back({-3.0 + 0.35 * i, 0.4 * ((i % 3) - 1), 1.0});
    std::reverse(row.begin(), row.end()); // the farthest first in the scene's order
    Scene everything, nearest;
    buildScene(everything, row);
    buildScene(nearest, std::vector<Eigen::Vector3d>(row.begin() + 4, row.end()));
    const Camera camera = cameraLookingAt({-6.0, 0.0, 2.0}, {0, 0, 0.3}, 96, 64, 70.0);
    Frame frames[2];
    std::uint64_t leftOut[2] = {};
    for (int i = 0; i < 2; ++i) {
        renderer().resetStats();
        RenderTarget target(renderer(), {Modality::FinalColor}, 0);
        target.render(i == 0 ? everything : nearest, camera, frames[i]);
        leftOut[i] = renderer().stats().lightsLeftOut;
    }
    EXPECT_EQ(leftOut[0], 4u);
    EXPECT_EQ(leftOut[1], 0u);
    EXPECT_TRUE(same(frames[0].get(Modality::FinalColor), frames[1].get(Modality::FinalColor)));
}

TEST_F(RenderLightsGlTest, ACoarseLevelOfDetailDoesNotShadowItself) {
    // A sphere with the built-in shape's levels, small in a 160 x 120 view, under a shadowed point light:
    // the view draws a coarse level whose quads lie inside the fine sphere the shadow maps hold (by up to
    // MeshLod::surfaceError). Its lit side must be as bright as without the shadow (before the offset grew by
    // that error, most of it was shadowed in a grid of facets: the default scene's ball at 320 x 240).
    Scene scene;
    const MeshId fine = scene.addMesh(primitives::sphere(0.5f, 48, 24));
    const double halfDiagonal = 0.5 * std::sqrt(3.0);
    std::vector<MeshLod> levels;
    for (int segments : {32, 24, 16, 12, 8}) {
        const double angle = M_PI / segments;
        levels.push_back({scene.addMesh(primitives::sphere(0.5f, segments, segments / 2)),
                          float(0.5 * (1.0 - std::cos(angle)) / halfDiagonal),
                          float(0.5 * std::sin(angle) * std::sin(angle) / halfDiagonal)});
    }
    scene.setMeshLods(fine, levels);
    const MaterialId white = scene.addMaterial(makeMaterial({0.8f, 0.8f, 0.8f}, 0.9f, 0.0f));
    Instance ball{fine, {white}, {1}};
    ball.transform = Eigen::Translation3d(0.0, 0.0, 0.5) * Eigen::Scaling(0.6);
    scene.addInstance(ball);
    Light lamp = pointLight({-1.0, -1.2, 2.2});
    lamp.range = 0.0f;
    lamp.castShadows = true;
    const LightId lampId = scene.addLight(lamp);
    Camera camera = cameraLookingAt({-4.0, -3.0, 2.0}, {0.0, 0.0, 0.5}, 160, 120, 40.0);
    camera.params.shadowResolution = 2048;
    // The level the view draws is a coarse one.
    const double focal = 80.0 / std::tan(20.0 * M_PI / 180.0);
    const double radius = 0.6 * halfDiagonal;
    const double pixels =
        radius * focal / ((camera.pose.translation() - Eigen::Vector3d(0, 0, 0.5)).norm() - radius);
    const MeshId drawn = scene.chooseLod(fine, pixels).mesh;
    ASSERT_GE(std::find_if(levels.begin(), levels.end(), [&](const MeshLod& l) { return l.mesh == drawn; }) -
                  levels.begin(),
              2);
    Frame frames[2];
    for (int i = 0; i < 2; ++i) {
        lamp.castShadows = i == 0;
        scene.setLight(lampId, lamp);
        RenderTarget target(renderer(), {Modality::DiffuseIllumination, Modality::ObjectIds}, 0);
        target.render(scene, camera, frames[i]);
    }
    const ImageBuffer& ids = frames[0].get(Modality::ObjectIds);
    const ImageBuffer& shadowed = frames[0].get(Modality::DiffuseIllumination);
    const ImageBuffer& open = frames[1].get(Modality::DiffuseIllumination);
    int lit = 0, darkened = 0;
    for (int y = 0; y < camera.params.height; ++y)
        for (int x = 0; x < camera.params.width; ++x) {
            if (ids.at(x, y) != 1.0f || open.at(x, y) < 0.05f)
                continue; // not the ball, or its side away from the lamp
            ++lit;
            darkened += shadowed.at(x, y) < 0.97f * open.at(x, y) ? 1 : 0;
        }
    ASSERT_GT(lit, 300);
    EXPECT_EQ(darkened, 0) << "of " << lit << " lit pixels";
}

} // namespace
} // namespace sp::render::test
