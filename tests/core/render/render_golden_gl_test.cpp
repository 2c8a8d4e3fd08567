// final_color of tiny scenes against golden PNGs with stated thresholds. SPEAR_UPDATE_GOLDEN=1 rewrites
// the goldens; on failure the actual image is written next to the test binary's output folder.

#include <cstdlib>
#include <filesystem>

#include "core/render/image_buffer.h"
#include "core/render/texture_image.h"
#include "gl_fixture.h"
#include "test_scenes.h"

namespace sp::render::test {
namespace {

// Thresholds per channel value (0..255): llvmpipe is deterministic, GPUs differ in rounding and in
// transcendental precision, and shadow edges move by a texel.
constexpr int kMaxDifference = 48;
constexpr double kMeanDifference = 0.6;

class RenderGoldenGlTest : public GlTest {
  protected:
    void compareWithGolden(const std::string& name, const ImageBuffer& image) {
        ASSERT_EQ(image.modality, Modality::FinalColor);
        const auto* pixels = reinterpret_cast<const std::uint8_t*>(image.bytes.data());
        const std::string golden = std::string(SPEAR_RENDER_GOLDEN_DIR) + "/" + name + ".png";
        const std::string outputDir = SPEAR_RENDER_TEST_OUTPUT_DIR;
        std::filesystem::create_directories(outputDir);
        const std::string actual = outputDir + "/" + name + ".png";
        writePng(actual, image.width, image.height, 4, pixels);
        if (const char* update = std::getenv("SPEAR_UPDATE_GOLDEN"); update && std::string(update) == "1") {
            writePng(golden, image.width, image.height, 4, pixels);
            GTEST_SKIP() << "rewrote " << golden;
        }
        TextureImage expected = TextureImage::load(golden);
        ASSERT_EQ(expected.width, image.width);
        ASSERT_EQ(expected.height, image.height);
        int maxDifference = 0;
        double sum = 0.0;
        for (std::size_t i = 0; i < expected.rgba.size(); ++i) {
            const int d = std::abs(int(expected.rgba[i]) - int(pixels[i]));
            maxDifference = std::max(maxDifference, d);
            sum += d;
        }
        const double mean = sum / double(expected.rgba.size());
        EXPECT_LE(maxDifference, kMaxDifference) << "actual image: " << actual;
        EXPECT_LE(mean, kMeanDifference) << "actual image: " << actual;
    }
};

TEST_F(RenderGoldenGlTest, ShapesUnderTheSunAces) {
    Scene scene;
    buildShapesScene(scene);
    Camera camera = cameraLookingAt({3.2, -2.4, 2.2}, {0, 0, 0.3}, 64, 64, 60.0);
    RenderTarget target(renderer(), {Modality::FinalColor}, 0);
    Frame frame;
    target.render(scene, camera, frame);
    compareWithGolden("shapes_aces_64", frame.get(Modality::FinalColor));
}

TEST_F(RenderGoldenGlTest, SpotAndPointLightsReinhard) {
    Scene scene;
    buildSpotScene(scene);
    Camera camera = cameraLookingAt({3.0, 1.0, 1.8}, {-0.5, 0, 0.6}, 64, 48, 70.0);
    camera.params.toneMap = ToneMap::Reinhard;
    camera.params.exposure = 1.5f;
    RenderTarget target(renderer(), {Modality::FinalColor}, 0);
    Frame frame;
    target.render(scene, camera, frame);
    compareWithGolden("spot_reinhard_64x48", frame.get(Modality::FinalColor));
}

TEST_F(RenderGoldenGlTest, ShadowsOffChangesOnlyShadowedPixels) {
    Scene scene;
    buildShapesScene(scene);
    Camera camera = cameraLookingAt({3.2, -2.4, 2.2}, {0, 0, 0.3}, 64, 64, 60.0);
    RenderTarget target(renderer(), {Modality::FinalColor}, 0);
    Frame withShadows, withoutShadows;
    target.render(scene, camera, withShadows);
    camera.params.shadows = false;
    target.render(scene, camera, withoutShadows);
    const auto a = withShadows.get(Modality::FinalColor).as<std::uint8_t>();
    const auto b = withoutShadows.get(Modality::FinalColor).as<std::uint8_t>();
    int darker = 0, brighter = 0;
    for (std::size_t i = 0; i < a.size(); ++i) {
        darker += a[i] + 2 < b[i];
        brighter += a[i] > b[i] + 2;
    }
    EXPECT_GT(darker, 100); // the shapes cast visible shadows on the ground
    EXPECT_EQ(brighter, 0); // shadows only remove light
}

} // namespace
} // namespace sp::render::test
