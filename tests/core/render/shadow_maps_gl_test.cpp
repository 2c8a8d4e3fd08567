// ShadowMaps redraws only the rectangles moving casters cover (now and at the previous update), from the
// still casters reaching into them and the moving ones. Whatever the history of updates, the maps must equal
// a fresh render of the same scene bit for bit; and when one object moves in a still scene, only its
// neighbourhood may be redrawn.

#include <epoxy/gl.h>

#include <algorithm>
#include <vector>

#include "core/render/gpu_scene_cache.h"
#include "core/render/shaders.h"
#include "core/render/shadow_maps.h"
#include "gl_fixture.h"
#include "test_scenes.h"

namespace sp::render::test {
namespace {

constexpr int kResolution = 256;

class ShadowMapsGlTest : public GlTest {
  protected:
    ShadowMapsGlTest() : depth_("shadow test", shaders::shadowVertex().c_str(), shaders::kShadowFragment) {}

    // Every layer a render of `scene` fills, as floats.
    std::vector<float> layers(ShadowMaps& maps, const Scene& scene) {
        maps.render(scene, kResolution, cache_, depth_);
        std::vector<float> values;
        for (const ShadowInfo& info : maps.infos()) {
            std::vector<float> layer(std::size_t(kResolution) * kResolution);
            glGetTextureSubImage(maps.texture(), 0, 0, 0, info.layer, kResolution, kResolution, 1, GL_RED,
                                 GL_FLOAT, GLsizei(layer.size() * sizeof(float)), layer.data());
            values.insert(values.end(), layer.begin(), layer.end());
        }
        return values;
    }

    // The maps `maps` hold after an update equal those of a ShadowMaps that never saw the scene before.
    void expectSameAsFresh(ShadowMaps& maps, const Scene& scene, const char* step) {
        const std::vector<float> kept = layers(maps, scene);
        ShadowMaps fresh;
        const std::vector<float> expected = layers(fresh, scene);
        ASSERT_EQ(kept.size(), expected.size()) << step;
        ASSERT_FALSE(kept.empty()) << step;
        EXPECT_LT(*std::min_element(kept.begin(), kept.end()), 1.0f) << step << ": the maps hold no caster";
        std::size_t differing = 0;
        for (std::size_t i = 0; i < kept.size(); ++i)
            differing += kept[i] != expected[i];
        EXPECT_EQ(differing, 0u) << step;
    }

    static void moveBy(Scene& scene, InstanceId id, const Eigen::Vector3d& offset) {
        Eigen::Affine3d transform = scene.instance(id).transform;
        transform.translation() += offset;
        scene.setTransform(id, transform);
    }

    static std::vector<InstanceId> instanceIds(const Scene& scene) {
        std::vector<InstanceId> ids;
        scene.forEachInstance([&](InstanceId id, const Instance&) { ids.push_back(id); });
        return ids;
    }

