// The throughput paths of the renderer: an attribute pass agrees with one pass, shadow maps are reused while
// nothing that shapes them changes (and shared by the views of a frame), instances outside the view
// are culled without changing the image, and latency 0 reads straight from the framebuffers.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <set>
#include <string>

#include "core/render/image_buffer.h"
#include "gl_fixture.h"
#include "test_scenes.h"

namespace sp::render::test {
namespace {

class RenderPathsGlTest : public GlTest {};

// Largest and mean per-channel difference of two uint8 images.
std::pair<int, double> difference(const ImageBuffer& a, const ImageBuffer& b) {
    const auto x = a.as<std::uint8_t>(), y = b.as<std::uint8_t>();
    int largest = 0;
    double sum = 0.0;
    for (std::size_t i = 0; i < x.size(); ++i) {
        const int d = std::abs(int(x[i]) - int(y[i]));
        largest = std::max(largest, d);
        sum += d;
    }
    return {largest, sum / double(x.size())};
}

TEST_F(RenderPathsGlTest, AttributePassAgreesWithOnePass) {
    Scene scene;
    buildShapesScene(scene);
    Camera camera = cameraLookingAt({3.2, -2.4, 2.2}, {0, 0, 0.3}, 96, 64, 60.0);
    ASSERT_NE(ModalitySet::all().requiredPasses(true).attributeTargets, 0u);

    // Rendered, as on a GPU: a software rasteriser computes position and the intrinsics instead, in one
    // pass (render_intrinsics_gl_test.cpp).
    const bool byDefault = renderer().derivesOnCpu();
    renderer().setDerivesOnCpu(false);
    renderer().resetStats();
    RenderTarget everything(renderer(), ModalitySet::all(), 0);
    RenderTarget colour(renderer(), {Modality::FinalColor, Modality::HdrColor, Modality::Depth}, 0);
    const ModalitySet attributes{Modality::BaseColor,  Modality::Roughness, Modality::Metallic,
                                 Modality::MaterialAo, Modality::ObjectIds, Modality::MaterialIds};
    RenderTarget plain(renderer(), attributes, 0);
    Frame all, a, b;
    everything.render(scene, camera, all);
    colour.render(scene, camera, a);
    plain.render(scene, camera, b);
    renderer().setDerivesOnCpu(byDefault);
    EXPECT_EQ(renderer().stats().surfacePasses, 3u);
    EXPECT_EQ(renderer().stats().attributePasses, 1u);

    // The attribute pass draws again at the surface pass's depth: every pixel the one-pass render
    // covers gets the same value, bit for bit (a depth mismatch would leave background holes).
    for (Modality m : attributes.list()) {
        const ImageBuffer &x = all.get(m), &y = b.get(m);
        ASSERT_EQ(x.bytes.size(), y.bytes.size());
        EXPECT_TRUE(std::equal(x.bytes.begin(), x.bytes.end(), y.bytes.begin())) << modalityName(m);
    }
    EXPECT_TRUE(std::equal(all.get(Modality::Depth).bytes.begin(), all.get(Modality::Depth).bytes.end(),
                           a.get(Modality::Depth).bytes.begin()));
    // Colour differs only by shading with the base colour and metallic rounded to float16 as diffuse_only
    // needs (see shaders.cpp, EXACT_INTRINSICS): within one 8-bit step.
    const auto [largest, mean] = difference(all.get(Modality::FinalColor), a.get(Modality::FinalColor));
    EXPECT_LE(largest, 1);
    EXPECT_LE(mean, 0.05);
    const ImageBuffer& ha = all.get(Modality::HdrColor);
    const ImageBuffer& hb = a.get(Modality::HdrColor);
    for (int y = 0; y < ha.height; ++y)
        for (int x = 0; x < ha.width; ++x)
            for (int c = 0; c < 3; ++c) {
                const float u = ha.at(x, y, c), v = hb.at(x, y, c);
                ASSERT_NEAR(u, v, 2e-3f * (std::abs(u) + std::abs(v)) + 1e-4f) << x << "," << y << " c" << c;
            }
}

TEST_F(RenderPathsGlTest, ConstantsInFlatVaryingsRenderTheSameImagesAsUniformReads) {
    // Every light type, two shadowed, more lights than a small budget holds, vignette and a non-default tone
    // curve: each modality is the same bit for bit whether the fragments read the view's constants from the
    // uniform buffer (0 slots), partly from flat varyings (the first light only) or as the renderer chooses.
    Scene scene;
    buildShapesScene(scene);
    addSpotAndPointLights(scene);
    Light fill;
    fill.direction = Eigen::Vector3d(0.6, 0.2, -0.5);
    fill.intensity = 0.4f;
    fill.castShadows = false;
    scene.addLight(fill);
    // The vignetted camera's fragments read its vignette too, so the plain one's budget is one less.
    Camera vignetted = cameraLookingAt({3.2, -2.4, 2.2}, {0, 0, 0.3}, 96, 64, 60.0);
    vignetted.params.vignetteIntensity = 0.6f;
    vignetted.params.toneMap = ToneMap::Reinhard;
    Camera plain = cameraLookingAt({-2.6, 2.9, 1.8}, {0, 0, 0.3}, 96, 64, 60.0);

    const int byDefault = renderer().constantSlots();
    // fFrame (4), fShadowSizes (1) and the sun (2): the spot, point and fill lights read the uniform buffer.
    const int budgets[] = {0, 7, std::max(byDefault, 16)};
    renderer().setAdaptiveConstantSlots(false); // these small views would spend none on their triangles
    std::vector<Frame> frames(std::size(budgets)), colours(std::size(budgets)), plains(std::size(budgets));
    for (std::size_t i = 0; i < std::size(budgets); ++i) {
        renderer().setConstantSlots(budgets[i]);
        RenderTarget target(renderer(), ModalitySet::all(), 0);
        target.render(scene, vignetted, frames[i]);
        RenderTarget colour(renderer(), {Modality::FinalColor}, 0); // final colour alone: another program
        colour.render(scene, vignetted, colours[i]);
        renderer().setConstantSlots(budgets[i] == 7 ? 6 : budgets[i]);
        colour.render(scene, plain, plains[i]);
    }
    renderer().setConstantSlots(byDefault);
    renderer().setAdaptiveConstantSlots(true);
    auto same = [](const ImageBuffer& x, const ImageBuffer& y) {
        return x.bytes.size() == y.bytes.size() &&
               std::equal(x.bytes.begin(), x.bytes.end(), y.bytes.begin());
    };
    for (std::size_t i = 1; i < std::size(budgets); ++i) {
        for (Modality m : ModalitySet::all().list())
            EXPECT_TRUE(same(frames[0].get(m), frames[i].get(m)))
                << modalityName(m) << ", slots " << budgets[i];
        EXPECT_TRUE(same(colours[0].get(Modality::FinalColor), colours[i].get(Modality::FinalColor)))
            << "final_color alone, slots " << budgets[i];
        EXPECT_TRUE(same(plains[0].get(Modality::FinalColor), plains[i].get(Modality::FinalColor)))
            << "final_color without vignette, slots " << budgets[i];
    }
}

TEST_F(RenderPathsGlTest, NormalsTurnedByFacingRenderTheImagesScreenDerivativesRender) {
    // Where a draw's normals lie on its triangles' winding side, the rasteriser's facing turns them to the
    // camera instead of a geometric normal from screen derivatives. Both turn the same interpolated normal,
    // so every modality is the same but where the derivatives' normal is too short to tell (a triangle seen
    // edge-on): from above and from under the ground, with a mirrored box, a mirrored sphere, a stretched
    // sphere (past the bound: derivatives) and a box wound inward (derivatives).
    Scene scene;
    buildShapesScene(scene);
    addSpotAndPointLights(scene);
    const MaterialId green = scene.addMaterial(makeMaterial({0.2f, 0.6f, 0.25f}, 0.35f, 0.0f));
    const MeshId box = scene.addMesh(primitives::box({0.4f, 0.3f, 0.5f}));
    const MeshId sphere = scene.addMesh(primitives::sphere(0.25f, 32, 16));
    const MeshId inwardBox = scene.addMesh(rewound(primitives::box({0.35f, 0.35f, 0.35f})));
    const auto place = [&](MeshId mesh, std::uint32_t id, const Eigen::Vector3d& at,
                           const Eigen::Vector3d& scale) {
        Instance instance{mesh, {green}, {id}};
        instance.transform = Eigen::Translation3d(at) * Eigen::AngleAxisd(0.4, Eigen::Vector3d::UnitZ()) *
                             Eigen::Scaling(scale);
        scene.addInstance(instance);
    };
    place(box, 20, {-1.0, 0.9, 0.25}, {-1.0, 1.0, 1.0});
    place(sphere, 21, {-1.2, -0.2, 0.6}, {-1.2, -1.2, 1.2});
    place(sphere, 22, {0.6, -1.4, 0.3}, {4.0, 1.0, 1.0});
    place(inwardBox, 23, {1.4, 0.7, 0.2}, {1.0, 1.0, 1.0});
    const Camera cameras[] = {cameraLookingAt({3.2, -2.4, 2.2}, {0, 0, 0.3}, 128, 96, 60.0),
                              cameraLookingAt({-2.0, 2.5, -1.5}, {0, 0, 0.0}, 128, 96, 60.0)};
    for (const Camera& camera : cameras) {
        Frame frames[2];
        std::uint64_t faced[2] = {};
        for (const bool facing : {false, true}) {
            renderer().setFacingFromWinding(facing);
            renderer().resetStats();
            RenderTarget target(renderer(), ModalitySet::all(), 0);
            target.render(scene, camera, frames[facing]);
            faced[facing] = renderer().stats().windingFacedInstances;
        }
        renderer().setFacingFromWinding(true);
        EXPECT_EQ(faced[0], 0u);
        // All but the stretched sphere and the inward box (those in view: the ground, the three shapes, the
        // mirrored box and sphere).
        EXPECT_EQ(faced[1], renderer().stats().drawnInstances - 2);
        for (Modality m : ModalitySet::all().list()) {
            const auto& a = frames[0].get(m).bytes;
            const auto& b = frames[1].get(m).bytes;
            ASSERT_EQ(a.size(), b.size()) << modalityName(m);
            const std::size_t pixel = a.size() / (128 * 96);
            std::size_t differing = 0;
            for (std::size_t i = 0; i < a.size(); i += pixel)
                differing += std::equal(a.begin() + i, a.begin() + i + pixel, b.begin() + i) ? 0 : 1;
            EXPECT_LE(differing, 128u * 96u / 500u) << modalityName(m) << ": pixels that differ";
        }
    }
}

TEST_F(RenderPathsGlTest, ViewsOfManyTrianglesPerPixelReadTheirConstantsFromTheUniformBuffer) {
    // With a budget of slots, a view spends them only where it has kPixelsPerConstantTriangle pixels for each
    // triangle it draws: the same scene seen large spends them, seen small (or as finely tessellated spheres)
    // reads the uniform buffer; the images are the same as with the budget spent whatever the view draws.
    EXPECT_EQ(renderer().viewConstantSlots(10, 16 * 10), renderer().constantSlots());
    EXPECT_EQ(renderer().viewConstantSlots(10, 16 * 10 - 1), 0);
    Scene scene;
    buildShapesScene(scene);
    const MeshId fine = scene.addMesh(primitives::sphere(0.3f, 64, 32)); // 4,096 triangles
    scene.addInstance({fine, {scene.addMaterial(makeMaterial({0.3f, 0.5f, 0.8f}, 0.4f, 0.0f))}, {40}});
    const int byDefault = renderer().constantSlots();
    renderer().setConstantSlots(std::max(byDefault, 16));
    const Camera large = cameraLookingAt({-2.6, 2.9, 1.8}, {0, 0, 0.3}, 1600, 1200, 60.0);
    const Camera small = cameraLookingAt({-2.6, 2.9, 1.8}, {0, 0, 0.3}, 96, 64, 60.0);
    std::vector<Frame> adaptive(2), spent(2);
    std::vector<std::uint64_t> passes;
    for (int on = 1; on >= 0; --on) {
        renderer().setAdaptiveConstantSlots(on == 1);
        int v = 0;
        for (const Camera* camera : {&large, &small}) {
            RenderTarget target(renderer(), {Modality::FinalColor, Modality::Normal, Modality::ObjectIds}, 0);
            const std::uint64_t before = renderer().stats(scene.uid()).constantSlotPasses;
            target.render(scene, *camera, (on == 1 ? adaptive : spent)[std::size_t(v++)]);
            passes.push_back(renderer().stats(scene.uid()).constantSlotPasses - before);
        }
    }
    renderer().setConstantSlots(byDefault);
    renderer().setAdaptiveConstantSlots(true);
    EXPECT_EQ(passes, (std::vector<std::uint64_t>{1, 0, 1, 1})) << "large, small; adaptive, then spent";
    for (std::size_t v = 0; v < 2; ++v)
        for (Modality m : {Modality::FinalColor, Modality::Normal, Modality::ObjectIds}) {
            const ImageBuffer &x = adaptive[v].get(m), &y = spent[v].get(m);
            EXPECT_TRUE(x.bytes.size() == y.bytes.size() &&
                        std::equal(x.bytes.begin(), x.bytes.end(), y.bytes.begin()))
                << modalityName(m) << (v == 0 ? ", large view" : ", small view");
        }
}

TEST_F(RenderPathsGlTest, ShadingWithoutLookupsWhereNoShadowReachesRendersTheSameImages) {
    // A floor much larger than the shadows on it, a low sun and a shadowed spot light; a box and a sphere
    // floating where no other shadow reaches, and a tall post behind the second camera whose shadow falls
    // into its view (its region crosses the camera's near plane). Every modality is the same bit for bit
    // whether the surface pass skips the shadow lookups where no shadow reaches (the floor in parts) or not.
    Scene scene;
    const MeshId floor = scene.addMesh(primitives::plane(40, 40));
    const MeshId box = scene.addMesh(primitives::box({0.8f, 0.8f, 0.8f}));
    const MeshId sphere = scene.addMesh(primitives::sphere(0.45f, 32, 16));
    const MeshId post = scene.addMesh(primitives::box({0.2f, 0.2f, 3.0f}));
    const MaterialId grey = scene.addMaterial(makeMaterial({0.6f, 0.6f, 0.55f}, 0.9f, 0.0f));
    const MaterialId red = scene.addMaterial(makeMaterial({0.7f, 0.12f, 0.1f}, 0.5f, 0.0f));
    const MaterialId gold = scene.addMaterial(makeMaterial({1.0f, 0.78f, 0.34f}, 0.3f, 1.0f));
    scene.addInstance({floor, {grey}, {1}});
    const auto place = [&](MeshId mesh, MaterialId material, std::uint32_t id, Eigen::Vector3d at) {
        Instance instance{mesh, {material}, {id}};
        instance.transform.translation() = at;
        scene.addInstance(instance);
    };
    place(box, red, 2, {0.3, 0.8, 0.4});
    place(sphere, gold, 3, {-0.2, -0.5, 0.45});
    place(box, red, 4, {1.4, -0.9, 0.4});
    place(box, red, 5, {2.5, -1.5, 3.0});    // floating: nothing shadows it
    place(sphere, gold, 7, {3.5, 0.5, 2.5}); // floating, but smooth: it shadows itself near its terminator
    place(post, grey, 6, {-4.5, 4.5, 1.5});
    Light sun;
    sun.direction = Eigen::Vector3d(0.8, -0.3, -0.5);
    sun.intensity = 3.0f;
    scene.addLight(sun);
    addSpotAndPointLights(scene);
    // The point light's shadows (a cube of maps around it) reach as far as it lights: a short range keeps
    // the floor far from it free of lookups, so that the floor is still drawn in parts.
    scene.forEachLight([&](LightId id, const Light& light) {
        if (light.type != LightType::Point)
            return;
        Light lamp = light;
        lamp.range = 1.5f;
        scene.setLight(id, lamp);
    });
    Environment environment;
    environment.ambient = {0.12f, 0.14f, 0.18f};
    environment.background = {0.25f, 0.3f, 0.4f};
    scene.setEnvironment(environment);
    Camera wide = cameraLookingAt({11.0, -9.0, 4.5}, {0.5, 0.0, 0.3}, 800, 450, 60.0);
    wide.params.shadowResolution = 1024;
    Camera past = cameraLookingAt({-3.0, 3.0, 1.6}, {0.5, -0.5, 0.3}, 480, 270, 70.0);

    const bool byDefault = renderer().shadowReach();
    std::vector<Frame> all(4), colour(4);
    std::uint64_t split = 0, unshadowed = 0;
    for (int i = 0; i < 4; ++i) {
        renderer().setShadowReach(i % 2 == 1);
        renderer().resetStats();
        const Camera& camera = i < 2 ? wide : past;
        RenderTarget everything(renderer(), ModalitySet::all(), 0);
        RenderTarget alone(renderer(), {Modality::FinalColor}, 0);
        everything.render(scene, camera, all[std::size_t(i)]);
        alone.render(scene, camera, colour[std::size_t(i)]);
        split += renderer().stats().splitInstances;
        unshadowed += renderer().stats().unshadowedInstances;
        if (i % 2 == 0) {
            EXPECT_EQ(renderer().stats().splitInstances + renderer().stats().unshadowedInstances, 0u);
        }
    }
    renderer().setShadowReach(byDefault);
    EXPECT_GE(split, 2u);      // the floor, in both views
    EXPECT_GE(unshadowed, 2u); // the floating box, at least
    for (int i : {1, 3}) {
        const std::size_t with = std::size_t(i), without = std::size_t(i - 1);
        for (Modality m : ModalitySet::all().list()) {
            const ImageBuffer &x = all[without].get(m), &y = all[with].get(m);
            EXPECT_TRUE(std::equal(x.bytes.begin(), x.bytes.end(), y.bytes.begin()))
                << modalityName(m) << ", view " << i / 2;
        }
        const ImageBuffer &x = colour[without].get(Modality::FinalColor),
                          &y = colour[with].get(Modality::FinalColor);
        EXPECT_TRUE(std::equal(x.bytes.begin(), x.bytes.end(), y.bytes.begin()))
            << "final_color alone, view " << i / 2;
    }
    // The post's shadow and the cluster's are in view: the lookups still ran where they fall.
    const auto [largest, mean] =
        difference(colour[0].get(Modality::FinalColor), colour[2].get(Modality::FinalColor));
    EXPECT_GT(largest, 0);
}

TEST_F(RenderPathsGlTest, ComputeLightingAgreesWithShadingInTheFragments) {
    // The shapes scene under a shadowed sun and spot light and a ranged point light, with a textured box
    // beside the untextured shapes (all shaded by the compute pass when it is on), views larger than a shared
    // page (512 x 512) so that they have framebuffers of their own. Colour alone; colour with depth and ids
    // (unshaded targets beside the G-buffer); hdr_color; a vignetted final_color with Reinhard's curve, whose
    // background the compute pass writes; colour with six material and geometry modalities, which leave a
    // draw buffer for the G-buffer but none for the textured box's material (shaded in its fragments). The
    // images agree but for the pixels where a shadow's edge or a face's edge falls: the compute pass computes
    // shadow-map coordinates per pixel where the fragments interpolate the vertices', and reads the normal
    // back from 22 bits and a textured material from 8 bits a channel; the unshaded targets are the same bit
    // for bit.
    Scene scene;
    buildShapesScene(scene);
    addSpotAndPointLights(scene);
    std::vector<std::uint8_t> rgba(4 * 4 * 4);
    for (std::size_t i = 0; i < rgba.size(); ++i)
        rgba[i] = i % 4 == 3 ? 255 : std::uint8_t(40 + 13 * i);
    Material textured = makeMaterial({1.0f, 1.0f, 1.0f}, 0.6f, 0.0f);
    textured.baseColorTexture = scene.addTexture(TextureImage::fromPixels(4, 4, rgba));
    Instance crate{scene.addMesh(primitives::box({0.5f, 0.5f, 0.5f})), {scene.addMaterial(textured)}, {9}};
    crate.transform.translation() = Eigen::Vector3d(-1.3, 0.9, 0.25);
    scene.addInstance(crate);
    Camera camera = cameraLookingAt({3.2, -3.0, 2.4}, {0.0, 0.0, 0.3}, 640, 560, 60.0);
    camera.params.shadowResolution = 1024;
    Camera vignetted = camera;
    vignetted.params.vignetteIntensity = 0.6f;
    vignetted.params.toneMap = ToneMap::Reinhard;
    const std::pair<ModalitySet, const Camera*> cases[] = {
        {{Modality::FinalColor}, &camera},
        {{Modality::FinalColor, Modality::Depth, Modality::ObjectIds}, &camera},
        {{Modality::HdrColor}, &camera},
        {{Modality::FinalColor}, &vignetted},
        {{Modality::FinalColor, Modality::Position, Modality::Normal, Modality::Depth, Modality::BaseColor,
          Modality::Roughness, Modality::ObjectIds},
         &camera},
    };
    // Float targets: the compute pass stores floats, so compact targets (llvmpipe's default) keep a view in
    // its fragments.
    const bool byDefault = renderer().computeLighting(), compactByDefault = renderer().compactTargets();
    renderer().setCompactTargets(false);
    for (const auto& [modalities, view] : cases) {
        Frame frames[2];
        bool materialTarget = false;
        for (int compute = 0; compute < 2; ++compute) {
            renderer().setComputeLighting(compute == 1);
            PassSet passes = modalities.requiredPasses(true);
            renderer().planComputeLighting(passes);
            EXPECT_EQ(passes.computeLighting(), compute == 1);
            materialTarget =
                (passes.surfaceTargets & render::targetBit(render::Target::GBufferMaterial)) != 0;
            EXPECT_EQ(materialTarget, compute == 1 && modalities.size() < 7);
            RenderTarget target(renderer(), modalities, 0);
            target.render(scene, *view, frames[compute]);
        }
        renderer().setComputeLighting(byDefault);
        for (Modality m : modalities.list()) {
            const ImageBuffer &forward = frames[0].get(m), &computed = frames[1].get(m);
            if (m != Modality::FinalColor && m != Modality::HdrColor) {
                EXPECT_TRUE(std::equal(forward.bytes.begin(), forward.bytes.end(), computed.bytes.begin()))
                    << modalityName(m);
                continue;
            }
            // Per channel: how many differ by more than 2 of 255 (final_color) or by more than 1% and 1e-3
            // (hdr_color), and the mean difference.
            std::size_t far = 0, channels = 0;
            double sum = 0.0;
            for (int y = 0; y < forward.height; ++y)
                for (int x = 0; x < forward.width; ++x)
                    for (int c = 0; c < 3; ++c, ++channels) {
                        const double a = forward.at(x, y, c), b = computed.at(x, y, c);
                        const double d = std::abs(a - b);
                        sum += d;
                        far += m == Modality::FinalColor ? d > 2.0 : d > 1e-3 + 0.01 * std::abs(a);
                    }
            EXPECT_LT(double(far) / double(channels), 0.005) << modalityName(m);
            EXPECT_LT(sum / double(channels), m == Modality::FinalColor ? 0.1 : 1e-3) << modalityName(m);
            // The textured crate: from its material texel, within what 8 bits a channel round (a step of
            // base colour's square root moves final_color by at most 1 of 255 here); in its fragments where
            // the pass had no room for the texel, by a program that also writes the G-buffer, which the
            // shader compiler may round differently in the last bit.
            const Eigen::Vector3d crateAt = view->project(Eigen::Vector3d(-1.3, 0.9, 0.5));
            const int cx = int(crateAt.x()), cy = int(crateAt.y());
            for (int c = 0; c < 3; ++c)
                EXPECT_NEAR(forward.at(cx, cy, c), computed.at(cx, cy, c),
                            m == Modality::FinalColor ? 1.0 : 0.01 * forward.at(cx, cy, c) + 1e-3)
                    << modalityName(m) << " on the crate, "
                    << (materialTarget ? "compute-lit" : "in its fragments");
        }
        // A longer ring reads the same compute-lit frame (the readback waits for the image stores).
        if (view == &camera && modalities.size() == 1) {
            renderer().setComputeLighting(true);
            RenderTarget ring(renderer(), modalities, 1);
            Frame later;
            ring.submit(scene, *view);
            ring.submit(scene, *view);
            ASSERT_EQ(ring.read(later), 1u);
            renderer().setComputeLighting(byDefault);
            const Modality m = modalities.list().front();
            EXPECT_TRUE(std::equal(later.get(m).bytes.begin(), later.get(m).bytes.end(),
                                   frames[1].get(m).bytes.begin()))
                << modalityName(m) << " at latency 1";
        }
        // One target moving between the paths as its modalities change: colour alone (compute), colour with
        // an intrinsic image (fragments), colour alone again, the same as the first.
        if (view == &camera && modalities.size() == 1 && modalities.contains(Modality::FinalColor)) {
            renderer().setComputeLighting(true);
            RenderTarget moving(renderer(), modalities, 0);
            Frame first, between, again;
            moving.render(scene, *view, first);
            moving.setModalities({Modality::FinalColor, Modality::DiffuseOnly});
            moving.render(scene, *view, between);
            moving.setModalities(modalities);
            moving.render(scene, *view, again);
            renderer().setComputeLighting(byDefault);
            const ImageBuffer &a = first.get(Modality::FinalColor), &b = again.get(Modality::FinalColor);
            EXPECT_TRUE(std::equal(a.bytes.begin(), a.bytes.end(), b.bytes.begin()))
                << "back to compute lighting";
            EXPECT_LT(difference(a, between.get(Modality::FinalColor)).second, 0.1)
                << "through the fragments";
        }
        // The vignetted background is darker in the corner than in the middle, as the forward pass draws it.
        if (view == &vignetted) {
            const ImageBuffer& image = frames[1].get(Modality::FinalColor);
            EXPECT_EQ(image.at(0, 0, 2), frames[0].get(Modality::FinalColor).at(0, 0, 2));
            EXPECT_LT(image.at(0, 0, 2), image.at(320, 5, 2));
        }
    }
    renderer().setCompactTargets(compactByDefault);
}

TEST_F(RenderPathsGlTest, TheGpuPathSwitchesAreReadFromTheEnvironmentAndCheckedThere) {
    // SPEAR_LIGHTING, SPEAR_READBACK, SPEAR_DERIVED_MODALITIES and SPEAR_TARGET_FORMATS override the device's
    // defaults; a value that is neither choice is refused naming the variable and the value.
    GlContext& context = *context_;
    ::setenv("SPEAR_LIGHTING", "compute", 1);
    ::setenv("SPEAR_READBACK", "direct", 1);
    ::setenv("SPEAR_DERIVED_MODALITIES", "rendered", 1);
    ::setenv("SPEAR_TARGET_FORMATS", "float", 1);
    {
        Renderer forced(context);
        EXPECT_TRUE(forced.computeLighting());
        EXPECT_FALSE(forced.stagedReadback());
        EXPECT_FALSE(forced.derivesOnCpu());
        EXPECT_FALSE(forced.compactTargets());
    }
    // A variable set to a value that is neither choice: the renderer is refused, naming both.
    const auto expectRefused = [&](const char* variable, const char* value, const char* message) {
        ::setenv(variable, value, 1);
        try {
            Renderer refused(context);
            ADD_FAILURE() << variable << "=" << value << " was accepted";
        } catch (const InvalidArgument& e) {
            EXPECT_STREQ(e.what(), message);
        }
    };
    expectRefused("SPEAR_DERIVED_MODALITIES", "gpu",
                  "Renderer::Renderer(): SPEAR_DERIVED_MODALITIES must be 'cpu' or 'rendered', got 'gpu'");
    ::unsetenv("SPEAR_DERIVED_MODALITIES");
    expectRefused("SPEAR_TARGET_FORMATS", "half",
                  "Renderer::Renderer(): SPEAR_TARGET_FORMATS must be 'compact' or 'float', got 'half'");
    ::unsetenv("SPEAR_TARGET_FORMATS");
    expectRefused("SPEAR_LIGHTING", "deferred",
                  "Renderer::Renderer(): SPEAR_LIGHTING must be 'compute' or 'forward', got 'deferred'");
    ::unsetenv("SPEAR_LIGHTING");
    ::unsetenv("SPEAR_READBACK");
    Renderer byDefault(context);
    EXPECT_EQ(byDefault.computeLighting(), !context.report().software);
    EXPECT_EQ(byDefault.stagedReadback(), !context.report().software);
    EXPECT_EQ(byDefault.derivesOnCpu(), context.report().software);
    EXPECT_EQ(byDefault.compactTargets(), context.report().software);
    context.makeCurrent(); // the fixture's renderer goes on in the same context
}

TEST_F(RenderPathsGlTest, DrawsPastWhatTheGBufferCanNameAreShadedInTheirFragments) {
    // The G-buffer names 1023 draws of a view (shaders::kGBufferRecords): 900 small boxes (one batch, lit by
    // the compute pass) and 300 small spheres after them (a batch past the limit, shaded in its fragments)
    // on a grid under a shadowed sun. The image agrees with fragment shading, and a sphere is the same bit
    // for bit.
    Scene scene;
    const MeshId box = scene.addMesh(primitives::box({0.1f, 0.1f, 0.1f}));
    const MeshId sphere = scene.addMesh(primitives::sphere(0.06f, 12, 6));
    const MaterialId red = scene.addMaterial(makeMaterial({0.7f, 0.12f, 0.1f}, 0.5f, 0.0f));
    const MaterialId blue = scene.addMaterial(makeMaterial({0.1f, 0.25f, 0.7f}, 0.3f, 0.0f));
    for (int i = 0; i < 1200; ++i) {
        Instance instance{i < 900 ? box : sphere, {i < 900 ? red : blue}, {std::uint32_t(i + 1)}};
        instance.transform.translation() = Eigen::Vector3d(0.2 * (i % 40) - 4.0, 0.2 * (i / 40) - 3.0, 0.0);
        scene.addInstance(instance);
    }
    Light sun;
    sun.direction = Eigen::Vector3d(-0.4, -0.5, -1.0);
    sun.intensity = 3.0f;
    scene.addLight(sun);
    const Camera camera = cameraLookingAt({0.0, -1.0, 9.0}, {0.0, 0.0, 0.0}, 640, 560, 60.0);
    // Float targets: compact ones (llvmpipe's default) keep a view in its fragments.
    const bool byDefault = renderer().computeLighting(), compactByDefault = renderer().compactTargets();
    renderer().setCompactTargets(false);
    Frame frames[2];
    for (int compute = 0; compute < 2; ++compute) {
        renderer().setComputeLighting(compute == 1);
        RenderTarget target(renderer(), {Modality::FinalColor, Modality::ObjectIds}, 0);
        target.render(scene, camera, frames[compute]);
    }
    renderer().setComputeLighting(byDefault);
    renderer().setCompactTargets(compactByDefault);
    const ImageBuffer &forward = frames[0].get(Modality::FinalColor),
                      &computed = frames[1].get(Modality::FinalColor);
    const auto [largest, mean] = difference(forward, computed);
    EXPECT_LT(mean, 0.1);
    int spheres = 0, boxes = 0;
    for (int y = 0; y < forward.height; ++y)
        for (int x = 0; x < forward.width; ++x) {
            const std::uint32_t id = frames[1].get(Modality::ObjectIds).uintAt(x, y);
            if (id > 900) {
                ++spheres;
                for (int c = 0; c < 3; ++c)
                    ASSERT_EQ(forward.at(x, y, c), computed.at(x, y, c)) << "sphere pixel " << x << ", " << y;
            } else if (id > 0) {
                ++boxes;
            }
        }
    EXPECT_GT(spheres, 1000);
    EXPECT_GT(boxes, 1000);
}

TEST_F(RenderPathsGlTest, AttributePassKeepsTheSurfacePassesFragmentWhereSurfacesTie) {
    // Two instances in the same place, different ids and materials: the surface pass keeps the first drawn
    // (GL_LESS); the attribute pass must write that one's ids and base colour, not the second's.
    Scene scene;
    buildShapesScene(scene);
    MeshId box = scene.addMesh(primitives::box({1.0f, 1.0f, 1.0f}));
    for (std::uint32_t id : {50u, 60u}) {
        Instance twin{box, {scene.addMaterial(makeMaterial({id / 100.0f, 0.2f, 0.2f}, 0.5f, 0.0f))}, {id}};
        twin.transform.translation() = Eigen::Vector3d(-1.0, 1.0, 0.5);
        scene.addInstance(twin);
    }
    Camera camera = cameraLookingAt({3.2, -2.4, 2.2}, {0, 0, 0.3}, 96, 64, 60.0);
    RenderTarget everything(renderer(), ModalitySet::all(), 0);
    RenderTarget alone(renderer(), {Modality::ObjectIds, Modality::BaseColor}, 0);
    ASSERT_NE(ModalitySet::all().requiredPasses(true).attributeTargets & targetBit(Target::Ids), 0u);
    Frame all, one;
    everything.render(scene, camera, all);
    alone.render(scene, camera, one);
    const auto ids = all.get(Modality::ObjectIds).as<std::uint32_t>();
    EXPECT_TRUE(std::find(ids.begin(), ids.end(), 50u) != ids.end() ||
                std::find(ids.begin(), ids.end(), 60u) != ids.end()); // the twins are in view
    for (Modality m : {Modality::ObjectIds, Modality::BaseColor}) {
        const ImageBuffer &x = all.get(m), &y = one.get(m);
        EXPECT_TRUE(std::equal(x.bytes.begin(), x.bytes.end(), y.bytes.begin())) << modalityName(m);
    }
}

// Where no surface is textured, a software rasteriser reads the material modalities (base colour, the
// parameters, both ids) from the draw each pixel's Target::Record names: the same images, bit for bit, as
// rendering them (compact targets round float16 as the lookup does), at latency 0 and 1, in a layer of a
// page and in framebuffers of its own, with two coincident boxes of which the first drawn stays in front.
// A base colour texture leaves base colour drawn (its box shows the texture's checker) and the rest looked
// up.
TEST_F(RenderPathsGlTest, MaterialModalitiesLookedUpFromTheDrawMatchTheRenderedOnes) {
    Scene scene;
    buildShapesScene(scene);
    addSpotAndPointLights(scene);
    MeshId box = scene.addMesh(primitives::box({1.0f, 1.0f, 1.0f}));
    for (std::uint32_t id : {50u, 60u}) {
        Material m = makeMaterial({id / 100.0f, 0.2f, 0.2f}, 0.1f * float(id) / 60.0f, 0.4f);
        m.ambientOcclusion = 0.7f;
        Instance twin{box, {scene.addMaterial(m)}, {id}};
        twin.transform.translation() = Eigen::Vector3d(-1.0, 1.0, 0.5);
        scene.addInstance(twin);
    }
    const bool derivesByDefault = renderer().derivesOnCpu(), compactByDefault = renderer().compactTargets();
    renderer().setCompactTargets(true);
    const ModalitySet materials = materialModalities();
    for (const int latency : {0, 1})
        for (const int width : {96, 640}) { // a layer of a page; framebuffers of its own
            const Camera camera = cameraLookingAt({3.2, -2.4, 2.2}, {0, 0, 0.3}, width, width * 2 / 3, 60.0);
            std::array<Frame, 2> frames; // looked up, rendered
            for (const bool derives : {true, false}) {
                renderer().setDerivesOnCpu(derives);
                RenderTarget target(renderer(), ModalitySet::all(), latency);
                for (int i = 0; i <= latency; ++i)
                    target.submit(scene, camera);
                ASSERT_TRUE(target.read(frames[derives ? 0 : 1]).has_value());
            }
            const std::string where =
                "latency " + std::to_string(latency) + ", " + std::to_string(width) + " wide: ";
            for (Modality m : materials.list()) {
                const ImageBuffer &a = frames[0].get(m), &b = frames[1].get(m);
                EXPECT_TRUE(std::equal(a.bytes.begin(), a.bytes.end(), b.bytes.begin()))
                    << where << modalityName(m);
            }
            const auto ids = frames[0].get(Modality::ObjectIds).as<std::uint32_t>();
            EXPECT_NE(std::find(ids.begin(), ids.end(), 50u), ids.end())
                << where << "the first twin is in front";
            EXPECT_EQ(std::find(ids.begin(), ids.end(), 60u), ids.end())
                << where << "the second is behind it";
        }

    // A checker base colour texture on one box: rendered, so its pixels differ.
    std::vector<std::uint8_t> checker;
    for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 16; ++x)
            checker.insert(checker.end(), {std::uint8_t((x / 4 + y / 4) % 2 ? 230 : 20), 128, 128, 255});
    Material textured = makeMaterial({1.0f, 1.0f, 1.0f}, 0.6f, 0.0f);
    textured.baseColorTexture =
        scene.addTexture(TextureImage::fromPixels(16, 16, checker), TextureEncoding::Linear);
    Instance crate{box, {scene.addMaterial(textured)}, {70}};
    crate.transform.translation() = Eigen::Vector3d(1.0, 1.2, 0.5);
    scene.addInstance(crate);
    std::array<Frame, 2> frames; // base colour drawn and the rest looked up; all drawn
    for (const bool derives : {true, false}) {
        renderer().setDerivesOnCpu(derives);
        RenderTarget target(renderer(), ModalitySet::all(), 0);
        ASSERT_TRUE(target.render(scene, cameraLookingAt({3.2, -2.4, 2.2}, {0, 0, 0.3}, 640, 426, 60.0),
                                  frames[derives ? 0 : 1]));
    }
    for (Modality m : materials.list()) {
        const ImageBuffer &a = frames[0].get(m), &b = frames[1].get(m);
        EXPECT_TRUE(std::equal(a.bytes.begin(), a.bytes.end(), b.bytes.begin()))
            << "textured: " << modalityName(m);
    }
    const Frame& frame = frames[0];
    const auto ids = frame.get(Modality::ObjectIds).as<std::uint32_t>();
    const auto base = frame.get(Modality::BaseColor).as<std::uint16_t>();
    std::set<std::uint16_t> reds;
    for (std::size_t p = 0; p < ids.size(); ++p)
        if (ids[p] == 70u)
            reds.insert(base[3 * p]);
    EXPECT_GT(reds.size(), 1u) << "the textured box's base colour varies across it";
    renderer().setDerivesOnCpu(derivesByDefault);
    renderer().setCompactTargets(compactByDefault);
}

TEST_F(RenderPathsGlTest, ShadowMapsAreReusedUntilSomethingMoves) {
    Scene scene;
    buildShapesScene(scene);
    Camera left = cameraLookingAt({3.2, -2.4, 2.2}, {0, 0, 0.3}, 48, 32, 60.0);
    Camera right = cameraLookingAt({3.2, -2.1, 2.2}, {0, 0.3, 0.3}, 48, 32, 60.0);
    RenderTarget a(renderer(), {Modality::FinalColor}, 0), b(renderer(), {Modality::FinalColor}, 0);
    Frame frame;
    a.render(scene, left, frame); // whatever earlier tests left in the shadow maps is replaced here
    renderer().resetStats();

    b.render(scene, right, frame); // a second view of the same frame
    EXPECT_EQ(renderer().stats().shadowPasses, 0u);
    EXPECT_EQ(renderer().stats().shadowReuses, 1u);

    Frame before;
    a.render(scene, left, before);
    InstanceId moved{};
    scene.forEachInstance([&](InstanceId id, const Instance&) { moved = id; });
    Eigen::Affine3d transform = scene.instance(moved).transform;
    transform.translation().x() += 0.25;
    scene.setTransform(moved, transform);
    a.render(scene, left, frame);
    EXPECT_GE(renderer().stats().shadowPasses, 1u); // an instance moved: the maps are rendered again

    renderer().resetStats();
    left.params.shadowResolution = 256;
    a.render(scene, left, frame);
    EXPECT_GE(renderer().stats().shadowPasses, 1u); // a new resolution too
}

TEST_F(RenderPathsGlTest, ObjectsFallingFarOutOfViewLeaveTheImageAsItWas) {
    // The sun's map covers what the camera sees: an object far out of view (fallen off the ground in a long
    // run) neither coarsens the shadows in the image nor makes the map be drawn again when it moves.
    Scene scene;
    buildShapesScene(scene);
    Camera camera = cameraLookingAt({3.2, -2.4, 2.2}, {0, 0, 0.3}, 96, 64, 60.0);
    RenderTarget target(renderer(), {Modality::FinalColor}, 0);
    Frame before;
    target.render(scene, camera, before);
    Instance fallen{scene.addMesh(primitives::sphere(0.15f, 16, 8)),
                    {scene.addMaterial(makeMaterial({0.5f, 0.5f, 0.5f}, 0.5f, 0.0f))},
                    {9}};
    fallen.transform.translation() = Eigen::Vector3d(-150.0, 80.0, -400.0);
    const InstanceId id = scene.addInstance(fallen);
    for (int step = 0; step < 2; ++step) {
        renderer().resetStats();
        Frame after;
        target.render(scene, camera, after);
        const ImageBuffer &x = before.get(Modality::FinalColor), &y = after.get(Modality::FinalColor);
        EXPECT_TRUE(std::equal(x.bytes.begin(), x.bytes.end(), y.bytes.begin())) << "step " << step;
        EXPECT_EQ(renderer().stats().culledInstances, 1u);
        Eigen::Affine3d transform = scene.instance(id).transform;
        transform.translation().z() -= 30.0;
        scene.setTransform(id, transform);
    }
}

TEST_F(RenderPathsGlTest, ScenesSharingARendererKeepTheirShadowMapsAndStatistics) {
    // Two worlds' scenes drawn in turn by one renderer: each keeps its shadow maps (reused from its own
    // previous frame, not redrawn because the other scene was drawn in between) and its own counts.
    Scene first, second;
    buildShapesScene(first);
    buildShapesScene(second);
    renderer().resetStats(); // the totals below count these two scenes, not those of earlier tests
    Camera camera = cameraLookingAt({3.2, -2.4, 2.2}, {0, 0, 0.3}, 48, 32, 60.0);
    RenderTarget a(renderer(), {Modality::FinalColor, Modality::ObjectIds}, 1);
    RenderTarget b(renderer(), {Modality::FinalColor}, 0);
    Frame frame;
    for (int i = 0; i < 3; ++i) {
        a.render(first, camera, frame);
        b.render(second, camera, frame);
    }
    const RenderStats one = renderer().stats(first.uid()), two = renderer().stats(second.uid());
    EXPECT_EQ(one.frames, 3u);
    EXPECT_EQ(two.frames, 3u);
    EXPECT_EQ(one.shadowReuses, 2u) << "the first scene's maps survive the second scene's frames";
    EXPECT_EQ(two.shadowReuses, 2u);
    EXPECT_EQ(one.shadowPasses, two.shadowPasses);
    EXPECT_EQ(one.readbacks, 4u) << "latency 1: frames 1 and 2 read, two modalities each";
    EXPECT_EQ(two.readbacks, 3u);
    const RenderStats total = renderer().stats();
    EXPECT_EQ(total.frames, one.frames + two.frames);
    EXPECT_EQ(total.readbacks, one.readbacks + two.readbacks);

    renderer().releaseScene(first);
    EXPECT_EQ(renderer().stats(first.uid()).frames, 0u) << "released with its statistics";
    std::vector<std::uint8_t> color(48 * 32 * 4);
    const OutputView view[] = {{Modality::FinalColor, color.data(), color.size()}};
    EXPECT_EQ(a.readAgain(view), 2u); // a frame of the released scene still reads, uncounted
    EXPECT_EQ(renderer().stats().frames, two.frames);
    EXPECT_EQ(renderer().stats().readbacks, two.readbacks);
}

TEST_F(RenderPathsGlTest, MeshesUnderASharedKeyAreUploadedOnceForAllScenes) {
    // What an engine's worlds do with a built-in shape: each scene adds it under the same key.
    Scene first, second, own;
    auto addBox = [](Scene& scene, float size, const std::string& key) {
        const MeshId mesh = scene.addMesh(primitives::box({size, size, size}), key);
        scene.addInstance({mesh, {scene.addMaterial(Material{})}, {1}});
        return mesh;
    };
    const MeshId firstBox = addBox(first, 1.0f, "test:shared box");
    addBox(second, 1.0f, "test:shared box");
    addBox(own, 1.0f, "");
    const Camera camera = cameraLookingAt({-4, 0, 0}, {0, 0, 0}, 16, 16);
    RenderTarget target(renderer(), {Modality::Depth}, 0);
    Frame frame;
    auto centreDepth = [&](const Scene& scene) {
        target.render(scene, camera, frame);
        return frame.get(Modality::Depth).at(8, 8);
    };
    EXPECT_NEAR(centreDepth(first), 3.5f, 1e-4f);
    EXPECT_NEAR(centreDepth(second), 3.5f, 1e-4f);
    EXPECT_NEAR(centreDepth(own), 3.5f, 1e-4f);
    EXPECT_EQ(renderer().stats(first.uid()).meshUploads, 1u);
    EXPECT_EQ(renderer().stats(second.uid()).meshUploads, 0u) << "drawn with the first scene's upload";
    EXPECT_EQ(renderer().stats(own.uid()).meshUploads, 1u) << "no key: its own copy";

    // A scene that changes the mesh gets a copy of its own; the other keeps drawing the shared one.
    first.updateMesh(firstBox, primitives::box({2.0f, 2.0f, 2.0f}));
    EXPECT_NEAR(centreDepth(first), 3.0f, 1e-4f);
    EXPECT_NEAR(centreDepth(second), 3.5f, 1e-4f);
    EXPECT_EQ(renderer().stats(first.uid()).meshUploads, 2u);

    // Released with the last scene holding it, the upload is made again by the next scene to need it.
    renderer().releaseScene(second);
    Scene third;
    addBox(third, 1.0f, "test:shared box");
    EXPECT_NEAR(centreDepth(third), 3.5f, 1e-4f);
    EXPECT_EQ(renderer().stats(third.uid()).meshUploads, 1u);
    renderer().releaseScene(first);
    renderer().releaseScene(own);
    renderer().releaseScene(third);
}

TEST_F(RenderPathsGlTest, CulledInstancesDoNotChangeTheImage) {
    Scene scene;
    buildShapesScene(scene);
    Camera camera = cameraLookingAt({3.2, -2.4, 2.2}, {0, 0, 0.3}, 64, 48, 60.0);
    camera.params.shadows = false; // a box behind the camera would otherwise shadow the scene
    RenderTarget target(renderer(), {Modality::FinalColor, Modality::ObjectIds}, 0);
    Frame before, after;
    target.render(scene, camera, before);
    const MaterialId grey = scene.addMaterial(makeMaterial({0.5f, 0.5f, 0.5f}, 0.5f, 0.0f));
    Instance behind{scene.addMesh(primitives::box()), {grey}, {4242}};
    behind.transform.translation() = Eigen::Vector3d(8.0, -6.0, 5.0); // behind the camera
    scene.addInstance(behind);
    renderer().resetStats();
    target.render(scene, camera, after);
    EXPECT_EQ(renderer().stats().culledInstances, 1u);
    EXPECT_EQ(difference(before.get(Modality::FinalColor), after.get(Modality::FinalColor)).first, 0);
    const auto ids = after.get(Modality::ObjectIds).as<std::uint32_t>();
    EXPECT_EQ(std::count(ids.begin(), ids.end(), 4242u), 0);
}

TEST_F(RenderPathsGlTest, InstancesSharingAMeshAreDrawnInOneCallWithTheirOwnMaterialsAndIds) {
    // Five boxes of one mesh (one of them mirrored), each with its own material and object id, a sixth
    // with a textured material, on a ground: the untextured boxes are one instanced draw, the textured one
    // and the ground one each, and every box's pixels carry its own id, material and a normal facing
    // the camera.
    Scene scene;
    const MeshId plane = scene.addMesh(primitives::plane(12, 12));
    const MeshId box = scene.addMesh(primitives::box({0.5f, 0.5f, 0.5f}));
    scene.addInstance({plane, {scene.addMaterial(makeMaterial({0.5f, 0.5f, 0.5f}, 0.9f, 0.0f))}, {1}});
    std::vector<Eigen::Vector3d> centres;
    std::vector<Eigen::Vector3f> colours;
    for (int i = 0; i < 6; ++i) {
        const Eigen::Vector3f colour(0.1f + 0.15f * float(i), 0.8f - 0.1f * float(i), 0.3f);
        Material material = makeMaterial(colour, 0.4f, i == 3 ? 1.0f : 0.0f);
        if (i == 5) {
            std::vector<std::uint8_t> white(4 * 4 * 4, 255);
            material.baseColorTexture = scene.addTexture(TextureImage::fromPixels(4, 4, white));
        }
        Instance instance{box, {scene.addMaterial(material)}, {std::uint32_t(100 + i)}};
        centres.emplace_back(-1.5 + 0.75 * i, 0.4 * (i % 2), 0.25);
        instance.transform =
            Eigen::Translation3d(centres.back()) * Eigen::AngleAxisd(0.3 * i, Eigen::Vector3d::UnitZ());
        if (i == 2)
            instance.transform = instance.transform * Eigen::Scaling(-1.0, 1.0, 1.0); // mirrored
        scene.addInstance(instance);
        colours.push_back(colour);
    }
    scene.addLight({});
    Camera camera = cameraLookingAt({0.0, -5.0, 2.5}, {0, 0, 0.25}, 96, 64, 60.0);
    renderer().resetStats();
    RenderTarget target(renderer(), {Modality::ObjectIds, Modality::BaseColor, Modality::Normal}, 0);
    Frame frame;
    target.render(scene, camera, frame);
    EXPECT_EQ(renderer().stats().drawCalls, 3u) << "untextured boxes, the textured box, the ground";
    EXPECT_EQ(renderer().stats().drawnInstances, 7u);

    const auto ids = frame.get(Modality::ObjectIds).as<std::uint32_t>();
    const auto base = frame.get(Modality::BaseColor).as<std::uint16_t>(); // float16 (H,W,3)
    const auto normals = frame.get(Modality::Normal).as<float>();
    for (std::size_t i = 0; i < centres.size(); ++i) {
        // The top face's centre: every box shows it to this camera.
        const Eigen::Vector3d pixel = camera.project(centres[i] + Eigen::Vector3d(0, 0, 0.25));
        const std::size_t at = std::size_t(pixel.y()) * 96 + std::size_t(pixel.x());
        EXPECT_EQ(ids[at], 100 + i) << "box " << i;
        for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(halfToFloat(base[3 * at + std::size_t(c)]), colours[i][c], 2e-3) << "box " << i;
        const Eigen::Vector3f normal(normals[3 * at], normals[3 * at + 1], normals[3 * at + 2]);
        EXPECT_NEAR(normal.z(), 1.0f, 1e-3) << "box " << i << ": the top face's normal, mirrored or not";
    }
}

TEST_F(RenderPathsGlTest, LatencyZeroReadsAFrameOnceAndLatencyOneMatchesIt) {
    Scene scene;
    buildShapesScene(scene);
    Camera camera = cameraLookingAt({3.2, -2.4, 2.2}, {0, 0, 0.3}, 40, 30, 60.0);
    RenderTarget direct(renderer(), {Modality::FinalColor, Modality::Depth}, 0);
    RenderTarget ring(renderer(), {Modality::FinalColor, Modality::Depth}, 1);
    Frame a, b;
    direct.submit(scene, camera);
    ASSERT_TRUE(direct.read(a).has_value());
    EXPECT_FALSE(direct.read(a).has_value()); // a frame is returned once
    ring.submit(scene, camera);
    EXPECT_FALSE(ring.read(b).has_value()); // priming
    ring.submit(scene, camera);
    ASSERT_TRUE(ring.read(b).has_value());
    EXPECT_EQ(difference(a.get(Modality::FinalColor), b.get(Modality::FinalColor)).first, 0);
    const auto da = a.get(Modality::Depth).as<float>(), db = b.get(Modality::Depth).as<float>();
    EXPECT_TRUE(std::equal(da.begin(), da.end(), db.begin()));
}

// Compact targets (float16 targets holding their bits in 16-bit integers, the normal as octahedral
// coordinates) read the same images as float targets: every modality, at latency 0 and 1, in a layer of a
// shared page and in framebuffers of its own, with position and the intrinsics computed on the CPU and all
// rendered (with the attribute pass). The float16 images differ by the rounding: packHalf2x16 rounds to
// nearest, as the CPU does (floatToHalf()), where llvmpipe's float16 framebuffers truncate, so a value is
// the same or one unit in the last place larger; the normal is within a few float32 ulps; the rest is the
// same bit for bit.
TEST_F(RenderPathsGlTest, CompactTargetsReadTheSameImagesAsFloatTargets) {
    Scene scene;
    buildShapesScene(scene);
    addSpotAndPointLights(scene);
    const bool compactByDefault = renderer().compactTargets(), derivesByDefault = renderer().derivesOnCpu();
    for (const bool derives : {true, false})
        for (const int latency : {0, 1})
            for (const int width : {96, 640}) { // a layer of a page; framebuffers of its own
                const Camera camera =
                    cameraLookingAt({3.2, -2.4, 2.2}, {0, 0, 0.3}, width, width * 2 / 3, 60.0);
                std::array<Frame, 2> frames;
                for (const bool compact : {false, true}) {
                    renderer().setCompactTargets(compact);
                    renderer().setDerivesOnCpu(derives);
                    RenderTarget target(renderer(), ModalitySet::all(), latency);
                    for (int i = 0; i <= latency; ++i)
                        target.submit(scene, camera);
                    ASSERT_TRUE(target.read(frames[compact ? 1 : 0]).has_value());
                }
                const std::string where = std::string(derives ? "computed" : "rendered") + ", latency " +
                                          std::to_string(latency) + ", " + std::to_string(width) + " wide: ";
                const Frame& compact = frames[1];
                for (Modality m : ModalitySet::all().list()) {
                    const ImageBuffer &a = frames[0].get(m), &b = compact.get(m);
                    ASSERT_EQ(a.bytes.size(), b.bytes.size());
                    if (m == Modality::Normal) {
                        const auto x = a.as<float>(), y = b.as<float>();
                        float largest = 0.0f;
                        std::size_t zeros = 0;
                        for (std::size_t i = 0; i < x.size(); ++i) {
                            largest = std::max(largest, std::abs(x[i] - y[i]));
                            zeros += y[i] == 0.0f && x[i] == 0.0f;
                        }
                        EXPECT_LE(largest, 5e-7f) << where << "normal";
                        EXPECT_GT(zeros, x.size() / 10) << where << "the background's normal is zero in both";
                    } else if (modalityInfo(m).dtype != DType::Float16) {
                        EXPECT_TRUE(std::equal(a.bytes.begin(), a.bytes.end(), b.bytes.begin()))
                            << where << modalityName(m);
                    } else if (!(derives &&
                                 (m == Modality::DiffuseOnly || m == Modality::SpecularResidual))) {
                        // (Computed ones follow their inputs' rounding: derived_images_test.cpp.)
                        const auto x = a.as<std::uint16_t>(), y = b.as<std::uint16_t>();
                        for (std::size_t i = 0; i < x.size(); ++i) {
                            const int up = int(y[i] & 0x7fff) - int(x[i] & 0x7fff); // in magnitude
                            ASSERT_TRUE((x[i] & 0x8000) == (y[i] & 0x8000) && (up == 0 || up == 1))
                                << where << modalityName(m) << " value " << i << ": " << x[i] << " and "
                                << y[i];
                        }
                    }
                }
                // The ground's base colour (0.6, 0.6, 0.55) is the material's, rounded to nearest.
                const auto ids = compact.get(Modality::ObjectIds).as<std::uint32_t>();
                const auto base = compact.get(Modality::BaseColor).as<std::uint16_t>();
                const std::size_t ground = std::size_t(std::find(ids.begin(), ids.end(), 1u) - ids.begin());
                ASSERT_LT(ground, ids.size()) << where << "the ground is in view";
                EXPECT_EQ(base[3 * ground], floatToHalf(0.6f)) << where;
                EXPECT_EQ(base[3 * ground + 2], floatToHalf(0.55f)) << where;
            }
    renderer().setCompactTargets(compactByDefault);
    renderer().setDerivesOnCpu(derivesByDefault);
}

TEST_F(RenderPathsGlTest, ABatchOfScenesRendersWhatEachRendersAlone) {
    // Worlds drawn as one batch (RenderTarget::submitAll) share framebuffers, one tile each, and keep their
    // shadow maps in layers of shared arrays:
    // a sun's (16-bit) and a spot light's (32-bit float, another array), a world with two suns (two layers),
    // a box moving in each every frame (the maps redrawn in parts), and a world joining at the third frame
    // (the array grows, keeping the others' maps). Every frame of every world equals what a renderer of its
    // own draws for that world alone, bit for bit, with the maps in one layered framebuffer or attached
    // layer by layer; and each target reads back the frame number it was given.
    std::vector<std::unique_ptr<Scene>> scenes;
    std::vector<InstanceId> movers;
    for (int i = 0; i < 3; ++i) {
        auto scene = std::make_unique<Scene>();
        buildShapesScene(*scene);
        if (i == 1)
            addSpotAndPointLights(*scene);
        if (i == 2) {
            Light second;
            second.direction = Eigen::Vector3d(0.3, 0.6, -1.0);
            scene->addLight(second);
        }
        const MeshId box = scene->addMesh(primitives::box({0.3f, 0.3f, 0.3f}));
        const MaterialId red = scene->addMaterial(makeMaterial({0.7f, 0.12f, 0.1f}, 0.5f, 0.0f));
        Instance mover{box, {red}, {40}};
        mover.transform.translation() = Eigen::Vector3d(0.6 - 0.5 * i, -0.4 + 0.3 * i, 0.9); // its own shadow
        movers.push_back(scene->addInstance(mover));
        scenes.push_back(std::move(scene));
    }
    const Camera camera = cameraLookingAt({3.2, -2.4, 2.2}, {0, 0, 0.3}, 64, 48, 60.0);
    const bool byDefault = renderer().layeredShadowMaps();
    for (const bool layered : {true, false}) {
        // Batched, the small views are tiles of one framebuffer (cleared by drawing, a surface and an
        // attribute pass); alone, each fills framebuffers of its own (cleared by glClear).
        const ModalitySet modalities =
            layered ? ModalitySet::all() : ModalitySet{Modality::FinalColor, Modality::Depth};
        renderer().setLayeredShadowMaps(layered);
        std::vector<std::unique_ptr<Renderer>> alone; // a renderer per world: its maps alone in its arrays
        std::vector<std::unique_ptr<RenderTarget>> batched, single;
        for (std::size_t i = 0; i < scenes.size(); ++i) {
            alone.push_back(std::make_unique<Renderer>(*context_));
            batched.push_back(std::make_unique<RenderTarget>(renderer(), modalities, 0));
            single.push_back(std::make_unique<RenderTarget>(*alone.back(), modalities, 0));
        }
        for (int frame = 0; frame < 4; ++frame) {
            const std::size_t worlds = frame < 2 ? 2 : 3;
            std::vector<RenderTarget::Submission> batch;
            for (std::size_t i = 0; i < worlds; ++i) {
                Eigen::Affine3d transform = scenes[i]->instance(movers[i]).transform;
                transform.translation() += Eigen::Vector3d(0.15, 0.1, 0.0);
                scenes[i]->setTransform(movers[i], transform);
                batch.push_back({batched[i].get(), scenes[i].get(), &camera});
            }
            const std::vector<std::uint64_t> numbers = RenderTarget::submitAll(batch);
            for (std::size_t i = 0; i < worlds; ++i) {
                Frame together, apart;
                ASSERT_EQ(batched[i]->read(together), numbers[i]);
                ASSERT_TRUE(single[i]->render(*scenes[i], camera, apart).has_value());
                for (Modality m : modalities.list()) {
                    const ImageBuffer &x = together.get(m), &y = apart.get(m);
                    EXPECT_TRUE(std::equal(x.bytes.begin(), x.bytes.end(), y.bytes.begin()))
                        << modalityName(m) << ", world " << i << ", frame " << frame << ", layered "
                        << layered;
                }
            }
        }
        single.clear();
        alone.clear();
        context_->makeCurrent();
    }
    renderer().setLayeredShadowMaps(byDefault);
}

TEST_F(RenderPathsGlTest, ViewsOfOneSceneAskingForOtherShadowResolutionsSplitTheBatch) {
    // A scene's maps exist at one resolution at a time: a second view asking for another one starts a new
    // part of the batch, after the first view was drawn with its own maps. Each view equals its render alone.
    Scene scene;
    buildShapesScene(scene);
    Camera fine = cameraLookingAt({3.2, -2.4, 2.2}, {0, 0, 0.3}, 48, 36, 60.0);
    fine.params.shadowResolution = 1024;
    Camera coarse = cameraLookingAt({-2.5, 3.0, 1.8}, {0, 0, 0.3}, 48, 36, 70.0);
    coarse.params.shadowResolution = 128;
    const ModalitySet modalities{Modality::FinalColor};
    Frame expectedFine, expectedCoarse;
    {
        Renderer alone(*context_);
        RenderTarget target(alone, modalities, 0);
        ASSERT_TRUE(target.render(scene, fine, expectedFine).has_value());
        Renderer other(*context_);
        RenderTarget second(other, modalities, 0);
        ASSERT_TRUE(second.render(scene, coarse, expectedCoarse).has_value());
    }
    context_->makeCurrent();
    renderer().resetStats();
    RenderTarget a(renderer(), modalities, 0), b(renderer(), modalities, 0);
    const RenderTarget::Submission batch[] = {{&a, &scene, &fine}, {&b, &scene, &coarse}};
    RenderTarget::submitAll(batch);
    EXPECT_EQ(renderer().stats(scene.uid()).shadowPasses, 2u) << "drawn at 1024 texels, then at 128";
    Frame gotFine, gotCoarse;
    ASSERT_TRUE(a.read(gotFine).has_value());
    ASSERT_TRUE(b.read(gotCoarse).has_value());
    EXPECT_EQ(difference(gotFine.get(Modality::FinalColor), expectedFine.get(Modality::FinalColor)).first, 0);
    EXPECT_EQ(difference(gotCoarse.get(Modality::FinalColor), expectedCoarse.get(Modality::FinalColor)).first,
              0);
    EXPECT_GT(difference(gotFine.get(Modality::FinalColor), gotCoarse.get(Modality::FinalColor)).first, 0);
}

TEST_F(RenderPathsGlTest, AFrameWaitingInALayerSurvivesItsFramebuffersGrowing) {
    // A latency-0 frame not read yet stays in its tile while other targets of its size take tiles of the same
    // framebuffers, which grow (moving the tiles) to hold them all.
    Scene scene;
    buildShapesScene(scene);
    const Camera camera = cameraLookingAt({3.2, -2.4, 2.2}, {0, 0, 0.3}, 40, 30, 60.0);
    const Camera other = cameraLookingAt({-2.0, 3.0, 1.5}, {0, 0, 0.3}, 40, 30, 70.0);
    const ModalitySet modalities{Modality::FinalColor, Modality::ObjectIds};
    Frame expected;
    {
        Renderer alone(*context_);
        RenderTarget target(alone, modalities, 0);
        ASSERT_TRUE(target.render(scene, camera, expected).has_value());
    }
    context_->makeCurrent();
    const std::size_t pages = renderer().atlas().pages();
    RenderTarget waiting(renderer(), modalities, 0);
    waiting.submit(scene, camera);
    std::vector<std::unique_ptr<RenderTarget>> others;
    std::vector<RenderTarget::Submission> batch;
    for (int i = 0; i < 6; ++i) {
        others.push_back(std::make_unique<RenderTarget>(renderer(), modalities, 0));
        batch.push_back({others.back().get(), &scene, &other});
    }
    RenderTarget::submitAll(batch);
    EXPECT_EQ(renderer().atlas().pages(), pages + 1) << "the seven 40x30 views share one page";
    Frame frame;
    ASSERT_TRUE(waiting.read(frame).has_value());
    for (Modality m : modalities.list()) {
        const ImageBuffer &x = frame.get(m), &y = expected.get(m);
        EXPECT_TRUE(std::equal(x.bytes.begin(), x.bytes.end(), y.bytes.begin())) << modalityName(m);
    }
    Frame another;
    ASSERT_TRUE(others[3]->read(another).has_value());
    EXPECT_GT(difference(another.get(Modality::FinalColor), frame.get(Modality::FinalColor)).first, 0)
        << "the other views show another picture";
}

} // namespace
} // namespace sp::render::test
