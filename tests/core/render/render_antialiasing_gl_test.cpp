// Anti-aliasing (CameraParams::antiAliasing): the exact modalities stay bit for bit what a camera without it
// reads; FXAA changes final_color at the silhouettes, the same whether read from the readback buffer
// (latency 1) or the framebuffers (latency 0); MSAA brings final_color close to a supersampled view and
// keeps hdr_color = diffuse_only + specular_residual; spatial samples (moved pixels, averaged) come closer
// with each step and keep the exact modalities exact. Anisotropic texture filtering keeps a floor's texture
// where trilinear filtering blurs it away at a grazing angle.

#include <epoxy/gl.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <limits>
#include <set>
#include <string>
#include <utility>

#include "core/base/error.h"
#include "core/render/image_buffer.h"
#include "core/render/primitives.h"
#include "gl_fixture.h"
#include "test_scenes.h"

namespace sp::render::test {
namespace {

class RenderAntiAliasingGlTest : public GlTest {};

const ModalitySet kModalities{Modality::FinalColor, Modality::Depth, Modality::Normal, Modality::ObjectIds};

// The shapes scene's view of every test here, at a size and with an anti-aliasing setting.
Camera shapesView(int width, int height, AntiAliasing antiAliasing) {
    Camera camera = cameraLookingAt({3.2, -2.4, 2.2}, {0, 0, 0.3}, width, height, 60.0);
    camera.params.antiAliasing = antiAliasing;
    return camera;
}

// A 40 m floor under a sun, its texture 16 x 16 texels of black and white squares `texelsPerSquare` wide,
// repeating every `textureSize` metres.
void buildCheckeredFloor(Scene& scene, int texelsPerSquare, float textureSize) {
    std::vector<std::uint8_t> checker(16 * 16 * 4);
    for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 16; ++x)
            for (int c = 0; c < 4; ++c)
                checker[std::size_t(4 * (16 * y + x) + c)] =
                    c == 3 || (x / texelsPerSquare + y / texelsPerSquare) % 2 == 0 ? 255 : 0;
    Material floor = makeMaterial({1.0f, 1.0f, 1.0f}, 1.0f, 0.0f);
    floor.baseColorTexture = scene.addTexture(TextureImage::fromPixels(16, 16, checker));
    floor.textureSize = textureSize;
    Instance instance{scene.addMesh(primitives::box({40.0f, 40.0f, 0.1f})), {scene.addMaterial(floor)}, {1}};
    instance.transform.translation() = Eigen::Vector3d(0.0, 0.0, -0.05);
    scene.addInstance(instance);
    Light sun;
    sun.direction = Eigen::Vector3d(0.2, 0.1, -1.0).normalized();
    scene.addLight(sun);
}

TEST_F(RenderAntiAliasingGlTest, FxaaFiltersFinalColorAtSilhouettesAndLeavesExactModalitiesExact) {
    Scene scene;
    buildShapesScene(scene);
    const Camera plain = shapesView(160, 120, AntiAliasing::None),
                 filtered = shapesView(160, 120, AntiAliasing::Fxaa);
    const Frame a = renderFrame(scene, plain, kModalities), b = renderFrame(scene, filtered, kModalities);

    for (Modality m : {Modality::Depth, Modality::Normal, Modality::ObjectIds})
        EXPECT_EQ(a.get(m).bytes, b.get(m).bytes) << modalityName(m);

    // Changed pixels, and how many of them lie within a pixel of an object's silhouette.
    const auto ids = a.get(Modality::ObjectIds).as<std::uint32_t>();
    const auto x = a.get(Modality::FinalColor).as<std::uint8_t>(),
               y = b.get(Modality::FinalColor).as<std::uint8_t>();
    const int w = plain.params.width, h = plain.params.height;
    const auto id = [&](int u, int v) {
        return ids[std::size_t(std::clamp(v, 0, h - 1)) * std::size_t(w) +
                   std::size_t(std::clamp(u, 0, w - 1))];
    };
    int changed = 0, atSilhouettes = 0;
    for (int v = 0; v < h; ++v)
        for (int u = 0; u < w; ++u) {
            const std::size_t i = 4 * (std::size_t(v) * std::size_t(w) + std::size_t(u));
            EXPECT_EQ(y[i + 3], 255);
            if (x[i] == y[i] && x[i + 1] == y[i + 1] && x[i + 2] == y[i + 2])
                continue;
            ++changed;
            bool silhouette = false;
            for (int dv = -1; dv <= 1; ++dv)
                for (int du = -1; du <= 1; ++du)
                    silhouette = silhouette || id(u + du, v + dv) != id(u, v);
            atSilhouettes += silhouette ? 1 : 0;
        }
    EXPECT_GT(changed, 100);
    // The rest are shadow edges and the sphere's highlight.
    EXPECT_GT(atSilhouettes, changed * 6 / 10) << changed << " changed";
}

TEST_F(RenderAntiAliasingGlTest, FxaaGivesOneImageWhateverTheLatency) {
    Scene scene;
    buildShapesScene(scene);
    // A small view drawn in a layer of shared framebuffers, and one with framebuffers of its own.
    for (auto [width, height] : {std::pair{160, 120}, std::pair{640, 480}}) {
        const Camera camera = shapesView(width, height, AntiAliasing::Fxaa);
        const Frame direct = renderFrame(scene, camera, kModalities);
        RenderTarget staged(renderer(), kModalities, 1);
        Frame frame;
        staged.submit(scene, camera);
        staged.submit(scene, camera);
        ASSERT_TRUE(staged.read(frame).has_value());
        EXPECT_EQ(frame.get(Modality::FinalColor).bytes, direct.get(Modality::FinalColor).bytes)
            << width << "x" << height;
    }
}

// Mean difference of final_color from the same view rendered `factor` x `factor` times larger and averaged
// down in linear light, in 8-bit steps.
double supersampledError(const ImageBuffer& color, const ImageBuffer& large, int width, int height,
                         int factor = 4) {
    const auto linear = [](std::uint8_t v) {
        const double c = v / 255.0;
        return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
    };
    const auto a = color.as<std::uint8_t>(), b = large.as<std::uint8_t>();
    double sum = 0.0;
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x)
            for (int c = 0; c < 3; ++c) {
                double mean = 0.0;
                for (int j = 0; j < factor; ++j)
                    for (int i = 0; i < factor; ++i)
                        mean += linear(b[4 * ((std::size_t(factor * y + j)) * std::size_t(factor * width) +
                                              std::size_t(factor * x + i)) +
                                         std::size_t(c)]);
                mean /= double(factor * factor);
                const double encoded =
                    mean <= 0.0031308 ? 12.92 * mean : 1.055 * std::pow(mean, 1 / 2.4) - 0.055;
                sum +=
                    std::abs(255.0 * encoded -
                             a[4 * (std::size_t(y) * std::size_t(width) + std::size_t(x)) + std::size_t(c)]);
            }
    return sum / (3.0 * width * height);
}

