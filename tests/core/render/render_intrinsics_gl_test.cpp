// The intrinsic decomposition: diffuse_illumination is the radiance of a white Lambertian surface,
// diffuse_only = base_color * (1 - metallic) * diffuse_illumination, and
// hdr_color.rgb = diffuse_only + specular_residual, per pixel, within float16 rounding.

#include <array>
#include <string>
#include <utility>
#include <vector>

#include "core/render/image_buffer.h"
#include "core/render/texture_image.h"
#include "gl_fixture.h"
#include "test_scenes.h"

namespace sp::render::test {
namespace {

using RenderIntrinsicsGlTest = GlTest;

// Renders the shapes under a sun and a spot light with `modalities` (which hold every image the identities
// name), in one pass or with an attribute pass as `attributePass` says, and checks the identities at
// every pixel.
void expectIdentitiesPerPixel(Renderer& renderer, const ModalitySet& modalities, bool attributePass) {
    ASSERT_EQ(modalities.requiredPasses(true).attributeTargets != 0, attributePass);
    Scene scene;
    buildShapesScene(scene);
    Light spot;
    spot.type = LightType::Spot;
    spot.position = Eigen::Vector3d(1, 1, 3);
    spot.direction = Eigen::Vector3d(-0.3, -0.3, -1);
    spot.intensity = 8.0f;
    scene.addLight(spot);
    Camera camera = cameraLookingAt({3.2, -2.4, 2.2}, {0, 0, 0.3}, 48, 40);
    RenderTarget target(renderer, modalities, 0);
    Frame frame;
    target.render(scene, camera, frame);
    const ImageBuffer& hdr = frame.get(Modality::HdrColor);
    const ImageBuffer& base = frame.get(Modality::BaseColor);
    const ImageBuffer& metallic = frame.get(Modality::Metallic);
    const ImageBuffer& illumination = frame.get(Modality::DiffuseIllumination);
    const ImageBuffer& diffuse = frame.get(Modality::DiffuseOnly);
    const ImageBuffer& residual = frame.get(Modality::SpecularResidual);
    const ImageBuffer& ids = frame.get(Modality::ObjectIds);
    int background = 0, metalPixels = 0;
    for (int y = 0; y < 40; ++y)
        for (int x = 0; x < 48; ++x) {
            const float oneMinusMetal = 1.0f - metallic.at(x, y);
            metalPixels += oneMinusMetal < 0.5f;
            for (int c = 0; c < 3; ++c) {
                // Recomputed from the stored float16 inputs, as the shader does.
                const float expectedDiffuse = base.at(x, y, c) * oneMinusMetal * illumination.at(x, y, c);
                ASSERT_NEAR(diffuse.at(x, y, c), expectedDiffuse, std::abs(expectedDiffuse) * 1e-3f + 1e-6f)
                    << "diffuse_only at " << x << "," << y << " c" << c;
                const float h = hdr.at(x, y, c), d = diffuse.at(x, y, c), r = residual.at(x, y, c);
                ASSERT_NEAR(h, d + r, 1e-3f * (std::abs(h) + std::abs(d) + std::abs(r)) + 1e-6f)
                    << "hdr = diffuse_only + specular_residual at " << x << "," << y << " c" << c;
                ASSERT_GE(illumination.at(x, y, c), 0.0f);
            }
            if (ids.uintAt(x, y) == 0) {
                ++background;
                EXPECT_EQ(illumination.at(x, y, 0), 0.0f);
                EXPECT_NEAR(residual.at(x, y, 2), scene.environment().background.z(), 1e-3f);
            }
        }
    EXPECT_GT(background, 0);
    EXPECT_GT(metalPixels, 0); // the gold sphere is in view: its diffuse part is zero
}

TEST_F(RenderIntrinsicsGlTest, IdentitiesHoldPerPixelInOnePass) {
    // Seven targets: shaded with the inputs rounded as the targets store them.
    expectIdentitiesPerPixel(renderer(),
                             {Modality::HdrColor, Modality::BaseColor, Modality::Metallic,
                              Modality::ObjectIds, Modality::DiffuseIllumination, Modality::DiffuseOnly,
                              Modality::SpecularResidual},
                             false);
}

TEST_F(RenderIntrinsicsGlTest, IdentitiesHoldPerPixelWithAnAttributePass) {
    // Rendered (as on a GPU): base colour, metallic and the ids come from the attribute pass, the rest from
    // the surface pass. Computed on the CPU (a software rasteriser's default): diffuse_only,
    // specular_residual and position from the images read, all drawn in one pass.
    const bool byDefault = renderer().derivesOnCpu();
    for (const bool derive : {false, true}) {
        SCOPED_TRACE(derive ? "computed on the CPU" : "rendered");
        renderer().setDerivesOnCpu(derive);
        expectIdentitiesPerPixel(renderer(), ModalitySet::all(), true);
    }
    renderer().setDerivesOnCpu(byDefault);
}

TEST_F(RenderIntrinsicsGlTest, ComputedIntrinsicsMatchRenderedOnesToAFloat16Step) {
    Scene scene;
    buildShapesScene(scene);
    Camera camera = cameraLookingAt({3.2, -2.4, 2.2}, {0, 0, 0.3}, 61, 37); // pixels not a multiple of 8
    const bool byDefault = renderer().derivesOnCpu();
    Frame frames[2];
    for (const bool derive : {false, true}) {
        renderer().setDerivesOnCpu(derive);
        RenderTarget target(renderer(), ModalitySet::all(), derive ? 1 : 0); // the staged path, too
        for (int i = 0; i < 2; ++i) // latency 1: the second submit's read returns the first frame
            target.submit(scene, camera);
        ASSERT_TRUE(target.read(frames[derive ? 1 : 0]).has_value());
    }
    renderer().setDerivesOnCpu(byDefault);
    // One float16 step of the larger magnitude: the shader rounds once from float32, the CPU from the
    // rounded hdr_color and diffuse_only.
    const auto step = [](float a, float b) {
        return std::max(std::abs(a), std::abs(b)) * (1.0f / 1024.0f) + 1e-6f;
    };
    for (Modality computed : {Modality::DiffuseOnly, Modality::SpecularResidual})
        for (int y = 0; y < 37; ++y)
            for (int x = 0; x < 61; ++x)
                for (int c = 0; c < 3; ++c) {
                    const float rendered = frames[0].get(computed).at(x, y, c);
                    const float cpu = frames[1].get(computed).at(x, y, c);
                    ASSERT_NEAR(cpu, rendered,
                                2.0f * step(rendered, frames[1].get(Modality::HdrColor).at(x, y, c)))
                        << modalityName(computed) << " at " << x << "," << y << " c" << c;
                }
}

TEST_F(RenderIntrinsicsGlTest, ComputedPositionMatchesTheRasterisedOne) {
    // The same point, rasterised (interpolated in float32 across its triangle) or computed from depth on
    // its pixel's centre ray (in double, rounded once): within float32 rounding of the coordinates.
    Scene scene;
    buildShapesScene(scene);
    Camera camera = cameraLookingAt({3.2, -2.4, 2.2}, {0, 0, 0.3}, 61, 37);
    const bool byDefault = renderer().derivesOnCpu();
    Frame frames[2];
    for (const bool derive : {false, true}) {
        renderer().setDerivesOnCpu(derive);
        RenderTarget target(renderer(), ModalitySet::all(), derive ? 1 : 0);
        for (int i = 0; i < 2; ++i)
            target.submit(scene, camera);
        ASSERT_TRUE(target.read(frames[derive ? 1 : 0]).has_value());
    }
    renderer().setDerivesOnCpu(byDefault);
    int geometry = 0;
    for (int y = 0; y < 37; ++y)
        for (int x = 0; x < 61; ++x) {
            const float depth = frames[1].get(Modality::Depth).at(x, y);
            ASSERT_EQ(depth, frames[0].get(Modality::Depth).at(x, y)) << x << "," << y;
            geometry += depth > 0.0f;
            for (int c = 0; c < 3; ++c) {
                const float rendered = frames[0].get(Modality::Position).at(x, y, c);
                const float cpu = frames[1].get(Modality::Position).at(x, y, c);
                if (depth == 0.0f) { // the background: 0 either way
                    ASSERT_EQ(cpu, 0.0f) << x << "," << y;
                    ASSERT_EQ(rendered, 0.0f) << x << "," << y;
                    continue;
                }
                // A few float32 steps of the distance from the camera (about 4 m here; 2.6e-6 m measured).
                ASSERT_NEAR(cpu, rendered, 2e-6f * depth + 1e-6f) << x << "," << y << " c" << c;
            }
        }
    EXPECT_GT(geometry, 61 * 37 / 4);
}

TEST_F(RenderIntrinsicsGlTest, AComputedModalityReadAloneOrAgainIsTheSame) {
    Scene scene;
    buildShapesScene(scene);
    Camera camera = cameraLookingAt({3.2, -2.4, 2.2}, {0, 0, 0.3}, 24, 16);
    const bool byDefault = renderer().derivesOnCpu();
    renderer().setDerivesOnCpu(true);
    RenderTarget target(renderer(), ModalitySet::all(), 0);
    Frame all;
    target.render(scene, camera, all);
    // Read again, alone: its inputs come from scratch reads instead of the views read beside it.
    for (Modality computed : {Modality::SpecularResidual, Modality::DiffuseOnly, Modality::Position}) {
        std::vector<std::byte> alone(modalityByteSize(computed, 24, 16));
        const OutputView view{computed, alone.data(), alone.size()};
        ASSERT_TRUE(target.readAgain(std::span<const OutputView>(&view, 1)).has_value());
        EXPECT_EQ(alone, all.get(computed).bytes) << modalityName(computed);
    }
    renderer().setDerivesOnCpu(byDefault);
}

TEST_F(RenderIntrinsicsGlTest, WhiteLambertianUnderANormalSunHasUnitIllumination) {
    // A directional light of intensity pi at normal incidence gives a white Lambertian radiance of 1,
    // whatever the surface's own colour.
    Scene scene;
    scene.setEnvironment({{0, 0, 0}, {0, 0, 0}});
    Material halfGrey = makeMaterial({0.5f, 0.25f, 1.0f}, 1.0f, 0.0f);
    scene.addInstance({scene.addMesh(primitives::plane(50, 50)), {scene.addMaterial(halfGrey)}, {1}});
    Light sun;
    sun.direction = Eigen::Vector3d(0, 0, -1);
    sun.intensity = float(M_PI);
    sun.castShadows = false;
    scene.addLight(sun);
    Camera camera = cameraLookingAt({0, 0, 5}, {0.01, 0, 0}, 16, 16, 40.0);
    RenderTarget target(renderer(), {Modality::DiffuseIllumination, Modality::DiffuseOnly}, 0);
    Frame frame;
    target.render(scene, camera, frame);
    for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 16; ++x) {
            for (int c = 0; c < 3; ++c)
                ASSERT_NEAR(frame.get(Modality::DiffuseIllumination).at(x, y, c), 1.0f, 1e-3f);
            ASSERT_NEAR(frame.get(Modality::DiffuseOnly).at(x, y, 0), 0.5f, 1e-3f);
            ASSERT_NEAR(frame.get(Modality::DiffuseOnly).at(x, y, 1), 0.25f, 1e-3f);
        }
}

TEST_F(RenderIntrinsicsGlTest, MaterialModalitiesAreTheMaterialInputs) {
    Scene scene;
    Material m = makeMaterial({0.2f, 0.4f, 0.6f}, 0.35f, 0.75f);
    m.ambientOcclusion = 0.5f;
    scene.addInstance({scene.addMesh(primitives::plane(50, 50)), {scene.addMaterial(m)}, {1}});
    Camera camera = cameraLookingAt({0, 0, 5}, {0.01, 0, 0}, 8, 8, 40.0);
    RenderTarget target(
        renderer(), {Modality::BaseColor, Modality::Roughness, Modality::Metallic, Modality::MaterialAo}, 0);
    Frame frame;
    target.render(scene, camera, frame);
    EXPECT_NEAR(frame.get(Modality::BaseColor).at(3, 3, 0), 0.2f, 1e-3f);
    EXPECT_NEAR(frame.get(Modality::BaseColor).at(3, 3, 2), 0.6f, 1e-3f);
    EXPECT_NEAR(frame.get(Modality::Roughness).at(3, 3), 0.35f, 1e-3f);
    EXPECT_NEAR(frame.get(Modality::Metallic).at(3, 3), 0.75f, 1e-3f);
    EXPECT_NEAR(frame.get(Modality::MaterialAo).at(3, 3), 0.5f, 1e-3f);
}

TEST_F(RenderIntrinsicsGlTest, BaseColorTextureUsesTopLeftUvOrigin) {
    // An 8x8 sRGB texture with four coloured quadrants; uv (0, 0) is the image's top-left texel.
    std::vector<std::uint8_t> rgba(8 * 8 * 4);
    const std::uint8_t colors[4][3] = {{255, 0, 0}, {0, 255, 0}, {0, 0, 255}, {188, 188, 188}};
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 8; ++x) {
            const int quadrant = (y / 4) * 2 + x / 4;
            for (int c = 0; c < 3; ++c)
                rgba[(y * 8 + x) * 4 + c] = colors[quadrant][c];
            rgba[(y * 8 + x) * 4 + 3] = 255;
        }
    Scene scene;
    Material textured;
    textured.baseColor = {1, 1, 1, 1};
    textured.baseColorTexture = scene.addTexture(TextureImage::fromPixels(8, 8, rgba));
    scene.addInstance({scene.addMesh(primitives::plane(2, 2)), {scene.addMaterial(textured)}, {1}});
    Camera camera = cameraLookingAt({0, 0, 3}, {0.001, 0, 0}, 64, 64, 60.0);
    RenderTarget target(renderer(), {Modality::BaseColor}, 0);
    Frame frame;
    target.render(scene, camera, frame);
    // The plane primitive maps uv (u, v) to (-1 + 2u, -1 + 2v, 0).
    const Eigen::Vector2d uvs[4] = {{0.25, 0.25}, {0.75, 0.25}, {0.25, 0.75}, {0.75, 0.75}};
    for (int q = 0; q < 4; ++q) {
        const Eigen::Vector3d pixel = camera.project({-1 + 2 * uvs[q].x(), -1 + 2 * uvs[q].y(), 0});
        for (int c = 0; c < 3; ++c) {
            const float srgb = colors[q][c] / 255.0f;
            const float linear = srgb <= 0.04045f ? srgb / 12.92f : std::pow((srgb + 0.055f) / 1.055f, 2.4f);
            EXPECT_NEAR(frame.get(Modality::BaseColor).at(int(pixel.x()), int(pixel.y()), c), linear, 0.01f)
                << "quadrant " << q << " channel " << c;
        }
    }
}

} // namespace
} // namespace sp::render::test

