// The path tracer against closed forms and the rasteriser: a furnace (a convex diffuse object in a uniform
// sky reflects base x sky), direct light of a Lambertian plane equal to the rasteriser's, error falling
// as 1 / sqrt(samples), and accumulation that restarts exactly when something changes.

#include <gtest/gtest.h>

#include <cmath>
#include <utility>

#include "core/base/error.h"
#include "core/pathtrace/path_tracer.h"
#include "core/render/render_target.h"
#include "core/render/texture_image.h"
#include "gl_fixture.h"
#include "test_scenes.h"

namespace sp::pathtrace {
namespace {

using render::Camera;
using render::Light;
using render::LightType;
using render::Material;
using render::Scene;

class PathTracerGlTest : public render::test::GlTest {
  protected:
    static Material material(Eigen::Vector3f base, float roughness, float metallic) {
        return render::test::makeMaterial(base, roughness, metallic);
    }
    // A sphere of radius 0.5 at the origin, seen from 3 m along +X with a narrow view that it fills.
    static render::MaterialId addSphere(Scene& scene, const Material& m) {
        const render::MaterialId id = scene.addMaterial(m);
        scene.addInstance({scene.addMesh(render::primitives::sphere(0.5f, 64, 32)), {id}, {1}});
        return id;
    }
    static Camera sphereCamera() { return lookingAlong({-3.0, 0.0, 0.0}, {1.0, 0.0, 0.0}, 16, 16, 8.0); }
    // A 40 m plane of material `id` under a shadowless sun travelling along `sunDirection`, no sky; the view
    // of it (24x16, no shadows).
    static Camera planeUnderSun(Scene& scene, render::MaterialId id, const Eigen::Vector3d& sunDirection) {
        scene.addInstance({scene.addMesh(render::primitives::plane(40.0f, 40.0f)), {id}, {1}});
        Light sun;
        sun.direction = sunDirection.normalized();
        sun.intensity = 3.0f;
        sun.castShadows = false;
        scene.addLight(sun);
        scene.setEnvironment({{0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, 0.0f}});
        Camera camera = lookingAlong({-2.0, 0.0, 1.5}, {1.0, 0.0, -0.6}, 24, 16, 50.0);
        camera.params.shadows = false;
        return camera;
    }
    // The mean over the image of channel 0.
    static double mean(const Accumulation& image) {
        double sum = 0.0;
        for (int y = 0; y < image.height; ++y)
            for (int x = 0; x < image.width; ++x)
                sum += image.mean(x, y, 0);
        return sum / (image.width * image.height);
    }
    static double rmsDifference(const Accumulation& a, const Accumulation& b) {
        double sum = 0.0;
        for (int y = 0; y < a.height; ++y)
            for (int x = 0; x < a.width; ++x)
                for (int c = 0; c < 3; ++c)
                    sum += std::pow(double(a.mean(x, y, c)) - b.mean(x, y, c), 2);
        return std::sqrt(sum / (a.width * a.height * 3));
    }
    // A white floor lit by a small, very bright emissive ball and by its reflection in a polished metal ball:
    // the emitter samples find the lamp itself (smooth light), but the caustic, the lamp's light off the
    // metal, only bounce rays find, so at 16 samples a few pixels catch it (fireflies). Returns the view and
    // the same view with other random numbers.
    static std::pair<Camera, Camera> causticScene(Scene& scene) {
        const render::MaterialId floor =
            scene.addMaterial(render::test::makeMaterial({1.0f, 1.0f, 1.0f}, 1.0f, 0.0f));
        scene.addInstance({scene.addMesh(render::primitives::plane(10.0f, 10.0f)), {floor}, {1}});
        Material glow = render::test::makeMaterial({0.0f, 0.0f, 0.0f}, 1.0f, 0.0f);
        glow.emissive = Eigen::Vector3f::Constant(500.0f);
        render::Instance ball{
            scene.addMesh(render::primitives::sphere(0.1f, 16, 8)), {scene.addMaterial(glow)}, {2}};
        ball.transform.translation() = Eigen::Vector3d(0.0, 0.0, 1.0);
        scene.addInstance(ball);
        render::Instance mirror{
            scene.addMesh(render::primitives::sphere(0.3f, 32, 16)),
            {scene.addMaterial(render::test::makeMaterial({1.0f, 1.0f, 1.0f}, 0.05f, 1.0f))},
            {3}};
        mirror.transform.translation() = Eigen::Vector3d(0.6, 0.3, 0.3);
        scene.addInstance(mirror);
        scene.setEnvironment({{0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, 0.0f}});
        const Camera camera = lookingAlong({0.0, -1.5, 0.8}, {0.0, 1.5, -0.8}, 16, 16, 60.0);
        Camera other = camera; // the same view with other random numbers
        other.params.farClip = 999.0;
        return {camera, other};
    }
    // How far apart independent images of `scene` are: the root mean square of the difference of the same
    // view, `camera` and `other`, traced with different random numbers, over 32 such pairs. The caustic's
    // rare paths make one pair's difference heavy-tailed (a few pixels catching it or not); the mean over
    // pairs is what a setting changes.
    double spread(const Scene& scene, const Camera& camera, const Camera& other, const Settings& settings) {
        double squares = 0.0;
        constexpr int kPairs = 32;
        for (int pair = 0; pair < kPairs; ++pair) {
            Camera first = camera, second = other; // other random numbers, the same image
            first.params.farClip += 10.0 * pair;
            second.params.farClip += 10.0 * pair;
            Accumulation a, b;
            tracer_.render(scene, first, settings, a);
            tracer_.render(scene, second, settings, b);
            squares += std::pow(rmsDifference(a, b), 2);
        }
        return std::sqrt(squares / kPairs);
    }
    PathTracer tracer_;
};

TEST_F(PathTracerGlTest, OneTracerRendersTwoScenesAsTwoTracersWould) {
    // The meshes are kept per scene: the same handles in another scene are other meshes.
    Scene sphere, box;
    addSphere(sphere, material({0.8f, 0.8f, 0.8f}, 0.6f, 0.0f));
    const render::MaterialId grey = box.addMaterial(material({0.8f, 0.8f, 0.8f}, 0.6f, 0.0f));
    box.addInstance({box.addMesh(render::primitives::box({0.3f, 0.3f, 0.3f})), {grey}, {1}});
    for (Scene* scene : {&sphere, &box})
        scene->setEnvironment({{1.0f, 1.0f, 1.0f}, {0.0f, 0.0f, 0.0f}});
    Accumulation first, second, alone;
    tracer_.render(sphere, sphereCamera(), {4, 1}, first);
    tracer_.render(box, sphereCamera(), {4, 1}, second);
    PathTracer fresh;
    fresh.render(box, sphereCamera(), {4, 1}, alone);
    EXPECT_EQ(second.sum, alone.sum);
}

TEST_F(PathTracerGlTest, AConvexDiffuseObjectInAUniformSkyReflectsBaseTimesSky) {
    // Furnace: every pixel of the sphere sees base x sky from its diffuse lobe, plus the specular lobe's
    // share, which is the same for any dielectric base (F0 = 0.04): the difference of two bases is exact.
    Accumulation white, grey;
    for (auto [base, image] : {std::pair{1.0f, &white}, std::pair{0.5f, &grey}}) {
        Scene scene;
        addSphere(scene, material({base, base, base}, 0.6f, 0.0f));
        scene.setEnvironment({{1.0f, 1.0f, 1.0f}, {1.0f, 1.0f, 1.0f}});
        tracer_.render(scene, sphereCamera(), {256, 3}, *image);
    }
    for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 16; ++x)
            EXPECT_NEAR(white.mean(x, y, 0) - grey.mean(x, y, 0), 0.5, 0.05) << x << ", " << y;
    EXPECT_NEAR(mean(white) - mean(grey), 0.5, 0.01);

