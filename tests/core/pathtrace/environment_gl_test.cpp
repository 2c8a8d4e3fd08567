// Sky and environment light in both renderers: a white diffuse object in a uniform environment map reflects
// the map's radiance (the furnace), both show the map as the background of the same pixels, and a sphere
// under the analytic sky and its sun has the same brightness in the rasteriser as in the path tracer.

#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "core/pathtrace/path_tracer.h"
#include "core/render/render_target.h"
#include "core/render/sky_model.h"
#include "gl_fixture.h"
#include "test_scenes.h"

namespace sp::pathtrace {
namespace {

using render::Camera;
using render::EnvironmentMap;
using render::Scene;

std::shared_ptr<const EnvironmentMap> mapOf(const std::function<Eigen::Vector3f(const Eigen::Vector3f&)>& f,
                                            int width = 256) {
    render::RadianceImage image{width, width / 2, {}};
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x)
            image.texels.push_back(f(EnvironmentMap::fromUv((float(x) + 0.5f) / float(image.width),
                                                            (float(y) + 0.5f) / float(image.height))));
    return std::make_shared<const EnvironmentMap>(std::move(image), 0.0f, "test");
}

render::Environment environmentOf(std::shared_ptr<const EnvironmentMap> map) {
    render::Environment environment;
    environment.map = std::move(map);
    return environment;
}

class EnvironmentGlTest : public render::test::GlTest {
  protected:
    // A sphere of radius 0.5 at the origin, seen from 3 m along +X with a narrow view that it fills.
    static void addSphere(Scene& scene, const render::Material& m) {
        scene.addInstance(
            {scene.addMesh(render::primitives::sphere(0.5f, 64, 32)), {scene.addMaterial(m)}, {1}});
    }
    static Camera sphereCamera() { return lookingAlong({-3.0, 0.0, 0.0}, {1.0, 0.0, 0.0}, 16, 16, 8.0); }

    render::Frame raster(const Scene& scene, const Camera& camera) {
        return renderFrame(
            scene, camera,
            {render::Modality::HdrColor, render::Modality::DiffuseIllumination, render::Modality::ObjectIds});
    }
    PathTracer tracer_;
};

TEST_F(EnvironmentGlTest, AWhiteDiffuseObjectInAUniformMapReachesItsRadianceInBothRenderers) {
    Scene scene;
    addSphere(scene, render::test::makeMaterial({1.0f, 1.0f, 1.0f}, 0.8f, 0.0f));
    const Eigen::Vector3f sky(0.7f, 0.8f, 0.9f);
    scene.setEnvironment(
        environmentOf(mapOf([&](const Eigen::Vector3f&) -> Eigen::Vector3f { return sky; })));
    const render::Frame frame = raster(scene, sphereCamera());
    Accumulation traced;
    tracer_.render(scene, sphereCamera(), {128, 3}, traced);
    const render::ImageBuffer& illumination = frame.get(render::Modality::DiffuseIllumination);
    // The rasteriser's terms are exact per pixel; the path tracer's mean is, each pixel within its noise at
    // 128 samples (the map's directions are drawn over the whole sphere, half of them behind the surface).
    Eigen::Vector3d tracedMean = Eigen::Vector3d::Zero();
    for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 16; ++x)
            for (int c = 0; c < 3; ++c) {
                EXPECT_NEAR(illumination.at(x, y, c), sky[c], 0.01f) << x << ", " << y;
                EXPECT_NEAR(traced.mean(traced.diffuseIlluminationSum, x, y, c), sky[c], 0.15f);
                tracedMean[c] += traced.mean(traced.diffuseIlluminationSum, x, y, c) / 256.0;
            }
    for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(tracedMean[c], sky[c], 0.01);
}

TEST_F(EnvironmentGlTest, BothRenderersShowTheMapAsTheBackground) {
    // Nothing in view: every pixel is the map along its ray, the same in both (a smooth map, so that the
    // path tracer's jitter within a pixel and the half-float texture change little).
    Scene scene;
    scene.setEnvironment(environmentOf(mapOf([](const Eigen::Vector3f& d) -> Eigen::Vector3f {
        return Eigen::Vector3f(1.0f + d.x(), 1.0f + d.y(), 1.0f + d.z()) * 0.5f;
    })));
    const Camera camera = lookingAlong({0.0, 0.0, 0.0}, {1.0, 1.0, 0.3}, 24, 16, 90.0);
    const render::Frame frame = raster(scene, camera);
    Accumulation traced;
    tracer_.render(scene, camera, {16, 0}, traced);
    const render::ImageBuffer& hdr = frame.get(render::Modality::HdrColor);
    for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 24; ++x)
            for (int c = 0; c < 3; ++c)
                EXPECT_NEAR(hdr.at(x, y, c), traced.mean(x, y, c), 0.02f) << x << ", " << y << ", " << c;
}

TEST_F(EnvironmentGlTest, ASphereUnderTheAnalyticSkyIsAsBrightInBothRenderers) {
    // Convex, so that neither renderer misses a bounce: the rasteriser's sky terms (spherical harmonics,
    // the prefiltered chain) against the path tracer's integral of the same map, rough and glossy.
    render::SkyParameters parameters;
    parameters.sunDirection = Eigen::Vector3f(0.5f, 0.3f, -0.6f).normalized();
    const std::shared_ptr<const EnvironmentMap> sky =
        std::make_shared<const EnvironmentMap>(render::PreethamSky(parameters).image(512, 256), 0.0f, "test");
    // Tolerance: the split sum's prefiltering takes the view along the normal, which loses some of a glossy
    // lobe's light at grazing angles (Karis 2013); a rough dielectric is mostly the harmonics' diffuse term.
    struct Case {
        float roughness, metallic;
        double tolerance;
    };
    for (const auto& [roughness, metallic, tolerance] : {Case{0.9f, 0.0f, 0.03}, Case{0.3f, 1.0f, 0.08}}) {
        Scene scene;
        addSphere(scene, render::test::makeMaterial({0.8f, 0.6f, 0.4f}, roughness, metallic));
        render::Light sun;
        sun.direction = parameters.sunDirection.cast<double>();
        sun.intensity = parameters.sunIrradiance.x();
        scene.addLight(sun);
        scene.setEnvironment(environmentOf(sky));
        Camera camera = sphereCamera();
        const render::Frame frame = raster(scene, camera);
        Accumulation traced;
        tracer_.render(scene, camera, {256, 3}, traced);
        double rasterSum = 0.0, tracedSum = 0.0;
        const render::ImageBuffer& hdr = frame.get(render::Modality::HdrColor);
        for (int y = 0; y < 16; ++y)
            for (int x = 0; x < 16; ++x)
                for (int c = 0; c < 3; ++c) {
                    rasterSum += hdr.at(x, y, c);
                    tracedSum += traced.mean(x, y, c);
                }
        EXPECT_NEAR(rasterSum / tracedSum, 1.0, tolerance) << roughness << " " << metallic;
    }
}

} // namespace
} // namespace sp::pathtrace
