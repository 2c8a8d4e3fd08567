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
    ShadowMapsGlTest()
        : layered_(epoxy_has_gl_extension("GL_ARB_shader_viewport_layer_array")), layers_(layered_),
          depth_("shadow test", shaders::shadowVertex(layered_).c_str(), shaders::kShadowFragment) {}

    std::uint64_t nextOwner() { return ++owners_; }

    // Every layer a render of `scene` fills, as floats.
    std::vector<float> layers(ShadowMaps& maps, const Scene& scene, const Sphere* seen = nullptr) {
        maps.render(scene, kResolution, cache_, depth_, seen);
        std::vector<float> values;
        for (const ShadowInfo& info : maps.infos()) {
            std::vector<float> layer(std::size_t(kResolution) * kResolution);
            glGetTextureSubImage(maps.texture(), 0, 0, 0, maps.firstLayer() + info.layer, kResolution,
                                 kResolution, 1, GL_RED, GL_FLOAT, GLsizei(layer.size() * sizeof(float)),
                                 layer.data());
            values.insert(values.end(), layer.begin(), layer.end());
        }
        return values;
    }

    // The maps `maps` hold after an update equal those of a ShadowMaps that never saw the scene before.
    void expectSameAsFresh(ShadowMaps& maps, const Scene& scene, const char* step,
                           const Sphere* seen = nullptr) {
        const std::vector<float> kept = layers(maps, scene, seen);
        ShadowLayers freshLayers(layered_); // storage of its own: the maps' layers are as in a new renderer
        ShadowMaps fresh(freshLayers, 1);
        const std::vector<float> expected = layers(fresh, scene, seen);
        ASSERT_EQ(kept.size(), expected.size()) << step;
        ASSERT_FALSE(kept.empty()) << step;
        EXPECT_LT(*std::min_element(kept.begin(), kept.end()), 1.0f) << step << ": the maps hold no caster";
        std::size_t differing = 0;
        for (std::size_t i = 0; i < kept.size(); ++i)
            differing += kept[i] != expected[i];
        EXPECT_EQ(differing, 0u) << step;
    }

    // The depth the first map holds where `world` falls.
    static float depthAt(const ShadowMaps& maps, const Eigen::Vector3d& world) {
        const ShadowInfo& info = maps.infos().at(0);
        const Eigen::Vector4f clip = info.worldToClip * world.cast<float>().homogeneous();
        const int x = int((clip.x() * 0.5f + 0.5f) * kResolution),
                  y = int((clip.y() * 0.5f + 0.5f) * kResolution);
        float value = -1.0f;
        glGetTextureSubImage(maps.texture(), 0, x, y, maps.firstLayer() + info.layer, 1, 1, 1, GL_RED,
                             GL_FLOAT, sizeof(value), &value);
        return value;
    }

    // Grey boxes of edge `edge` at `positions` (one mesh and material between them), object ids from
    // `firstId`.
    static std::vector<InstanceId> addBoxes(Scene& scene, float edge,
                                            const std::vector<Eigen::Vector3d>& positions,
                                            std::uint32_t firstId = 9) {
        const MeshId box = scene.addMesh(primitives::box(Eigen::Vector3f::Constant(edge)));
        const MaterialId grey = scene.addMaterial(makeMaterial({0.5f, 0.5f, 0.5f}, 0.5f, 0.0f));
        std::vector<InstanceId> ids;
        for (const Eigen::Vector3d& position : positions) {
            Instance instance{box, {grey}, {firstId++}};
            instance.transform.translation() = position;
            ids.push_back(scene.addInstance(instance));
        }
        return ids;
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

    bool layered_;
    ShadowLayers layers_;
    std::uint64_t owners_ = 0;
    SharedUploads uploads_;
    GpuSceneCache cache_{uploads_};
    ShaderProgram depth_;
};