    // A smooth white metal in a white sky reflects the sky: radiance 1 (the GGX lobe's white furnace).
    Scene scene;
    addSphere(scene, material({1.0f, 1.0f, 1.0f}, 0.05f, 1.0f));
    scene.setEnvironment({{1.0f, 1.0f, 1.0f}, {1.0f, 1.0f, 1.0f}});
    Accumulation metal;
    tracer_.render(scene, sphereCamera(), {256, 3}, metal);
    EXPECT_NEAR(mean(metal), 1.0, 0.03);
}

TEST_F(PathTracerGlTest, IntrinsicPartsHaveTheirClosedForms) {
    // In a white sky of radiance 1, a white Lambertian surface anywhere on a convex object reflects 1:
    // diffuse_illumination is 1 on a dielectric and on a metal alike (estimated from the same paths), and
    // diffuse_only is base x (1 - metallic) x that.
    for (float metallic : {0.0f, 1.0f}) {
        Scene scene;
        addSphere(scene, material({0.6f, 0.4f, 0.2f}, 0.5f, metallic));
        scene.setEnvironment({{1.0f, 1.0f, 1.0f}, {1.0f, 1.0f, 1.0f}});
        Accumulation image;
        tracer_.render(scene, sphereCamera(), {256, 3}, image);
        double illumination = 0.0, diffuseOnly[3] = {0.0, 0.0, 0.0};
        for (int y = 0; y < 16; ++y)
            for (int x = 0; x < 16; ++x) {
                for (int c = 0; c < 3; ++c) {
                    illumination += image.mean(image.diffuseIlluminationSum, x, y, c) / (16 * 16 * 3);
                    diffuseOnly[c] += image.mean(image.diffuseOnlySum, x, y, c) / (16 * 16);
                }
            }
        EXPECT_NEAR(illumination, 1.0, 0.03) << metallic;
        const float base[3] = {0.6f, 0.4f, 0.2f};
        for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(diffuseOnly[c], base[c] * (1.0f - metallic), 0.02) << metallic << " " << c;
    }
}

TEST_F(PathTracerGlTest, DirectLightOfALambertianPlaneMatchesTheRasteriser) {
    // A rough plane under a shadowless sun, no sky: both renderers evaluate the same surface model with
    // the same light, so their hdr_color agree (the path tracer's is a mean over jittered pixel areas).
    Scene scene;
    const render::MaterialId id = scene.addMaterial(material({0.5f, 0.4f, 0.3f}, 0.9f, 0.0f));
    const Camera camera = planeUnderSun(scene, id, {0.3, 0.2, -1.0});

    const render::Frame frame = renderFrame(
        scene, camera,
        {render::Modality::HdrColor, render::Modality::DiffuseIllumination, render::Modality::DiffuseOnly});
    Accumulation traced;
    tracer_.render(scene, camera, {64, 0}, traced);
    const render::ImageBuffer& raster = frame.get(render::Modality::HdrColor);
    const render::ImageBuffer& illumination = frame.get(render::Modality::DiffuseIllumination);
    const render::ImageBuffer& diffuseOnly = frame.get(render::Modality::DiffuseOnly);
    for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 24; ++x)
            for (int c = 0; c < 3; ++c) {
                EXPECT_NEAR(traced.mean(x, y, c), raster.at(x, y, c), 0.02 * raster.at(x, y, c) + 2e-3)
                    << x << ", " << y << ", " << c;
                // The intrinsic parts too: direct light only, so both renderers have the same closed form.
                EXPECT_NEAR(traced.mean(traced.diffuseIlluminationSum, x, y, c), illumination.at(x, y, c),
                            0.02 * illumination.at(x, y, c) + 2e-3);
                EXPECT_NEAR(traced.mean(traced.diffuseOnlySum, x, y, c), diffuseOnly.at(x, y, c),
                            0.02 * diffuseOnly.at(x, y, c) + 2e-3);
            }
}