// The largest relative difference of hdr_color from diffuse_only + specular_residual in a 96 x 64 frame.
double decompositionError(const Frame& frame) {
    const auto hdr = frame.get(Modality::HdrColor).as<std::uint16_t>();
    const auto diffuse = frame.get(Modality::DiffuseOnly).as<std::uint16_t>();
    const auto residual = frame.get(Modality::SpecularResidual).as<std::uint16_t>();
    double largest = 0.0;
    for (std::size_t p = 0; p < std::size_t(96 * 64); ++p)
        for (std::size_t c = 0; c < 3; ++c) {
            const double h = halfToFloat(hdr[4 * p + c]), d = halfToFloat(diffuse[3 * p + c]),
                         r = halfToFloat(residual[3 * p + c]);
            largest = std::max(largest, std::abs(h - d - r) / std::max(1.0, std::abs(h)));
        }
    return largest;
}

TEST_F(RenderAntiAliasingGlTest, MsaaLeavesEveryExactModalityExactAndBringsFinalColorCloseToSupersampling) {
    Scene scene;
    buildShapesScene(scene);
    const Camera plain = shapesView(96, 64, AntiAliasing::None),
                 multisampled = shapesView(96, 64, AntiAliasing::Msaa);
    const Camera large = shapesView(4 * 96, 4 * 64, AntiAliasing::None);
    // Every modality rendered in float targets, as a multisampled frame renders them, so that the exact ones
    // compare bit for bit.
    const bool derives = renderer().derivesOnCpu(), compact = renderer().compactTargets();
    renderer().setDerivesOnCpu(false);
    renderer().setCompactTargets(false);
    const Frame a = renderFrame(scene, plain, ModalitySet::all());
    const Frame big = renderFrame(scene, large, {Modality::FinalColor});
    renderer().setDerivesOnCpu(derives);
    renderer().setCompactTargets(compact);
    renderer().resetStats();
    const Frame b = renderFrame(scene, multisampled, ModalitySet::all());
    EXPECT_EQ(renderer().stats().surfacePasses, 1u);
    EXPECT_EQ(renderer().stats().attributePasses, 1u);

    for (Modality m :
         {Modality::Depth, Modality::Position, Modality::Normal, Modality::ObjectIds, Modality::MaterialIds,
          Modality::BaseColor, Modality::Roughness, Modality::Metallic, Modality::MaterialAo})
        EXPECT_EQ(a.get(m).bytes, b.get(m).bytes) << modalityName(m);
    const double before =
        supersampledError(a.get(Modality::FinalColor), big.get(Modality::FinalColor), 96, 64);
    const double after =
        supersampledError(b.get(Modality::FinalColor), big.get(Modality::FinalColor), 96, 64);
    EXPECT_LT(after, 0.6 * before) << before << " -> " << after;

    // The resolve averages each shaded target alike: hdr_color is still diffuse_only + specular_residual.
    EXPECT_LT(decompositionError(b), 4e-3);
}