namespace sp::render::test {
namespace {

TEST_F(RenderIntrinsicsGlTest, PointAndSpotLightsFollowInverseSquareAndCone) {
    Scene scene;
    scene.setEnvironment({{0, 0, 0}, {0, 0, 0}});
    scene.addInstance({scene.addMesh(primitives::plane(100, 100)), {scene.addMaterial(Material{})}, {1}});
    Light point;
    point.type = LightType::Point;
    point.position = Eigen::Vector3d(0, 0, 2);
    point.intensity = 8.0f;
    LightId light = scene.addLight(point);
    Camera camera = cameraLookingAt({0, 0, 10}, {0.001, 0, 0}, 32, 32, 60.0);
    RenderTarget target(renderer(), {Modality::DiffuseIllumination, Modality::Position}, 0);
    Frame frame;
    target.render(scene, camera, frame);
    // White Lambertian radiance under a point light: I cos(theta) / d^2 / pi, at the pixel's own point.
    auto expectedAt = [&](int x, int y) {
        const ImageBuffer& position = frame.get(Modality::Position);
        const Eigen::Vector3d p(position.at(x, y, 0), position.at(x, y, 1), position.at(x, y, 2));
        const Eigen::Vector3d toLight = point.position - p;
        return float(8.0 * (toLight.z() / toLight.norm()) / toLight.squaredNorm() / M_PI);
    };
    const Eigen::Vector3d below = camera.project({0, 0, 0}), offset = camera.project({2, 0, 0});
    const int bx = int(below.x()), by = int(below.y()), ox = int(offset.x()), oy = int(offset.y());
    for (auto [x, y] : {std::pair{bx, by}, std::pair{ox, oy}}) {
        const float expected = expectedAt(x, y);
        EXPECT_NEAR(frame.get(Modality::DiffuseIllumination).at(x, y), expected, 2e-3f * expected)
            << x << "," << y;
    }
    EXPECT_GT(expectedAt(bx, by), 2.5f * expectedAt(ox, oy)); // the two pixels are far apart

    // A spot pointing down with a 20 degree outer cone: as bright as the point light on its axis, dark
    // 45 degrees off axis.
    Light spot = point;
    spot.type = LightType::Spot;
    spot.direction = Eigen::Vector3d(0, 0, -1);
    spot.innerConeDeg = 10.0f;
    spot.outerConeDeg = 20.0f;
    scene.setLight(light, spot);
    target.render(scene, camera, frame);
    EXPECT_NEAR(frame.get(Modality::DiffuseIllumination).at(bx, by), expectedAt(bx, by),
                2e-3f * expectedAt(bx, by));
    EXPECT_EQ(frame.get(Modality::DiffuseIllumination).at(ox, oy), 0.0f);
}

} // namespace
} // namespace sp::render::test