TEST_F(PathTracerGlTest, MaxPathIntensityTradesFirefliesForBias) {
    // Independent images of the caustic (exact: approximateCaustics off) differ a lot at 16 samples.
    // Clamping what a path brings back makes them agree far better, at the cost of light taken away; 0
    // clamps nothing (the same sums as the default settings).
    Scene scene;
    const auto [camera, other] = causticScene(scene);
    auto spread = [&](const Settings& settings) { return this->spread(scene, camera, other, settings); };
    const double clamped16 = spread({16, 2, 20.0f, false}), exact16 = spread({16, 2, 0.0f, false});
    EXPECT_LT(clamped16, 0.5 * exact16) << clamped16 << " against " << exact16;
    Accumulation clamped, unclamped, defaults;
    tracer_.render(scene, other, {1024, 2, 20.0f, false}, clamped);
    tracer_.render(scene, other, {1024, 2, 0.0f, false}, unclamped);
    EXPECT_LT(mean(clamped), mean(unclamped)); // light is only ever taken away
    PathTracer a, b;
    a.render(scene, camera, {16, 1, 0.0f}, clamped);
    b.render(scene, camera, Settings(16, 1), defaults);
    EXPECT_EQ(clamped.sum, defaults.sum);
    EXPECT_THROW(tracer_.render(scene, camera, {16, 1, -1.0f}, clamped), InvalidArgument);
}