TEST_F(RenderAntiAliasingGlTest, MsaaTakesTheDevicesMostSamplesAndRefusesOtherCounts) {
    Scene scene;
    buildShapesScene(scene);
    Camera camera = shapesView(64, 48, AntiAliasing::Msaa);
    camera.params.msaaSamples = 8; // llvmpipe offers 4
    ASSERT_GE(renderer().maxSamples(), 1);
    const Frame frame = renderFrame(scene, camera, {Modality::FinalColor});
    EXPECT_EQ(frame.get(Modality::FinalColor).bytes.size(), std::size_t(64 * 48 * 4));
    camera.params.msaaSamples = 3;
    EXPECT_THROW(renderFrame(scene, camera, {Modality::FinalColor}), InvalidArgument);
}

TEST_F(RenderAntiAliasingGlTest, SpatialSamplesAverageMovedPixelsAndLeaveExactModalitiesExact) {
    Scene scene;
    buildShapesScene(scene);
    // Against the view rendered 16 x 16 times larger and averaged down: finer than any pattern here, and none
    // of them is a subset of its samples (which would favour that one). In hdr_color, whose float16 steps are
    // far finer than final_color's 8-bit ones (whose rounding alone differs by a quarter step on average).
    const int n = 16;
    const Camera plain = shapesView(96, 64, AntiAliasing::None);
    const Camera large = shapesView(n * 96, n * 64, AntiAliasing::None);
    const bool derives = renderer().derivesOnCpu(), compact = renderer().compactTargets();
    renderer().setDerivesOnCpu(false);
    renderer().setCompactTargets(false);
    const Frame a = renderFrame(scene, plain, ModalitySet::all());
    const Frame big = renderFrame(scene, large, {Modality::HdrColor});
    renderer().setDerivesOnCpu(derives);
    renderer().setCompactTargets(compact);
    const ImageBuffer& reference = big.get(Modality::HdrColor);
    const auto error = [&](const Frame& frame) {
        const ImageBuffer& hdr = frame.get(Modality::HdrColor);
        double sum = 0.0;
        for (int y = 0; y < 64; ++y)
            for (int x = 0; x < 96; ++x)
                for (int c = 0; c < 3; ++c) {
                    double mean = 0.0;
                    for (int j = 0; j < n; ++j)
                        for (int i = 0; i < n; ++i)
                            mean += reference.at(n * x + i, n * y + j, c);
                    sum += std::abs(hdr.at(x, y, c) - mean / (n * n));
                }
        return sum / (96 * 64 * 3);
    };
    const double aliased = error(a);

    double previous = aliased;
    for (int count : {2, 4, 8, 16}) {
        Camera sampled = plain;
        sampled.params.spatialSamples = count;
        renderer().resetStats();
        const Frame b = renderFrame(scene, sampled, ModalitySet::all());
        EXPECT_EQ(renderer().stats().surfacePasses, std::uint64_t(count)); // one a sample
        EXPECT_EQ(renderer().stats().attributePasses, 1u);
        for (Modality m : {Modality::Depth, Modality::Position, Modality::Normal, Modality::ObjectIds,
                           Modality::MaterialIds, Modality::BaseColor, Modality::Roughness,
                           Modality::Metallic, Modality::MaterialAo})
            EXPECT_EQ(a.get(m).bytes, b.get(m).bytes) << count << " samples, " << modalityName(m);
        // Closer to the supersampled view with each doubling of the samples.
        const double now = error(b);
        std::cout << count << " spatial samples: mean difference " << now << " (none: " << aliased << ")\n";
        EXPECT_LT(now, 0.8 * previous) << count << " samples";
        previous = now;

        // The resolve averages each shaded target alike: hdr_color is still diffuse_only + specular_residual.
        EXPECT_LT(decompositionError(b), 4e-3) << count << " samples";
    }
}