TEST_F(ShadowMapsGlTest, AnyHistoryOfUpdatesGivesTheMapsOfAFreshRender) {
    Scene scene;
    buildShapesScene(scene); // ground, box, sphere, cylinder under a sun
    const std::vector<InstanceId> ids = instanceIds(scene);
    ShadowMaps maps(layers_, nextOwner());
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
    const InstanceId id = addBoxes(scene, 0.3f, {{0.5, 0.5, 0.15}}, 77)[0];
    ShadowMaps maps(layers_, nextOwner());
    expectSameAsFresh(maps, scene, "first update");
    EXPECT_EQ(maps.format(), unsigned(GL_R32F)); // perspective depth is not linear
    moveBy(scene, id, {0.8, 0.0, 0.0});
    expectSameAsFresh(maps, scene, "the crate moved");
    moveBy(scene, id, {-0.8, 0.8, 0.0});
    expectSameAsFresh(maps, scene, "the crate moved again");
    EXPECT_EQ(maps.lastUpdate().fullMaps, 0u);
}

TEST_F(ShadowMapsGlTest, APointLightHasACubeOfSixMapsAfterTheProjectedOnesAndTheSameGuarantee) {
    // The spot scene (a spot light and a point light) with the point light casting shadows, and a sun added
    // after them: the sun's and the spot's maps take the first layers (the vertex shader interpolates their
    // coordinates), the point light's six faces follow, each a perspective map from the lamp. A crate moving
    // near the lamp leaves the maps equal to a fresh render's, and a face it is wholly behind is not redrawn.
    Scene scene;
    buildSpotScene(scene);
    Light sun;
    sun.direction = Eigen::Vector3d(0.3, 0.2, -1.0);
    scene.addLight(sun);
    Eigen::Vector3d lamp = Eigen::Vector3d::Zero();
    scene.forEachLight([&](LightId id, const Light& light) {
        if (light.type != LightType::Point)
            return;
        Light shadowed = light;
        shadowed.castShadows = true;
        scene.setLight(id, shadowed);
        lamp = light.position;
    });
    const InstanceId id = addBoxes(scene, 0.3f, {lamp + Eigen::Vector3d(0.0, 0.0, -0.6)}, 77)[0];
    ShadowMaps maps(layers_, nextOwner());
    expectSameAsFresh(maps, scene, "first update");
    ASSERT_EQ(maps.infos().size(), 8u);
    EXPECT_EQ(maps.infos()[0].lightOrdinal, 0); // the spot light
    EXPECT_EQ(maps.infos()[1].lightOrdinal, 2); // the sun
    for (int face = 0; face < 6; ++face) {
        const ShadowInfo& info = maps.infos()[std::size_t(2 + face)];
        EXPECT_EQ(info.lightOrdinal, 1);
        EXPECT_EQ(info.layer, 2 + face);
        EXPECT_TRUE(info.perspective);
        // The face looks along its axis: the point one metre from the lamp that way is at its centre.
        Eigen::Vector3d along = Eigen::Vector3d::Zero();
        along[face / 2] = face % 2 == 0 ? 1.0 : -1.0;
        const Eigen::Vector4f clip = info.worldToClip * (lamp + along).cast<float>().homogeneous();
        EXPECT_GT(clip.w(), 0.0f) << face;
        EXPECT_NEAR(clip.x() / clip.w(), 0.0f, 1e-4f) << face;
        EXPECT_NEAR(clip.y() / clip.w(), 0.0f, 1e-4f) << face;
    }
    moveBy(scene, id, {0.2, 0.0, 0.0});
    expectSameAsFresh(maps, scene, "the crate moved under the lamp");
    EXPECT_EQ(maps.lastUpdate().fullMaps, 0u);
    // Redrawn: where the crate is in the spot's, the sun's and the lamp's downward face; the other five faces
    // see nothing of it (those it is wholly behind, above all, are not redrawn whole).
    EXPECT_LE(maps.lastUpdate().redrawnRects, 3u);
    moveBy(scene, id, {0.0, 0.3, 0.0});
    expectSameAsFresh(maps, scene, "the crate moved again");
}