TEST_F(PathTracerGlTest, ApproximateCausticsTurnTheCausticIntoAGlowThatKeepsItsLight) {
    // The same caustic with path regularisation: the metal, met after the floor's diffuse bounce, is shaded
    // as rough, so the emitter samples from it find the lamp instead of bounce rays finding it by chance.
    // What is left is the chance of the floor's bounce meeting the metal ball: independent 64-sample images
    // differ about a quarter less than exact ones (0.72x over 128 pairs with the stratified sampler, whose
    // bounce directions already meet the metal evenly; 0.64x at 16 samples with independent numbers), and
    // the converged image keeps most of the light (the caustic is spread, not removed: the metal reflects
    // what it did, over a wider lobe).
    Scene scene;
    const auto [camera, other] = causticScene(scene);
    auto spread = [&](const Settings& settings) { return this->spread(scene, camera, other, settings); };
    const double exact = spread({64, 2, 0.0f, false}), approximated = spread({64, 2, 0.0f, true});
    EXPECT_LT(approximated, 0.8 * exact) << approximated << " against " << exact;
    Accumulation converged, exactImage;
    tracer_.render(scene, other, {1024, 2, 0.0f, true}, converged);
    tracer_.render(scene, other, {1024, 2, 0.0f, false}, exactImage);
    EXPECT_NEAR(mean(converged), mean(exactImage), 0.15 * mean(exactImage));
    EXPECT_FALSE(Settings().approximateCaustics); // the unbiased estimate unless asked
}