TEST_F(RenderAntiAliasingGlTest, ASubpixelOffsetMovesTheImageByThatMuch) {
    // A pixel's centre moved by (dx, dy) shows what the unmoved camera shows at (x + dx, y + dy): on a floor
    // seen at a slant, whose position is smooth in the image, the unmoved position plus its gradient times
    // the offset (to second order in the offset).
    Scene scene;
    Instance floor{scene.addMesh(primitives::box({40.0f, 40.0f, 0.1f})),
                   {scene.addMaterial(makeMaterial({0.5f, 0.5f, 0.5f}, 1.0f, 0.0f))},
                   {1}};
    floor.transform.translation() = Eigen::Vector3d(0.0, 0.0, -0.05);
    scene.addInstance(floor);
    Camera camera = cameraLookingAt({0.0, 0.0, 2.0}, {4.0, 1.0, 0.0}, 64, 48, 60.0);
    const Frame unmoved = renderFrame(scene, camera, {Modality::Position});
    const Eigen::Vector2d offset(0.25, -0.375);
    camera.subpixelOffset = offset;
    const Frame moved = renderFrame(scene, camera, {Modality::Position});
    const ImageBuffer &p0 = unmoved.get(Modality::Position), &p1 = moved.get(Modality::Position);
    double largest = 0.0, shift = 0.0;
    for (int y = 30; y < 46; ++y)
        for (int x = 8; x < 56; ++x)
            for (int c = 0; c < 2; ++c) {
                const double gx = (p0.at(x + 1, y, c) - p0.at(x - 1, y, c)) / 2.0,
                             gy = (p0.at(x, y + 1, c) - p0.at(x, y - 1, c)) / 2.0;
                const double expected = p0.at(x, y, c) + offset.x() * gx + offset.y() * gy;
                largest = std::max(largest, std::abs(p1.at(x, y, c) - expected));
                shift = std::max(shift, double(std::abs(p1.at(x, y, c) - p0.at(x, y, c))));
            }
    EXPECT_GT(shift, 0.02); // it moved
    EXPECT_LT(largest, 0.1 * shift) << "moved up to " << shift;
}

TEST_F(RenderAntiAliasingGlTest, SpatialSamplesStandInForMultisamplingCombineWithFxaaAndRefuseOtherCounts) {
    Scene scene;
    buildShapesScene(scene);
    const Frame reference = renderFrame(scene, shapesView(64, 48, AntiAliasing::None), kModalities);
    Frame frames[3];
    const AntiAliasing methods[3] = {AntiAliasing::None, AntiAliasing::Msaa, AntiAliasing::Fxaa};
    for (int i = 0; i < 3; ++i) {
        Camera camera = shapesView(64, 48, methods[i]);
        camera.params.spatialSamples = 4;
        frames[i] = renderFrame(scene, camera, kModalities);
        EXPECT_EQ(frames[i].get(Modality::FinalColor).bytes.size(), std::size_t(64 * 48 * 4));
        EXPECT_EQ(frames[i].get(Modality::ObjectIds).bytes, reference.get(Modality::ObjectIds).bytes);
        EXPECT_EQ(frames[i].get(Modality::Depth).bytes, reference.get(Modality::Depth).bytes);
    }
    // Each moved pass single-sampled, with Msaa as without it; FXAA filters the average.
    EXPECT_EQ(frames[1].get(Modality::FinalColor).bytes, frames[0].get(Modality::FinalColor).bytes);
    EXPECT_NE(frames[2].get(Modality::FinalColor).bytes, frames[0].get(Modality::FinalColor).bytes);
    Camera camera = shapesView(64, 48, AntiAliasing::None);
    for (int count : {0, 3, 32}) {
        camera.params.spatialSamples = count;
        try {
            renderFrame(scene, camera, {Modality::FinalColor});
            ADD_FAILURE() << "spatialSamples " << count << " was accepted";
        } catch (const InvalidArgument& e) {
            EXPECT_NE(std::string(e.what()).find("spatialSamples must be 1, 2, 4, 8 or 16, got " +
                                                 std::to_string(count)),
                      std::string::npos)
                << e.what();
        }
    }
}