namespace sp::render::test {
namespace {

// A texture filled with one RGBA value.
TextureImage solid(std::uint8_t r, std::uint8_t g, std::uint8_t b) {
    std::vector<std::uint8_t> rgba;
    for (int i = 0; i < 4 * 4; ++i)
        rgba.insert(rgba.end(), {r, g, b, 255});
    return TextureImage::fromPixels(4, 4, rgba);
}

TEST_F(RenderIntrinsicsGlTest, NormalAndOcclusionRoughnessMetallicTextures) {
    Scene scene;
    Material m;
    m.roughness = 1.0f;
    m.metallic = 1.0f;
    m.ambientOcclusion = 0.5f;
    // Tangent-space (0.71, 0, 0.71): tilted 45 degrees towards the texture's +u, which the plane primitive
    // maps to world +X. glTF layout for occlusion (R), roughness (G) and metallic (B).
    m.normalTexture = scene.addTexture(solid(218, 128, 218), TextureEncoding::Linear);
    m.roughnessMetallicTexture = scene.addTexture(solid(102, 64, 191), TextureEncoding::Linear);
    const MaterialId material = scene.addMaterial(m);
    scene.addInstance({scene.addMesh(primitives::plane(50, 50)), {material}, {1}});
    Camera camera = cameraLookingAt({0, 0, 5}, {0.01, 0, 0}, 8, 8, 40.0);
    RenderTarget target(renderer(),
                        {Modality::Normal, Modality::Roughness, Modality::Metallic, Modality::MaterialAo}, 0);
    Frame frame;
    target.render(scene, camera, frame);
    const ImageBuffer& normal = frame.get(Modality::Normal);
    EXPECT_NEAR(normal.at(4, 4, 0), 0.707f, 0.02f);
    EXPECT_NEAR(normal.at(4, 4, 1), 0.0f, 0.02f);
    EXPECT_NEAR(normal.at(4, 4, 2), 0.707f, 0.02f);
    EXPECT_NEAR(frame.get(Modality::Roughness).at(4, 4), 64.0f / 255.0f, 2e-3f);
    EXPECT_NEAR(frame.get(Modality::MaterialAo).at(4, 4), 0.5f * 102.0f / 255.0f,
                2e-3f); // the factor times R

    // Green tilts towards the image's up, i.e. decreasing v, which the plane maps to world -Y.
    m.normalTexture = scene.addTexture(solid(128, 218, 218), TextureEncoding::Linear);
    scene.setMaterial(material, m);
    target.render(scene, camera, frame);
    EXPECT_NEAR(frame.get(Modality::Normal).at(4, 4, 0), 0.0f, 0.02f);
    EXPECT_NEAR(frame.get(Modality::Normal).at(4, 4, 1), -0.707f, 0.02f);
    EXPECT_NEAR(frame.get(Modality::Metallic).at(4, 4), 191.0f / 255.0f, 2e-3f);
}

TEST(PackOcclusionRoughnessMetallic, PutsTheOcclusionInRAndLeavesWhatIsAbsentUnscaled) {
    TextureImage rm = solid(0, 64, 191), ao = solid(102, 102, 102);
    rm.source = "rm.png";
    ao.source = "ao.png";
    const TextureImage both = packOcclusionRoughnessMetallic(&rm, &ao);
    const TextureImage rmOnly = packOcclusionRoughnessMetallic(&rm, nullptr);
    const TextureImage aoOnly = packOcclusionRoughnessMetallic(nullptr, &ao);
    const TextureImage self = packOcclusionRoughnessMetallic(&rm, &rm); // an ORM map named as both
    for (const auto& [image, expected] :
         std::vector<std::pair<const TextureImage*, std::array<int, 4>>>{{&both, {102, 64, 191, 255}},
                                                                         {&rmOnly, {255, 64, 191, 255}},
                                                                         {&aoOnly, {102, 255, 255, 255}},
                                                                         {&self, {0, 64, 191, 255}}})
        for (int c = 0; c < 4; ++c)
            EXPECT_EQ(image->rgba[std::size_t(c)], expected[std::size_t(c)])
                << image->source << " channel " << c;
    TextureImage small = TextureImage::fromPixels(2, 2, std::vector<std::uint8_t>(16, 200));
    small.source = "small.png";
    try {
        packOcclusionRoughnessMetallic(&rm, &small);
        FAIL() << "maps of two sizes were packed";
    } catch (const InvalidArgument& error) {
        EXPECT_NE(std::string(error.what()).find("'small.png' is 2x2"), std::string::npos) << error.what();
        EXPECT_NE(std::string(error.what()).find("'rm.png' 4x4"), std::string::npos) << error.what();
    }
    EXPECT_THROW(packOcclusionRoughnessMetallic(nullptr, nullptr), InvalidArgument);
}

TEST_F(RenderIntrinsicsGlTest, UpdatedMeshIsReuploaded) {
    Scene scene;
    MeshId mesh = scene.addMesh(primitives::box({1, 1, 1}));
    scene.addInstance({mesh, {scene.addMaterial(Material{})}, {1}});
    Camera camera = cameraLookingAt({-5, 0, 0}, {0, 0, 0}, 8, 8, 40.0);
    RenderTarget target(renderer(), {Modality::Depth}, 0);
    Frame frame;
    target.render(scene, camera, frame);
    EXPECT_NEAR(frame.get(Modality::Depth).at(4, 4), 4.5f, 1e-4f);
    renderer().resetStats();
    scene.updateMesh(mesh, primitives::box({3, 3, 3}));
    target.render(scene, camera, frame);
    EXPECT_NEAR(frame.get(Modality::Depth).at(4, 4), 3.5f, 1e-4f);
    EXPECT_EQ(renderer().stats().meshUploads, 1u);
    target.render(scene, camera, frame);
    EXPECT_EQ(renderer().stats().meshUploads, 1u); // unchanged meshes are not uploaded again
}

} // namespace
} // namespace sp::render::test