TEST_F(PathTracerGlTest, PointLightShadowsInTheRasteriserFallWhereThePathTracersDo) {
    // A lamp (a point light) 1.5 m over a floor, a box on the floor beside it and a wall on the far side of
    // the box: the box shadows the floor and the wall, as in the path tracer, whose shadow rays are exact.
    // The rasteriser looks the shadows up in a cube of six maps around the lamp, some of whose faces' seams
    // cross the floor. Direct light only, no sky: a shadow is black.
    Scene scene;
    const render::MaterialId grey = scene.addMaterial(material({0.6f, 0.6f, 0.6f}, 0.9f, 0.0f));
    scene.addInstance({scene.addMesh(render::primitives::plane(6.0f, 6.0f)), {grey}, {1}});
    render::Instance box{
        scene.addMesh(render::primitives::box(Eigen::Vector3f::Constant(0.5f))), {grey}, {2}};
    box.transform.translation() = Eigen::Vector3d(0.8, 0.0, 0.25);
    scene.addInstance(box);
    render::Instance wall{
        scene.addMesh(render::primitives::box(Eigen::Vector3f(0.1f, 3.0f, 2.0f))), {grey}, {3}};
    wall.transform.translation() = Eigen::Vector3d(2.0, 0.0, 1.0);
    scene.addInstance(wall);
    Light lamp;
    lamp.type = LightType::Point;
    lamp.position = Eigen::Vector3d(-0.6, 0.0, 1.5);
    lamp.intensity = 4.0f;
    lamp.castShadows = true;
    const render::LightId lampId = scene.addLight(lamp);
    scene.setEnvironment({{0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, 0.0f}});
    Camera camera = lookingAlong({0.3, -3.0, 2.0}, {1.2, 3.0, -1.7}, 64, 48, 60.0);
    camera.params.shadowResolution = 1024;

    const render::Frame frame = renderFrame(scene, camera, {render::Modality::HdrColor});
    const render::ImageBuffer& raster = frame.get(render::Modality::HdrColor);
    Accumulation traced;
    tracer_.render(scene, camera, {64, 0}, traced);
    Light unshadowed = lamp;
    unshadowed.castShadows = false;
    scene.setLight(lampId, unshadowed);
    const render::Frame withoutShadows = renderFrame(scene, camera, {render::Modality::HdrColor});
    const render::ImageBuffer& lit = withoutShadows.get(render::Modality::HdrColor);

    // Where the path tracer's lamp casts a shadow (dark there, lit by the same lamp without shadows), the
    // rasteriser's is dark; where the path tracer's lamp lights, the rasteriser's shadows take nothing away
    // but along the shadows' edges (a map's texel against a pixel's jittered samples).
    int cast = 0, dark = 0, lighted = 0, kept = 0;
    for (int y = 0; y < 48; ++y)
        for (int x = 0; x < 64; ++x) {
            const float expected = traced.mean(x, y, 0);
            if (expected < 1e-4f && lit.at(x, y, 0) > 1e-2f) {
                ++cast;
                dark += raster.at(x, y, 0) < 1e-3f;
            } else if (expected > 1e-3f) {
                ++lighted;
                kept += std::abs(raster.at(x, y, 0) - lit.at(x, y, 0)) <= 0.02f * lit.at(x, y, 0);
            }
        }
    EXPECT_GT(cast, 64 * 48 / 25) << "the shadows are in view";
    EXPECT_GT(dark, cast * 9 / 10) << dark << " of " << cast;
    EXPECT_GT(kept, lighted * 97 / 100) << kept << " of " << lighted;
}

TEST_F(PathTracerGlTest, NormalMapsTurnTheShadingAsTheRasterisersDo) {
    // A rough plane whose normal map tilts every normal 30 degrees towards +u, under a shadowless sun: the
    // direct light depends on the mapped normal, and the path tracer's matches the rasteriser's per pixel
    // (and differs from the plane without the map).
    Scene scene;
    std::vector<std::uint8_t> texels;
    for (int i = 0; i < 16; ++i)
        texels.insert(texels.end(), {191, 128, 238, 255}); // (0.5, 0, 0.866) encoded
    Material mapped = material({0.6f, 0.6f, 0.6f}, 0.9f, 0.0f);
    mapped.normalTexture =
        scene.addTexture(render::TextureImage::fromPixels(4, 4, texels), render::TextureEncoding::Linear);
    const render::MaterialId id = scene.addMaterial(mapped);
    const Camera camera = planeUnderSun(scene, id, {0.6, 0.3, -1.0});

    const render::Frame frame = renderFrame(scene, camera, {render::Modality::HdrColor});
    Accumulation traced, flat;
    tracer_.render(scene, camera, {64, 0}, traced);
    Material plain = mapped;
    plain.normalTexture.reset();
    scene.setMaterial(id, plain);
    tracer_.render(scene, camera, {64, 0}, flat);
    const render::ImageBuffer& raster = frame.get(render::Modality::HdrColor);
    for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 24; ++x) {
            EXPECT_NEAR(traced.mean(x, y, 0), raster.at(x, y, 0), 0.02 * raster.at(x, y, 0) + 2e-3)
                << x << ", " << y;
            EXPECT_GT(std::abs(traced.mean(x, y, 0) - flat.mean(x, y, 0)), 0.05 * flat.mean(x, y, 0));
        }
}