TEST_F(RenderAntiAliasingGlTest, SpatialSamplesReadTexturesAsAViewThatManyTimesLargerReadsThem) {
    // A floor of 0.25 m black and white squares seen from 2 m up: past a few metres a square is under a
    // pixel, and a pixel's own mip level is grey. Sixteen samples of that level would average grey to grey;
    // read 2 levels finer (log2 sqrt(16)), as a view 4 x 4 times larger reads them, they average the squares
    // they cover, as a view 16 x 16 times larger averaged down does.
    Scene scene;
    buildCheckeredFloor(scene, 2, 2.0f);
    const int width = 96, height = 64, n = 16;
    Camera camera = cameraLookingAt({-6.0, 0.0, 2.0}, {0.0, 0.0, 0.0}, width, height, 60.0);
    const Camera large = cameraLookingAt({-6.0, 0.0, 2.0}, {0.0, 0.0, 0.0}, n * width, n * height, 60.0);
    const bool byDefault = renderer().anisotropicFiltering();
    renderer().setAnisotropicFiltering(false);
    const Frame reference = renderFrame(scene, large, {Modality::HdrColor});
    const Frame plain = renderFrame(scene, camera, {Modality::HdrColor});
    camera.params.spatialSamples = 16;
    const Frame sampled = renderFrame(scene, camera, {Modality::HdrColor});
    renderer().setAnisotropicFiltering(byDefault);
    const auto error = [&](const Frame& frame) {
        double sum = 0.0;
        for (int y = 0; y < height; ++y)
            for (int x = 0; x < width; ++x) {
                double mean = 0.0;
                for (int j = 0; j < n; ++j)
                    for (int i = 0; i < n; ++i)
                        mean += reference.get(Modality::HdrColor).at(n * x + i, n * y + j, 0);
                sum += std::abs(frame.get(Modality::HdrColor).at(x, y, 0) - mean / (n * n));
            }
        return sum / (width * height);
    };
    const double none = error(plain), spatial = error(sampled);
    std::cout << "checkered floor, mean difference from 16 x 16 supersampling: none " << none
              << ", 16 spatial samples " << spatial << "\n";
    EXPECT_LT(spatial, 0.3 * none);
}

TEST(SpatialSamplePattern, OneSampleInEachRowAndColumnInsideThePixel) {
    for (int count : {1, 2, 4, 8, 16}) {
        const auto pattern = spatialSamplePattern(count);
        ASSERT_EQ(pattern.size(), std::size_t(count));
        std::set<int> columns, rows;
        for (const Eigen::Vector2d& p : pattern) {
            EXPECT_TRUE(p.x() >= -0.5 && p.x() < 0.5 && p.y() >= -0.5 && p.y() < 0.5) << p.transpose();
            columns.insert(int(std::floor((p.x() + 0.5) * count)));
            rows.insert(int(std::floor((p.y() + 0.5) * count)));
        }
        EXPECT_EQ(columns.size(), std::size_t(count));
        EXPECT_EQ(rows.size(), std::size_t(count));
    }
    EXPECT_THROW(spatialSamplePattern(3), InvalidArgument);
}

// Whether the current context's samplers filter anisotropically (as Renderer::Renderer() asks).
bool samplerAnisotropy() {
    return epoxy_gl_version() >= 46 || epoxy_has_gl_extension("GL_ARB_texture_filter_anisotropic") ||
           epoxy_has_gl_extension("GL_EXT_texture_filter_anisotropic");
}