TEST_F(ShadowMapsGlTest, OneObjectMovingInAStillSceneRedrawsOnlyItsNeighbourhood) {
    Scene scene;
    buildShapesScene(scene);
    addBoxes(scene, 0.4f, {{3.6, 3.6, 0.2}}); // in a corner of the ground, far from the sphere
    const std::vector<InstanceId> ids = instanceIds(scene);
    ShadowMaps maps(layers_, nextOwner());
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
    ShadowMaps maps(layers_, nextOwner());
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

TEST_F(ShadowMapsGlTest, CastersFarApartAreRedrawnInRectanglesOfTheirOwn) {
    // Two boxes moving in opposite corners of the ground: the texels between them stay as they are (one
    // rectangle around both would be most of the map), and the maps still equal a fresh render.
    Scene scene;
    buildShapesScene(scene);
    const std::vector<InstanceId> boxes = addBoxes(scene, 0.3f, {{-3.4, -3.4, 0.15}, {3.4, 3.4, 0.15}});
    const InstanceId first = boxes[0], second = boxes[1];
    ShadowMaps maps(layers_, nextOwner());
    expectSameAsFresh(maps, scene, "first update");
    for (int step = 0; step < 3; ++step) {
        moveBy(scene, first, {0.05, 0.0, 0.0});
        moveBy(scene, second, {0.0, -0.05, 0.0});
        expectSameAsFresh(maps, scene, "both boxes moved");
        const ShadowUpdate& update = maps.lastUpdate();
        EXPECT_EQ(update.fullMaps, 0u);
        EXPECT_EQ(update.redrawnRects, 2u);
        EXPECT_EQ(update.dynamicDraws, 2u);
        EXPECT_LT(update.redrawnTexels, std::size_t(kResolution) * kResolution / 20);
    }
}

TEST_F(ShadowMapsGlTest, HundredsOfMovingCastersAreRedrawnInOneRectangle) {
    // Past a few hundred rectangles, merging them pairwise would cost more than it saves: one rectangle
    // around them all is redrawn, and the maps still equal a fresh render.
    Scene scene;
    buildShapesScene(scene);
    std::vector<Eigen::Vector3d> grid;
    for (int i = 0; i < 210; ++i)
        grid.emplace_back(-3.5 + 0.5 * (i % 15), -3.5 + 0.5 * (i / 15), 1.5);
    const std::vector<InstanceId> boxes = addBoxes(scene, 0.1f, grid, 100);
    ShadowMaps maps(layers_, nextOwner());
    expectSameAsFresh(maps, scene, "first update");
    for (const InstanceId id : boxes)
        moveBy(scene, id, {0.02, 0.0, 0.0});
    expectSameAsFresh(maps, scene, "every box moved");
    EXPECT_EQ(maps.lastUpdate().fullMaps, 0u);
    EXPECT_EQ(maps.lastUpdate().redrawnRects, 1u);
}

TEST_F(ShadowMapsGlTest, StorageHoldsOnlyTheMapsDrawn) {
    // One sun, one layer; a second shadowed light grows the storage, and the maps still equal a fresh render.
    Scene scene;
    buildShapesScene(scene);
    ShadowMaps maps(layers_, nextOwner());
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

TEST_F(ShadowMapsGlTest, ObjectsFarOutOfViewNeitherStretchNorRedrawTheDirectionalMap) {
    // Objects that fell or rolled far away (as in a long co-simulation) are outside what the camera sees:
    // the sun's map keeps the region and texels of the scene in view, and their moving draws nothing.
    Scene scene;
    buildShapesScene(scene);
    Sphere seen;
    scene.bounds(seen.centre, seen.radius);
    ShadowMaps before(layers_, nextOwner());
    const std::vector<float> expected = layers(before, scene, &seen);
    const InstanceId id = addBoxes(scene, 0.3f, {{300.0, -40.0, -500.0}})[0];
    ShadowMaps maps(layers_, nextOwner());
    EXPECT_EQ(layers(maps, scene, &seen), expected);
    EXPECT_EQ(maps.directionalRegion(), before.directionalRegion());
    moveBy(scene, id, {0.0, 0.0, -20.0});
    EXPECT_EQ(layers(maps, scene, &seen), expected);
    EXPECT_EQ(maps.lastUpdate().fullMaps, 0u);
    EXPECT_EQ(maps.lastUpdate().redrawnTexels, 0u) << "the fallen box is outside the map";
    ShadowMaps whole(layers_,
                     nextOwner()); // fitted to the whole scene, the map would stretch to the fallen box
    layers(whole, scene);
    EXPECT_GT(whole.directionalRegion().radius, 100.0);
}

TEST_F(ShadowMapsGlTest, ACasterTowardsTheLightFarBeyondTheRegionStillShadowsIt) {
    // The map covers a small patch of ground; a small box 30 m up towards the sun is far outside the map's
    // depth range, yet it is drawn (at depth 0, depth clamping) and shadows the patch.
    Scene scene;
    buildShapesScene(scene); // the sun shines along (-0.4, -0.5, -1)
    const Eigen::Vector3d patch(-2.5, 2.5, 0.0);
    const Eigen::Vector3d towardsSun = -Eigen::Vector3d(-0.4, -0.5, -1.0).normalized();
    addBoxes(scene, 0.2f, {patch + 30.0 * towardsSun});
    const Sphere seen{patch, 0.5};
    ShadowMaps maps(layers_, nextOwner());
    ASSERT_GT(maps.render(scene, kResolution, cache_, depth_, &seen), 0u);
    ASSERT_LT(maps.directionalRegion().radius, 1.0);
    EXPECT_EQ(depthAt(maps, patch), 0.0f) << "the high box's shadow";
    EXPECT_GT(depthAt(maps, patch + Eigen::Vector3d(0.4, -0.1, 0.0)), 0.3f) << "the ground beside it";
}

TEST_F(ShadowMapsGlTest, TheDirectionalRegionIsKeptWhileItHoldsWhatIsSeenAndSharedByTheViewsOfAFrame) {
    Scene scene;
    buildShapesScene(scene);
    const std::vector<InstanceId> ids = instanceIds(scene);
    const Sphere view{{0.0, 0.0, 0.3}, 2.0};
    ShadowMaps maps(layers_, nextOwner());
    ASSERT_GT(maps.render(scene, kResolution, cache_, depth_, &view), 0u);
    const Sphere fitted = maps.directionalRegion();
    EXPECT_TRUE(fitted.holds(view));
    EXPECT_LT(fitted.radius, 1.5 * view.radius);

    // Another view of the same frame, seeing a little to the side: the map is shared as it is.
    const Sphere nudged{{0.1, 0.0, 0.3}, 2.0};
    EXPECT_EQ(maps.render(scene, kResolution, cache_, depth_, &nudged), 0u);
    EXPECT_EQ(maps.directionalRegion(), fitted);
    // One seeing beyond it: the region widens to hold both views, so that neither redraws it again.
    const Sphere aside{{3.0, 3.0, 0.0}, 1.0};
    EXPECT_GT(maps.render(scene, kResolution, cache_, depth_, &aside), 0u);
    const Sphere both = maps.directionalRegion();
    EXPECT_TRUE(both.holds(view) && both.holds(aside));
    EXPECT_EQ(maps.render(scene, kResolution, cache_, depth_, &view), 0u);

    // A new frame (the sphere moved) seen by the first view alone: fitted afresh, as a new map would be.
    moveBy(scene, ids[2], {0.05, 0.0, 0.0});
    expectSameAsFresh(maps, scene, "a new frame", &view);
    EXPECT_EQ(maps.directionalRegion(), fitted);
    // The next frame sees a little less: the region is kept, and only around the sphere is drawn again.
    moveBy(scene, ids[2], {0.05, 0.0, 0.0});
    const Sphere closer{{0.0, 0.0, 0.3}, 1.8};
    maps.render(scene, kResolution, cache_, depth_, &closer);
    EXPECT_EQ(maps.directionalRegion(), fitted);
    EXPECT_EQ(maps.lastUpdate().fullMaps, 0u);
    EXPECT_EQ(maps.lastUpdate().dynamicDraws, 1u);
}

// Found by spear_rpc_fuzz: an actor moved to 1e300 made the scene's bounds infinite, and snapping them
// looped for good. Such a scene renders without shadow maps, at once.
TEST_F(ShadowMapsGlTest, AnObjectNearTheFloatLimitTurnsShadowsOffInsteadOfHanging) {
    Scene scene;
    buildShapesScene(scene);
    addBoxes(scene, 1.0f, {{1e300, 0.0, 0.0}});
    ShadowMaps maps(layers_, nextOwner());
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