TEST_F(PathTracerGlTest, ErrorFallsAsOneOverTheSquareRootOfSamples) {
    // Rough surfaces, so that the error is the estimator's spread rather than a few rare bright paths.
    Scene scene;
    addSphere(scene, material({0.8f, 0.5f, 0.3f}, 0.9f, 0.0f));
    const render::MaterialId floor = scene.addMaterial(material({0.6f, 0.6f, 0.6f}, 0.8f, 0.0f));
    render::Instance ground{scene.addMesh(render::primitives::plane(10.0f, 10.0f)), {floor}, {2}};
    ground.transform.translation() = Eigen::Vector3d(0.0, 0.0, -0.5);
    scene.addInstance(ground);
    Light sun;
    sun.direction = Eigen::Vector3d(1.0, 0.5, -1.0).normalized();
    scene.addLight(sun);
    scene.setEnvironment({{0.4f, 0.5f, 0.6f}, {0.0f, 0.0f, 0.0f}});
    Camera camera = lookingAlong({-3.0, -1.0, 1.0}, {3.0, 1.0, -1.0}, 16, 16, 40.0);
    Camera other = camera; // the same view with other random numbers: an independent reference
    other.params.farClip = 999.0;

    Accumulation reference, few, many;
    tracer_.render(scene, other, {4096, 4}, reference);
    tracer_.render(scene, camera, {16, 4}, few);
    tracer_.render(scene, camera, {128, 4}, many);
    tracer_.render(scene, camera, {128, 4}, many); // accumulates: 256 samples in all
    ASSERT_EQ(many.samples, 256u);
    const double ratio = rmsDifference(few, reference) / rmsDifference(many, reference);
    EXPECT_GT(ratio, 3.0); // sqrt(256 / 16) = 4, less the reference's own noise
    EXPECT_LT(ratio, 5.0);
}

TEST_F(PathTracerGlTest, AccumulationRestartsWhenTheSceneOrCameraChanges) {
    Scene scene;
    const render::MaterialId id = addSphere(scene, material({0.8f, 0.8f, 0.8f}, 0.5f, 0.0f));
    scene.addLight(Light{});
    const Camera camera = sphereCamera();
    Accumulation image;
    tracer_.render(scene, camera, {2, 1}, image);
    tracer_.render(scene, camera, {3, 1}, image);
    EXPECT_EQ(image.samples, 5u); // a still view accumulates
    // Lights added again in another order (as a world does every frame) are the same lights.
    Light lamp;
    lamp.type = LightType::Point;
    lamp.position = {-2.0, 1.0, 1.0};
    const render::LightId lampId = scene.addLight(lamp);
    tracer_.render(scene, camera, {1, 1}, image);
    EXPECT_EQ(image.samples, 1u); // a new light: another image
    std::vector<Light> lights;
    std::vector<render::LightId> ids;
    scene.forEachLight([&](render::LightId id, const Light& light) {
        ids.push_back(id);
        lights.push_back(light);
    });
    for (render::LightId id : ids)
        scene.removeLight(id);
    for (auto it = lights.rbegin(); it != lights.rend(); ++it)
        scene.addLight(*it);
    tracer_.render(scene, camera, {1, 1}, image);
    EXPECT_EQ(image.samples, 2u);
    (void)lampId;
    const std::uint64_t builds = tracer_.builds();

    Material red = scene.material(id);
    red.baseColor << 0.8f, 0.1f, 0.1f, 1.0f;
    scene.setMaterial(id, red);
    tracer_.render(scene, camera, {2, 1}, image);
    EXPECT_EQ(image.samples, 2u);        // restarted
    EXPECT_EQ(tracer_.builds(), builds); // without rebuilding the geometry
    EXPECT_LT(image.mean(8, 8, 1), image.mean(8, 8, 0));

    Camera moved = camera;
    moved.pose.translation().y() += 0.01;
    tracer_.render(scene, moved, {2, 1}, image);
    EXPECT_EQ(image.samples, 2u);
    tracer_.render(scene, moved, {2, 2}, image); // more bounces: another image
    EXPECT_EQ(image.samples, 2u);

    scene.forEachInstance([&](render::InstanceId instance, const render::Instance&) {
        scene.setTransform(instance, Eigen::Affine3d(Eigen::Translation3d(0.0, 0.0, 0.1)));
    });
    tracer_.render(scene, moved, {2, 2}, image);
    EXPECT_EQ(image.samples, 2u);
    EXPECT_EQ(tracer_.builds(), builds + 1);
}