TEST_F(RenderAntiAliasingGlTest,
       AnisotropicFilteringBringsAGrazingFloorCloserToSupersamplingAndLeavesIdsAndDepth) {
    // A 40 m floor of 1 m black and white squares (a 16 x 16 texture, 4 texels a square, repeating every 4
    // m), seen along it from 1.5 m up. Far away a pixel's footprint on the floor is long and thin: trilinear
    // filtering takes the mip level of its long side and greys the squares out; anisotropic filtering
    // samples along it. Against the same view rendered 4 x 4 larger and averaged down, its far floor is
    // closer. The geometry is the same: depth and ids bit for bit.
    Scene scene;
    buildCheckeredFloor(scene, 4, 4.0f);
    const int width = 128, height = 96;
    const Camera camera = cameraLookingAt({-19.0, 0.0, 1.5}, {-9.0, 0.0, 0.0}, width, height, 60.0);
    const Camera large = cameraLookingAt({-19.0, 0.0, 1.5}, {-9.0, 0.0, 0.0}, 4 * width, 4 * height, 60.0);
    const bool byDefault = renderer().anisotropicFiltering();
    renderer().setAnisotropicFiltering(false);
    const Frame supersampled = renderFrame(scene, large, {Modality::HdrColor});
    Frame frames[2];
    for (int anisotropic = 0; anisotropic < 2; ++anisotropic) {
        renderer().setAnisotropicFiltering(anisotropic == 1);
        frames[anisotropic] =
            renderFrame(scene, camera, {Modality::HdrColor, Modality::Depth, Modality::ObjectIds});
    }
    renderer().setAnisotropicFiltering(byDefault);
    for (Modality m : {Modality::Depth, Modality::ObjectIds})
        EXPECT_EQ(frames[0].get(m).bytes, frames[1].get(m).bytes) << modalityName(m);
    // The mean difference over the far half of the floor (the rows between the horizon and the middle).
    const ImageBuffer& reference = supersampled.get(Modality::HdrColor);
    const auto error = [&](const ImageBuffer& image) {
        double sum = 0.0;
        int count = 0;
        for (int y = 0; y < height / 2; ++y)
            for (int x = 0; x < width; ++x) {
                if (frames[0].get(Modality::ObjectIds).at(x, y) == 0)
                    continue; // the sky
                double average = 0.0;
                for (int j = 0; j < 4; ++j)
                    for (int i = 0; i < 4; ++i)
                        average += reference.at(4 * x + i, 4 * y + j, 0) / 16.0;
                sum += std::abs(image.at(x, y, 0) - average);
                ++count;
            }
        return sum / std::max(count, 1);
    };
    const double trilinear = error(frames[0].get(Modality::HdrColor)),
                 anisotropic = error(frames[1].get(Modality::HdrColor));
    EXPECT_LT(anisotropic, 0.8 * trilinear) << "trilinear " << trilinear << ", anisotropic " << anisotropic;
    std::cout << "grazing floor, mean difference from 4 x 4 supersampling: trilinear " << trilinear
              << ", anisotropic " << anisotropic << " (in the "
              << (renderer().shaderAnisotropy() ? "shader" : "sampler") << ")\n";
    // The other place, where the context has it: the shader's reads, or the sampler's samples.
    const bool inShader = renderer().shaderAnisotropy();
    if (!inShader && !samplerAnisotropy())
        return;
    renderer().setShaderAnisotropy(!inShader);
    renderer().setAnisotropicFiltering(true);
    const Frame other = renderFrame(scene, camera, {Modality::HdrColor, Modality::Depth});
    renderer().setShaderAnisotropy(inShader);
    renderer().setAnisotropicFiltering(byDefault);
    EXPECT_EQ(other.get(Modality::Depth).bytes, frames[0].get(Modality::Depth).bytes);
    const double elsewhere = error(other.get(Modality::HdrColor));
    EXPECT_LT(elsewhere, 0.8 * trilinear) << "trilinear " << trilinear << ", anisotropic " << elsewhere;
    std::cout << "  in the " << (inShader ? "sampler" : "shader") << ": " << elsewhere << "\n";
}