    SharedUploads uploads_;
    GpuSceneCache cache_{uploads_};
    ShaderProgram depth_;
};

TEST_F(ShadowMapsGlTest, AnyHistoryOfUpdatesGivesTheMapsOfAFreshRender) {
    Scene scene;
    buildShapesScene(scene); // ground, box, sphere, cylinder under a sun
    const std::vector<InstanceId> ids = instanceIds(scene);
    ShadowMaps maps;
    expectSameAsFresh(maps, scene, "first update");
    // Moves longer than the box's footprint: where it was must be drawn again from the still casters.
    moveBy(scene, ids[1], {1.5, 0.0, 0.0});
    expectSameAsFresh(maps, scene, "the box moved");
    moveBy(scene, ids[1], {-1.5, 1.0, 0.0});
    expectSameAsFresh(maps, scene, "the box moved again");
    EXPECT_EQ(maps.lastUpdate().fullMaps, 0u); // only around the box
    moveBy(scene, ids[1], {-0.3, 0.0, 0.1});
    moveBy(scene, ids[2], {0.0, 0.3, 0.0});
    expectSameAsFresh(maps, scene, "the box and the sphere moved");
    expectSameAsFresh(maps, scene, "nothing moved");
    scene.removeInstance(ids[2]);
    expectSameAsFresh(maps, scene, "the sphere was removed");
    Instance hidden = scene.instance(ids[3]);
    hidden.visible = false;
    scene.setInstance(ids[3], hidden);
    moveBy(scene, ids[1], {0.0, -0.2, 0.0});
    expectSameAsFresh(maps, scene, "the cylinder was hidden while the box moved");
}

TEST_F(ShadowMapsGlTest, SpotLightMapsKeepFullDepthPrecisionAndTheSameGuarantee) {
    Scene scene;
    buildSpotScene(scene);
    MeshId box = scene.addMesh(primitives::box({0.3f, 0.3f, 0.3f}));
    Instance crate{box, {scene.addMaterial(makeMaterial({0.5f, 0.5f, 0.5f}, 0.5f, 0.0f))}, {77}};
    crate.transform.translation() = Eigen::Vector3d(0.5, 0.5, 0.15);
    const InstanceId id = scene.addInstance(crate);
    ShadowMaps maps;
    expectSameAsFresh(maps, scene, "first update");
    EXPECT_EQ(maps.format(), unsigned(GL_R32F)); // perspective depth is not linear
    moveBy(scene, id, {0.8, 0.0, 0.0});
    expectSameAsFresh(maps, scene, "the crate moved");
    moveBy(scene, id, {-0.8, 0.8, 0.0});
    expectSameAsFresh(maps, scene, "the crate moved again");
    EXPECT_EQ(maps.lastUpdate().fullMaps, 0u);
}

TEST_F(ShadowMapsGlTest, OneObjectMovingInAStillSceneRedrawsOnlyItsNeighbourhood) {
    Scene scene;
    buildShapesScene(scene);
    Instance far{scene.addMesh(primitives::box({0.4f, 0.4f, 0.4f})),
                 {scene.addMaterial(makeMaterial({0.5f, 0.5f, 0.5f}, 0.5f, 0.0f))},
                 {9}};
    far.transform.translation() =
        Eigen::Vector3d(3.6, 3.6, 0.2); // in a corner of the ground, far from the sphere
    scene.addInstance(far);
    const std::vector<InstanceId> ids = instanceIds(scene);
    ShadowMaps maps;
    maps.render(scene, kResolution, cache_, depth_);
    EXPECT_EQ(maps.format(), unsigned(GL_R16)); // orthographic maps only
    moveBy(scene, ids[2], {0.05, 0.0, 0.0});    // the sphere starts moving: only around it is drawn again
    maps.render(scene, kResolution, cache_, depth_);
    EXPECT_EQ(maps.lastUpdate().fullMaps, 0u);
    moveBy(scene, ids[2], {0.05, 0.0, 0.0});
    maps.render(scene, kResolution, cache_, depth_);
    const ShadowUpdate& update = maps.lastUpdate();
    EXPECT_EQ(update.maps, 1u);
    EXPECT_EQ(update.fullMaps, 0u);
    EXPECT_EQ(update.dynamicDraws, 1u); // the sphere
    // and the still casters whose (conservative) footprints reach the sphere's: the ground, the box and the
    // cylinder nearby, not the box in the far corner.
    EXPECT_EQ(update.staticDraws, 3u);
    EXPECT_GT(update.redrawnTexels, 0u);
    EXPECT_LT(update.redrawnTexels, std::size_t(kResolution) * kResolution / 10);
}

TEST_F(ShadowMapsGlTest, CastersStoppingStartingAndLeavingAreRedrawnWhereTheyWere) {
    // A caster coming to rest, a still one starting to move, one removed and one hidden: each update redraws
    // around them alone and leaves the maps a fresh render would make.
    Scene scene;
    buildShapesScene(scene);
    const std::vector<InstanceId> ids = instanceIds(scene); // ground, box, sphere, cylinder
    ShadowMaps maps;
    expectSameAsFresh(maps, scene, "first update");
    moveBy(scene, ids[1], {0.3, 0.0, 0.0});
    expectSameAsFresh(maps, scene, "the box moved");
    expectSameAsFresh(maps, scene, "the box came to rest");
    EXPECT_EQ(maps.lastUpdate().maps, 0u) << "nothing changed: the maps are reused";
    moveBy(scene, ids[2], {0.0, 0.3, 0.0});
    expectSameAsFresh(maps, scene, "the sphere, still until now, moved");
    EXPECT_EQ(maps.lastUpdate().fullMaps, 0u);
    EXPECT_EQ(maps.lastUpdate().dynamicDraws, 1u);
    scene.removeInstance(ids[3]);
    expectSameAsFresh(maps, scene, "the still cylinder was removed");
    EXPECT_EQ(maps.lastUpdate().fullMaps, 0u);
    EXPECT_GT(maps.lastUpdate().redrawnTexels, 0u) << "where the cylinder was";
    Instance hidden = scene.instance(ids[1]);
    hidden.visible = false;
    scene.setInstance(ids[1], hidden);
    expectSameAsFresh(maps, scene, "the box was hidden");
    EXPECT_EQ(maps.lastUpdate().fullMaps, 0u);
}

TEST_F(ShadowMapsGlTest, StorageHoldsOnlyTheMapsDrawn) {
    // One sun, one layer; a second shadowed light grows the storage, and the maps still equal a fresh render.
    Scene scene;
    buildShapesScene(scene);
    ShadowMaps maps;
    expectSameAsFresh(maps, scene, "one sun");
    auto layers = [&] {
        GLint depth = 0;
        glGetTextureLevelParameteriv(maps.texture(), 0, GL_TEXTURE_DEPTH, &depth);
        return depth;
    };
    EXPECT_EQ(layers(), 1);
    Light second;
    second.direction = Eigen::Vector3d(0.3, 0.6, -1.0);
    scene.addLight(second);
    expectSameAsFresh(maps, scene, "a second sun");
    EXPECT_EQ(layers(), 2);
}

// Found by spear_rpc_fuzz: an actor moved to 1e300 made the scene's bounds infinite, and snapping them
// looped for good. Such a scene renders without shadow maps, at once.
TEST_F(ShadowMapsGlTest, AnObjectNearTheFloatLimitTurnsShadowsOffInsteadOfHanging) {
    Scene scene;
    buildShapesScene(scene);
    Instance far{scene.addMesh(primitives::box()),
                 {scene.addMaterial(makeMaterial({0.5f, 0.5f, 0.5f}, 0.5f, 0.0f))},
                 {9}};
    far.transform.translation() = Eigen::Vector3d(1e300, 0.0, 0.0);
    scene.addInstance(far);
    ShadowMaps maps;
    EXPECT_EQ(maps.render(scene, kResolution, cache_, depth_), 0u);
    EXPECT_TRUE(maps.infos().empty());
    Camera camera = cameraLookingAt({3.2, -2.4, 2.2}, {0, 0, 0.3}, 32, 24, 60.0);
    RenderTarget target(renderer(), {Modality::FinalColor}, 0);
    Frame frame;
    target.render(scene, camera, frame);
    EXPECT_EQ(frame.get(Modality::FinalColor).width, 32);
}

} // namespace
} // namespace sp::render::test