TEST_F(PathTracerGlTest, InstancesThatCastNoShadowsAreSeenButDoNotShadow) {
    // A box over a plane, under a sun straight above: the plane below it is dark, unless the box does not
    // cast shadows (it stays in the scene for every other ray).
    for (bool casts : {true, false}) {
        Scene scene;
        const render::MaterialId grey = scene.addMaterial(material({0.5f, 0.5f, 0.5f}, 1.0f, 0.0f));
        scene.addInstance({scene.addMesh(render::primitives::plane(20.0f, 20.0f)), {grey}, {1}});
        render::Instance box{scene.addMesh(render::primitives::box({1.0f, 1.0f, 0.2f})), {grey}, {2}};
        box.transform.translation() = Eigen::Vector3d(0.0, 0.0, 1.0);
        box.castShadows = casts;
        scene.addInstance(box);
        Light sun;
        sun.direction = {0.0, 0.0, -1.0};
        scene.addLight(sun);
        scene.setEnvironment({{0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, 0.0f}});
        // From the side, low: the middle of the view is the plane under the box (x = -0.1).
        Accumulation image;
        Camera camera = lookingAlong({-3.0, 0.0, 0.3}, {1.0, 0.0, -0.1}, 16, 16, 10.0);
        tracer_.render(scene, camera, {4, 0}, image);
        if (casts)
            EXPECT_LT(image.mean(8, 8, 0), 0.01);
        else
            EXPECT_NEAR(image.mean(8, 8, 0), 0.5, 0.05); // base / pi x the sun's pi
        // A camera without shadows (bShadows false) traces no shadow rays to lights, as the rasteriser
        // then draws no shadow maps.
        camera.params.shadows = false;
        tracer_.render(scene, camera, {4, 0}, image);
        EXPECT_EQ(image.samples, 4u);
        EXPECT_NEAR(image.mean(8, 8, 0), 0.5, 0.05);
    }
}

TEST_F(PathTracerGlTest, BadSettingsAreRefusedNamingTheField) {
    Scene scene;
    Accumulation image;
    EXPECT_THROW(
        {
            try {
                tracer_.render(scene, sphereCamera(), {0, 1}, image);
            } catch (const sp::InvalidArgument& error) {
                EXPECT_NE(std::string(error.what()).find("samplesPerPixel 0"), std::string::npos)
                    << error.what();
                throw;
            }
        },
        sp::InvalidArgument);
    EXPECT_THROW(tracer_.render(scene, sphereCamera(), {1, 65}, image), sp::InvalidArgument);
}

} // namespace
} // namespace sp::pathtrace