TEST_F(RenderAntiAliasingGlTest, SpatialSamplesWithAnisotropicTexturesComeCloserThanTrilinearOnes) {
    // The grazing floor with 16 spatial samples, against the view rendered 8 x 8 larger and averaged down
    // (trilinear, so that its own filtering does not favour the anisotropic reads; 4 x 4 would read exactly
    // what 16 trilinear samples read, and favour them): each sample's anisotropic reads cover
    // that sample's share of the pixel (a quarter of it along each axis), so the average is no blurrier than
    // trilinear samples' and keeps more of the far squares. Spread over the whole pixel, the shader's reads
    // blurred the samples' average past trilinear's (the default scene's mean difference from supersampling
    // 0.19 -> 0.50 of 255).
    Scene scene;
    buildCheckeredFloor(scene, 4, 4.0f);
    const int width = 128, height = 96;
    Camera camera = cameraLookingAt({-19.0, 0.0, 1.5}, {-9.0, 0.0, 0.0}, width, height, 60.0);
    constexpr int kScale = 8;
    Camera large =
        cameraLookingAt({-19.0, 0.0, 1.5}, {-9.0, 0.0, 0.0}, kScale * width, kScale * height, 60.0);
    large.params.maxAnisotropy = 1;
    const Frame supersampled = renderFrame(scene, large, {Modality::HdrColor, Modality::ObjectIds});
    const ImageBuffer& reference = supersampled.get(Modality::HdrColor);
    camera.params.spatialSamples = 16;
    const auto error = [&](int anisotropy) {
        camera.params.maxAnisotropy = anisotropy;
        const Frame frame = renderFrame(scene, camera, {Modality::HdrColor, Modality::ObjectIds});
        double sum = 0.0;
        int count = 0;
        for (int y = 0; y < height / 2; ++y)
            for (int x = 0; x < width; ++x) {
                if (frame.get(Modality::ObjectIds).at(x, y) == 0)
                    continue; // the sky
                double average = 0.0;
                for (int j = 0; j < kScale; ++j)
                    for (int i = 0; i < kScale; ++i)
                        average += reference.at(kScale * x + i, kScale * y + j, 0) / double(kScale * kScale);
                sum += std::abs(frame.get(Modality::HdrColor).at(x, y, 0) - average);
                ++count;
            }
        return sum / std::max(count, 1);
    };
    const double trilinear = error(1), anisotropic = error(8);
    EXPECT_LT(anisotropic, trilinear) << "trilinear " << trilinear << ", anisotropic " << anisotropic;
    std::cout << "grazing floor, 16 spatial samples, mean difference from 8 x 8 supersampling: trilinear "
              << trilinear << ", anisotropic " << anisotropic << "\n";
}

TEST_F(RenderAntiAliasingGlTest, AViewsMaxAnisotropyTakesThePlaceOfTheRenderersDefault) {
    // The grazing floor above: a view asking for the renderer's default number of samples (8 in a sampler,
    // 4 reads in the shader) renders what its anisotropic default renders, one asking for 1 what its
    // trilinear default renders, whatever the default; 0 follows it.
    Scene scene;
    buildCheckeredFloor(scene, 4, 4.0f);
    Camera camera = cameraLookingAt({-19.0, 0.0, 1.5}, {-9.0, 0.0, 0.0}, 64, 48, 60.0);
    const bool byDefault = renderer().anisotropicFiltering();
    const auto render = [&](bool rendererDefault, int view) {
        renderer().setAnisotropicFiltering(rendererDefault);
        camera.params.maxAnisotropy = view;
        return renderFrame(scene, camera, {Modality::HdrColor}).get(Modality::HdrColor).bytes;
    };
    const int samples =
        renderer().shaderAnisotropy() ? Renderer::kShaderAnisotropy : int(Renderer::kMaxAnisotropy);
    const auto trilinear = render(false, 0), anisotropic = render(true, 0);
    EXPECT_NE(trilinear, anisotropic);
    EXPECT_EQ(render(false, samples), anisotropic);
    EXPECT_EQ(render(true, 1), trilinear);
    EXPECT_EQ(render(true, 0), anisotropic); // the view's choice did not stay with the renderer
    EXPECT_EQ(render(false, 0), trilinear);
    renderer().setAnisotropicFiltering(byDefault);
    camera.params.maxAnisotropy = 17;
    EXPECT_THROW(camera.params.validate("test"), InvalidArgument);
}

