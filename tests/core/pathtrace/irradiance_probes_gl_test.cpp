// The rasteriser's global illumination: the irradiance volume's blend (no GL), probes lit by the path tracer,
// and the rasteriser shading with them against the path tracer's own images: a furnace (a white object in a
// uniform sky reflects the sky), a closed white room lit from inside, no sunlight leaking into a closed room,
// and the bound on the updates a change takes to reach every probe.

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <numeric>

#include "closed_room.h"
#include "core/base/error.h"
#include "core/pathtrace/irradiance_probes.h"
#include "core/pathtrace/path_tracer.h"
#include "core/render/render_target.h"
#include "gl_fixture.h"
#include "test_scenes.h"

namespace sp::pathtrace {
namespace {

using render::Camera;
using render::IrradianceProbe;
using render::IrradianceVolume;
using render::Light;
using render::LightType;
using render::Scene;

IrradianceVolume uniformVolume(const Eigen::Vector3f& radiance) {
    IrradianceVolume volume;
    volume.counts = {3, 3, 3};
    IrradianceProbe probe;
    probe.constant = radiance;
    probe.freeDistance.fill(IrradianceVolume::kMaxFreeDistance);
    volume.probes.assign(27, probe);
    return volume;
}

TEST(IrradianceVolumeTest, UniformProbesGiveTheirRadianceEverywhere) {
    const IrradianceVolume volume = uniformVolume({0.5f, 1.0f, 2.0f});
    for (const Eigen::Vector3d& p : {Eigen::Vector3d(0.3, 1.2, 0.7), Eigen::Vector3d(-5.0, 9.0, 0.0)})
        for (const Eigen::Vector3f& n : {Eigen::Vector3f(0, 0, 1), Eigen::Vector3f(0.6f, -0.8f, 0.0f)})
            EXPECT_TRUE(volume.radiance(p, n).isApprox(Eigen::Vector3f(0.5f, 1.0f, 2.0f), 1e-5f));
    EXPECT_EQ(volume.packed().size(), 27u * 8u);
}

TEST(IrradianceVolumeTest, APointSeesOnlyTheProbesWhoseFreeBoxHoldsIt) {
    // Two layers of probes along X with a wall between them (x = 0.5): the left probes see 1, the right 9.
    IrradianceVolume volume = uniformVolume({1.0f, 1.0f, 1.0f});
    volume.counts = {2, 2, 2};
    volume.probes.resize(8);
    for (int z = 0; z < 2; ++z)
        for (int y = 0; y < 2; ++y) {
            IrradianceProbe& left = volume.probes[volume.index(0, y, z)];
            IrradianceProbe& right = volume.probes[volume.index(1, y, z)];
            left.freeDistance[1] = 0.5f;  // +X: the wall
            right.freeDistance[0] = 0.5f; // -X: the wall
            right.constant = Eigen::Vector3f::Constant(9.0f);
        }
    // A point on the left face of the wall, facing left, sees the left probes alone.
    EXPECT_NEAR(volume.radiance({0.49, 0.5, 0.5}, {-1.0f, 0.0f, 0.0f}).x(), 1.0f, 0.02f);
    EXPECT_NEAR(volume.radiance({0.51, 0.5, 0.5}, {1.0f, 0.0f, 0.0f}).x(), 9.0f, 0.2f);
}

TEST(IrradianceVolumeTest, BadVolumesAreRefusedWithTheField) {
    IrradianceVolume volume = uniformVolume({1.0f, 1.0f, 1.0f});
    volume.counts = {1, 3, 9};
    EXPECT_THROW(
        try { volume.validate("test"); } catch (const InvalidArgument& e) {
            EXPECT_NE(std::string(e.what()).find("counts[0] must be in [2, 256], got 1"), std::string::npos);
            throw;
        },
        InvalidArgument);
    volume = uniformVolume({1.0f, 1.0f, 1.0f});
    volume.spacing = 0.0;
    EXPECT_THROW(volume.validate("test"), InvalidArgument);
    volume = uniformVolume({1.0f, 1.0f, 1.0f});
    volume.probes[4].constant.x() = NAN;
    Scene scene;
    EXPECT_THROW(scene.setIrradianceVolume(std::make_shared<IrradianceVolume>(volume)), InvalidArgument);
    ProbeSettings settings;
    settings.rays = 0;
    EXPECT_THROW(settings.validate("test"), InvalidArgument);
}

class IrradianceProbesGlTest : public render::test::GlTest {
  protected:
    // Mean of channel c over the pixels of `image` (an ImageBuffer of float16 or float32 channels).
    static double mean(const render::ImageBuffer& image, int c = 0) {
        double sum = 0.0;
        for (int y = 0; y < image.height; ++y)
            for (int x = 0; x < image.width; ++x)
                sum += image.at(x, y, c);
        return sum / (image.width * image.height);
    }
    static double mean(const Accumulation& image, const std::vector<double>& sums) {
        double sum = 0.0;
        for (int y = 0; y < image.height; ++y)
            for (int x = 0; x < image.width; ++x)
                sum += image.mean(sums, x, y, 0);
        return sum / (image.width * image.height);
    }
    // diffuse_illumination of the rasteriser with the scene's volume (or without, `gi` false).
    render::Frame raster(const Scene& scene, Camera camera, bool gi = true) {
        camera.params.globalIllumination = gi;
        return renderFrame(scene, camera,
                           {render::Modality::DiffuseIllumination, render::Modality::HdrColor});
    }
    PathTracer tracer_;
};

TEST_F(IrradianceProbesGlTest, AWhiteObjectInAUniformSkyReflectsTheSky) {
    // Furnace: every probe sees radiance 1 from everywhere (the sky, or the white sphere reflecting it), so
    // the rasterised sphere's white-surface radiance is 1 where it had the sky term's 1 before; so does the
    // path tracer's.
    Scene scene;
    const render::MaterialId white =
        scene.addMaterial(render::test::makeMaterial({1.0f, 1.0f, 1.0f}, 1.0f, 0.0f));
    scene.addInstance({scene.addMesh(render::primitives::sphere(0.5f, 64, 32)), {white}, {1}});
    scene.setEnvironment({{1.0f, 1.0f, 1.0f}, {1.0f, 1.0f, 1.0f}});
    IrradianceProbes probes;
    scene.setIrradianceVolume(probes.update(scene, tracer_, {}));
    ASSERT_NE(scene.irradianceVolume(), nullptr);
    const Camera camera = lookingAlong({-3.0, 0.0, 0.0}, {1.0, 0.0, 0.0}, 16, 16, 8.0);
    for (bool vertex : {false, true}) {
        renderer().setVertexIrradiance(vertex);
        const render::Frame frame = raster(scene, camera);
        const render::ImageBuffer& illumination = frame.get(render::Modality::DiffuseIllumination);
        for (int y = 0; y < 16; ++y)
            for (int x = 0; x < 16; ++x)
                EXPECT_NEAR(illumination.at(x, y, 0), 1.0f, 0.05f)
                    << x << ", " << y << ", per vertex " << vertex;
    }
}

TEST_F(IrradianceProbesGlTest, AClosedRoomLitFromInsideMatchesThePathTracer) {
    Scene scene;
    test::buildClosedRoom(scene, false);
    const Camera camera = test::closedRoomCamera();
    // A probe's paths bounce maxBounces times after the surface it sees, which is itself a bounce for the
    // points that blend it: the reference bounces once more.
    ProbeSettings settings;
    settings.maxBounces = 4;
    Accumulation traced;
    tracer_.render(scene, camera, {256, settings.maxBounces + 1}, traced);
    const double reference = mean(traced, traced.diffuseIlluminationSum);

    IrradianceProbes probes;
    scene.setIrradianceVolume(probes.update(scene, tracer_, settings));
    const double without = mean(raster(scene, camera, false).get(render::Modality::DiffuseIllumination));
    // Direct light alone falls well short of the reference; with the probes within 5 % of it, blended per
    // pixel or per vertex.
    EXPECT_LT(without, 0.75 * reference);
    for (bool vertex : {false, true}) {
        renderer().setVertexIrradiance(vertex);
        const double withProbes = mean(raster(scene, camera).get(render::Modality::DiffuseIllumination));
        EXPECT_NEAR(withProbes / reference, 1.0, 0.05)
            << "raster " << withProbes << ", path traced " << reference << ", per vertex " << vertex;
        std::cout << "closed room, diffuse_illumination: path traced " << reference << ", raster "
                  << withProbes << " with probes blended per " << (vertex ? "vertex" : "pixel") << ", "
                  << without << " without\n";
    }
}

TEST_F(IrradianceProbesGlTest, LightVertexConnectionsTakeTheLampsHotSpotOutOfTheProbesNoise) {
    // The closed room: most of its light is the lamp's hot spot on the ceiling, 0.3 m above it, which a
    // probe's bounce rays find by chance (blotches a few probes wide in a rasterised wall). Every probe lit
    // with 128 rays, with light-vertex connections and without, against the same probes lit with 4,096:
    // both estimates are unbiased, and the connections' error is far lower.
    Scene scene;
    test::buildClosedRoom(scene, false);
    IrradianceProbes probes;
    const render::IrradianceVolume placed = *probes.update(scene, tracer_, {});
    std::vector<std::size_t> all(placed.probes.size());
    std::iota(all.begin(), all.end(), std::size_t(0));
    const auto lit = [&](int rays, bool connections) {
        render::IrradianceVolume volume = placed;
        Settings settings;
        settings.maxBounces = 3;
        settings.lightConnections = connections;
        tracer_.lightProbes(scene, volume, all, rays, settings);
        return volume;
    };
    const render::IrradianceVolume reference = lit(4096, true), joined = lit(128, true),
                                   bounced = lit(128, false);
    const auto error = [&](const render::IrradianceVolume& volume) {
        double squares = 0.0, total = 0.0;
        for (std::size_t i = 0; i < all.size(); ++i) {
            if (reference.probes[i].freeDistance[0] <= 0.0f)
                continue; // inside a wall: not lit, its neighbours' mean
            squares += (volume.probes[i].constant - reference.probes[i].constant).squaredNorm();
            total += reference.probes[i].constant.squaredNorm();
        }
        return std::sqrt(squares / std::max(total, 1e-12));
    };
    EXPECT_LT(error(joined), 0.5 * error(bounced))
        << "with connections " << error(joined) << ", without " << error(bounced);
    std::cout << "closed room, probes at 128 rays against 4096: relative RMSE " << error(joined)
              << " with light-vertex connections, " << error(bounced) << " without\n";
}

TEST_F(IrradianceProbesGlTest, PerVertexBlendingLeavesTheExactModalitiesAsTheyWere) {
    // Per-vertex indirect light draws meshes subdivided to the probe spacing: the surface is the same, so ids
    // are equal and depth within float rounding of the view without indirect light.
    Scene scene;
    test::buildClosedRoom(scene, false);
    IrradianceProbes probes;
    scene.setIrradianceVolume(probes.update(scene, tracer_, {}));
    renderer().setVertexIrradiance(true);
    Camera camera = test::closedRoomCamera();
    render::Frame frames[2];
    for (int gi = 0; gi < 2; ++gi) {
        camera.params.globalIllumination = gi == 1;
        render::RenderTarget target(
            renderer(), {render::Modality::HdrColor, render::Modality::Depth, render::Modality::ObjectIds},
            0);
        target.render(scene, camera, frames[gi]);
    }
    const render::ImageBuffer& depth0 = frames[0].get(render::Modality::Depth);
    const render::ImageBuffer& depth1 = frames[1].get(render::Modality::Depth);
    int differentIds = 0;
    for (int y = 0; y < depth0.height; ++y)
        for (int x = 0; x < depth0.width; ++x) {
            EXPECT_NEAR(depth1.at(x, y), depth0.at(x, y), 1e-5f * depth0.at(x, y)) << x << ", " << y;
            differentIds += frames[0].get(render::Modality::ObjectIds).at(x, y) !=
                            frames[1].get(render::Modality::ObjectIds).at(x, y);
        }
    EXPECT_EQ(differentIds, 0);
}

TEST_F(IrradianceProbesGlTest, ComputeLightingBlendsTheProbesPerPixelAndLeavesVertexBlendingToTheFragments) {
    // The compute pass has no vertices to blend probes at: with per-vertex blending (llvmpipe's default), a
    // view planned for it is shaded in its fragments, the same image as without it; per pixel, it shades and
    // agrees with the fragments. (Before, the compute program failed to compile there.) A view larger than a
    // shared page, so that it has framebuffers of its own.
    Scene scene;
    test::buildClosedRoom(scene, false);
    IrradianceProbes probes;
    scene.setIrradianceVolume(probes.update(scene, tracer_, {}));
    Camera camera = test::closedRoomCamera();
    camera.params.width = 640;
    camera.params.height = 560;
    // Float targets: compact ones (llvmpipe's default) keep a view in its fragments.
    const bool computeByDefault = renderer().computeLighting(),
               vertexByDefault = renderer().vertexIrradiance(),
               compactByDefault = renderer().compactTargets();
    renderer().setCompactTargets(false);
    for (bool vertex : {true, false}) {
        renderer().setVertexIrradiance(vertex);
        render::Frame frames[2];
        for (int compute = 0; compute < 2; ++compute) {
            renderer().setComputeLighting(compute == 1);
            frames[compute] = renderFrame(scene, camera, {render::Modality::HdrColor});
        }
        const render::ImageBuffer &forward = frames[0].get(render::Modality::HdrColor),
                                  &computed = frames[1].get(render::Modality::HdrColor);
        if (vertex) {
            EXPECT_TRUE(std::equal(forward.bytes.begin(), forward.bytes.end(), computed.bytes.begin()));
            continue;
        }
        double sum = 0.0, difference = 0.0;
        for (int y = 0; y < forward.height; ++y)
            for (int x = 0; x < forward.width; ++x)
                for (int c = 0; c < 3; ++c) {
                    sum += forward.at(x, y, c);
                    difference += std::abs(forward.at(x, y, c) - computed.at(x, y, c));
                }
        EXPECT_LT(difference / sum, 0.01) << "per pixel";
        // ... and it is the compute pass's image: its 22-bit normal differs from the fragments' somewhere.
        EXPECT_GT(difference, 0.0) << "per pixel";
    }
    renderer().setComputeLighting(computeByDefault);
    renderer().setVertexIrradiance(vertexByDefault);
    renderer().setCompactTargets(compactByDefault);
}

TEST_F(IrradianceProbesGlTest, SmallThingsMovingLeaveTheProbesAsTheyAre) {
    // Instances under half a probe spacing in radius are invisible to the probes: moving one (a ball rolling)
    // makes no probe stale; moving a large one does.
    Scene scene;
    test::buildClosedRoom(scene, false);
    const render::MaterialId grey =
        scene.addMaterial(render::test::makeMaterial({0.5f, 0.5f, 0.5f}, 0.8f, 0.0f));
    const render::MeshId box = scene.addMesh(render::primitives::box());
    render::Instance small{box, {grey}, {7}}, large{box, {grey}, {8}};
    small.transform = Eigen::Translation3d(0.5, 0.5, 0.1) * Eigen::Scaling(0.2);
    large.transform = Eigen::Translation3d(-1.0, 0.0, 0.5) * Eigen::Scaling(1.0);
    const render::InstanceId smallId = scene.addInstance(small), largeId = scene.addInstance(large);
    IrradianceProbes probes;
    ProbeSettings settings;
    settings.rays = 16;
    probes.update(scene, tracer_, settings); // 0.5 m apart: the cutoff is 0.25 m, the small box's radius 0.17
    const std::uint64_t builds = tracer_.builds();
    scene.setTransform(smallId, Eigen::Translation3d(0.8, 0.2, 0.1) * Eigen::Scaling(0.2));
    probes.update(scene, tracer_, settings);
    EXPECT_EQ(probes.litLastUpdate(), 0u);
    EXPECT_EQ(tracer_.builds(), builds); // nor does it rebuild the rays' geometry
    scene.setTransform(largeId, Eigen::Translation3d(-0.5, 0.0, 0.5) * Eigen::Scaling(1.0));
    probes.update(scene, tracer_, settings);
    EXPECT_EQ(probes.litLastUpdate(), std::size_t(settings.probesPerFrame));
    EXPECT_EQ(tracer_.builds(), builds + 1);
    // A camera sees the small box where it now is: a path-traced image brings the geometry up to date.
    scene.setTransform(smallId, Eigen::Translation3d(0.2, 0.6, 0.1) * Eigen::Scaling(0.2));
    probes.update(scene, tracer_, settings);
    const Camera camera = test::closedRoomCamera();
    Accumulation shared, fresh;
    tracer_.render(scene, camera, {1, 1}, shared);
    PathTracer other;
    other.render(scene, camera, {1, 1}, fresh);
    EXPECT_EQ(shared.ids, fresh.ids);
    EXPECT_EQ(shared.sum, fresh.sum);
}

// Adds a grey box of side `size` at `at` with object id `id` to `scene`.
render::InstanceId addGreyBox(Scene& scene, const Eigen::Vector3d& at, double size, std::uint32_t id) {
    const render::MaterialId grey =
        scene.addMaterial(render::test::makeMaterial({0.5f, 0.5f, 0.5f}, 0.8f, 0.0f));
    render::Instance box{scene.addMesh(render::primitives::box()), {grey}, {id}};
    box.transform = Eigen::Translation3d(at) * Eigen::Scaling(size);
    return scene.addInstance(box);
}

TEST_F(IrradianceProbesGlTest, AnInstanceBeyondTheRaysReachLeavesTheGridWhereTheSceneIs) {
    // A thing placed at 1e176 m (a mistyped exponent) would put the probes where no float ray can start.
    Scene scene;
    test::buildClosedRoom(scene, false);
    IrradianceProbes probes;
    ProbeSettings settings;
    settings.rays = 16;
    const auto room = probes.update(scene, tracer_, settings);
    ASSERT_NE(room, nullptr);
    addGreyBox(scene, {1e176, 0.0, 0.0}, 1.0, 9);
    const auto volume = probes.update(scene, tracer_, settings);
    ASSERT_NE(volume, nullptr);
    EXPECT_EQ(volume->spacing, room->spacing);
    EXPECT_EQ(volume->counts, room->counts);
    EXPECT_TRUE(volume->origin.allFinite());
    // Nor does it, or a box scaled to nothing, stop the path tracer: no ray meets either.
    addGreyBox(scene, {0.5, 0.5, 0.5}, 0.0, 10);
    Accumulation image;
    tracer_.render(scene, test::closedRoomCamera(), {1, 1}, image);
    EXPECT_EQ(image.samples, 1u);
    for (double value : image.sum)
        ASSERT_TRUE(std::isfinite(value));
}

TEST_F(IrradianceProbesGlTest, AThingFallingAwayBeyondTheCamerasReachLeavesTheGridAsItWas) {
    Scene scene;
    test::buildClosedRoom(scene, false);
    IrradianceProbes probes;
    ProbeSettings settings;
    settings.rays = 16;
    const Eigen::AlignedBox3d around(Eigen::Vector3d::Constant(-50.0), Eigen::Vector3d::Constant(50.0));
    const auto room = probes.update(scene, tracer_, settings, around);
    ASSERT_NE(room, nullptr);
    const render::InstanceId id = addGreyBox(scene, {-150.0, 80.0, -400.0}, 1.0, 9);
    for (double z : {-400.0, -430.0, -460.0}) {
        scene.setTransform(id, Eigen::Translation3d(-150.0, 80.0, z) * Eigen::Scaling(1.0));
        const auto volume = probes.update(scene, tracer_, settings, around);
        EXPECT_EQ(volume, room) << "at z = " << z; // nothing lit again, the same volume
    }
    // Without a region the grid stretches to the box (what `around` is for).
    const auto stretched = probes.update(scene, tracer_, settings);
    ASSERT_NE(stretched, nullptr);
    EXPECT_GT(stretched->spacing, room->spacing);
}

TEST_F(IrradianceProbesGlTest, AGroundTheCamerasMoveOverKeepsOneGrid) {
    // A 200 m ground reaches into the cameras' region wherever they go: it counts whole, so the grid stays.
    Scene scene;
    const render::MaterialId grey =
        scene.addMaterial(render::test::makeMaterial({0.5f, 0.5f, 0.5f}, 0.8f, 0.0f));
    render::Instance ground{scene.addMesh(render::primitives::box()), {grey}, {1}};
    ground.transform = Eigen::Translation3d(0.0, 0.0, -0.05) * Eigen::Scaling(200.0, 200.0, 0.1);
    scene.addInstance(ground);
    IrradianceProbes probes;
    ProbeSettings settings;
    settings.rays = 16;
    const auto first = probes.update(
        scene, tracer_, settings, {Eigen::Vector3d(-60.0, -50.0, -48.0), Eigen::Vector3d(40.0, 50.0, 52.0)});
    ASSERT_NE(first, nullptr);
    for (double x : {-20.0, 0.0, 35.0})
        EXPECT_EQ(
            probes.update(scene, tracer_, settings,
                          {Eigen::Vector3d(x - 50.0, -50.0, -48.0), Eigen::Vector3d(x + 50.0, 50.0, 52.0)}),
            first)
            << "cameras at x = " << x;
}

TEST_F(IrradianceProbesGlTest, SunlightOutsideAClosedRoomDoesNotLeakIn) {
    // The same room with a sun 10x the lamp outside: the inside must look as it did without the sun.
    Scene dark, sunny;
    test::buildClosedRoom(dark, false);
    test::buildClosedRoom(sunny, true);
    IrradianceProbes a, b;
    dark.setIrradianceVolume(a.update(dark, tracer_, {}));
    sunny.setIrradianceVolume(b.update(sunny, tracer_, {}));
    const Camera camera = test::closedRoomCamera();
    for (bool vertex : {false, true}) {
        renderer().setVertexIrradiance(vertex);
        const double inside = mean(raster(dark, camera).get(render::Modality::DiffuseIllumination));
        const double withSun = mean(raster(sunny, camera).get(render::Modality::DiffuseIllumination));
        EXPECT_NEAR(withSun / inside, 1.0, 0.05)
            << "without the sun " << inside << ", with it " << withSun << ", per vertex " << vertex;
    }
}

TEST_F(IrradianceProbesGlTest, AChangeReachesEveryProbeWithinTheStatedUpdates) {
    Scene scene;
    const render::LightId lampId = test::buildClosedRoom(scene, false);
    ProbeSettings settings;
    settings.rays = 16;
    settings.probesPerFrame = 40;
    IrradianceProbes probes;
    std::shared_ptr<const IrradianceVolume> first = probes.update(scene, tracer_, settings);
    EXPECT_EQ(probes.litLastUpdate(), first->probes.size());
    // A still scene lights nothing more and keeps its volume.
    EXPECT_EQ(probes.update(scene, tracer_, settings), first);
    EXPECT_EQ(probes.litLastUpdate(), 0u);

    // The lamp moves: after framesToSettle() updates the volume is what lighting it from scratch gives.
    const int bound = probes.framesToSettle();
    EXPECT_EQ(bound, int((first->probes.size() + 39) / 40));
    Light lamp = scene.light(lampId);
    lamp.position = {-1.0, -0.5, 1.0};
    scene.setLight(lampId, lamp);
    std::shared_ptr<const IrradianceVolume> latest;
    for (int i = 0; i < bound; ++i) {
        latest = probes.update(scene, tracer_, settings);
        EXPECT_GT(probes.litLastUpdate(), 0u) << i;
    }
    IrradianceProbes fresh;
    const std::shared_ptr<const IrradianceVolume> expected = fresh.update(scene, tracer_, settings);
    ASSERT_EQ(latest->probes.size(), expected->probes.size());
    for (std::size_t i = 0; i < expected->probes.size(); ++i) {
        EXPECT_EQ(latest->probes[i].constant, expected->probes[i].constant) << i;
        EXPECT_EQ(latest->probes[i].linear, expected->probes[i].linear) << i;
    }
    probes.update(scene, tracer_, settings);
    EXPECT_EQ(probes.litLastUpdate(), 0u);
}

} // namespace
} // namespace sp::pathtrace