TEST_F(RenderAntiAliasingGlTest, AViewsMipBiasChoosesTheLevelItsTexturesAreReadAt) {
    // The floor of black and white squares, 2 texels each, seen from 3 m up and 4 m away: near the middle a
    // square is a few pixels across and trilinear filtering (bias 0) greys it; a level finer (-1) keeps more
    // of its contrast, a level coarser (+1) less. Per view: 0 again renders as before; depth and ids are the
    // same bit for bit; a bias outside [-2, 2] (or NaN) is refused. Trilinear, so that each pixel reads one
    // level: the shader's anisotropic reads average several along the footprint, which at a finer level
    // take alternate squares (checked below only to follow the bias).
    Scene scene;
    buildCheckeredFloor(scene, 2, 1.0f);
    const int width = 96, height = 64;
    Camera camera = cameraLookingAt({-4.0, 0.0, 3.0}, {0.0, 0.0, 0.0}, width, height, 60.0);
    EXPECT_EQ(camera.params.mipBias, 0.0f);
    camera.params.maxAnisotropy = 1;
    const auto render = [&](float bias) {
        camera.params.mipBias = bias;
        return renderFrame(scene, camera, {Modality::HdrColor, Modality::Depth, Modality::ObjectIds});
    };
    // The spread of the floor's brightness over the image: the squares' contrast.
    const auto contrast = [&](const Frame& frame) {
        const ImageBuffer& image = frame.get(Modality::HdrColor);
        double sum = 0.0, squares = 0.0;
        for (int y = 0; y < height; ++y)
            for (int x = 0; x < width; ++x) {
                sum += image.at(x, y, 0);
                squares += double(image.at(x, y, 0)) * image.at(x, y, 0);
            }
        const double n = double(width) * height, mean = sum / n;
        return std::sqrt(std::max(squares / n - mean * mean, 0.0));
    };
    const Frame sharper = render(-1.0f), plain = render(0.0f), softer = render(1.0f);
    EXPECT_GT(contrast(sharper), 1.1 * contrast(plain));
    EXPECT_LT(contrast(softer), 0.9 * contrast(plain));
    EXPECT_EQ(render(0.0f).get(Modality::HdrColor).bytes, plain.get(Modality::HdrColor).bytes);
    for (Modality m : {Modality::Depth, Modality::ObjectIds})
        EXPECT_EQ(sharper.get(m).bytes, plain.get(m).bytes) << modalityName(m);
    // Anisotropic reads (in the sampler or the shader's textureLod) follow the bias too.
    camera.params.maxAnisotropy = 8;
    const auto colour = [&](float bias) { return render(bias).get(Modality::HdrColor).bytes; };
    const auto anisotropicPlain = colour(0.0f);
    EXPECT_NE(colour(-1.0f), anisotropicPlain);
    EXPECT_NE(colour(1.0f), anisotropicPlain);
    EXPECT_LT(contrast(render(1.0f)), 0.9 * contrast(render(0.0f)));
    camera.params.maxAnisotropy = 0;
    for (float bad : {-2.5f, 2.5f, std::numeric_limits<float>::quiet_NaN()}) {
        camera.params.mipBias = bad;
        EXPECT_THROW(camera.params.validate("test"), InvalidArgument) << bad;
    }
}

// A renderer made with `variable` set to `value` is refused with `message`; the variable is unset after.
void expectRefusedSetting(GlContext& context, const char* variable, const char* value, const char* message) {
    ::setenv(variable, value, 1);
    try {
        Renderer refused(context);
        ADD_FAILURE() << variable << "=" << value << " was accepted";
    } catch (const InvalidArgument& e) {
        EXPECT_STREQ(e.what(), message);
    }
    ::unsetenv(variable);
}

TEST_F(RenderAntiAliasingGlTest,
       AnisotropicFilteringIsOnByDefaultInTheSamplerOrTheShaderAndSetFromTheEnvironment) {
    GlContext& context = *context_;
    ::setenv("SPEAR_TEXTURE_FILTER", "anisotropic", 1);
    EXPECT_TRUE(Renderer(context).anisotropicFiltering());
    ::setenv("SPEAR_TEXTURE_FILTER", "trilinear", 1);
    EXPECT_FALSE(Renderer(context).anisotropicFiltering());
    expectRefusedSetting(
        context, "SPEAR_TEXTURE_FILTER", "bilinear",
        "Renderer::Renderer(): SPEAR_TEXTURE_FILTER must be 'anisotropic' or 'trilinear', got "
        "'bilinear'");
    // On by default everywhere: in the sampler on a GPU, in the shader on a software rasteriser (or where the
    // sampler has none); SPEAR_ANISOTROPY chooses.
    EXPECT_TRUE(Renderer(context).anisotropicFiltering());
    EXPECT_EQ(Renderer(context).shaderAnisotropy(), context.report().software || !samplerAnisotropy());
    ::setenv("SPEAR_ANISOTROPY", "shader", 1);
    EXPECT_TRUE(Renderer(context).shaderAnisotropy());
    expectRefusedSetting(
        context, "SPEAR_ANISOTROPY", "texture",
        "Renderer::Renderer(): SPEAR_ANISOTROPY must be 'shader' or 'sampler', got 'texture'");
    context.makeCurrent(); // the fixture's renderer goes on in the same context
}

} // namespace
} // namespace sp::render::test
