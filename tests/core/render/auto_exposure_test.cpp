// Automatic exposure's metering and adaptation: a uniform image meters its luminance, the histogram leaves
// out what lies beyond its percentiles, final_color read back meters what its HDR radiance meters, clipping
// is told apart, and adaptation follows Unreal's f-stops per second.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <vector>

#include "core/base/error.h"
#include "core/render/auto_exposure.h"
#include "core/render/tone.h"

namespace sp::render {
namespace {

// An RGB float image of `width` x `height` whose pixel i (row-major) has luminance luminance(i), grey.
template <typename Luminance> std::vector<float> greyImage(int width, int height, Luminance luminance) {
    std::vector<float> rgb(std::size_t(width) * std::size_t(height) * 3);
    for (std::size_t i = 0; i < rgb.size() / 3; ++i)
        rgb[3 * i] = rgb[3 * i + 1] = rgb[3 * i + 2] = float(luminance(i));
    return rgb;
}

// final_color of a linear RGB image as the camera's tone curve makes it.
std::vector<std::uint8_t> finalColor(const std::vector<float>& rgb, const CameraParams& params) {
    std::vector<std::uint8_t> rgba(rgb.size() / 3 * 4, 255);
    for (std::size_t i = 0; i < rgb.size() / 3; ++i)
        for (int c = 0; c < 3; ++c)
            rgba[4 * i + std::size_t(c)] =
                std::uint8_t(std::lround(255.0f * toneMapChannel(rgb[3 * i + std::size_t(c)], c, params)));
    return rgba;
}

TEST(AutoExposure, AUniformImageMetersItsLuminanceAndIsShownAsMiddleGrey) {
    const std::vector<float> rgb = greyImage(64, 48, [](std::size_t) { return 2.5; });
    for (MeteringMode mode : {MeteringMode::Mean, MeteringMode::Histogram}) {
        MeteringSettings settings;
        settings.mode = mode;
        const double ev = meterHdr(rgb.data(), 64, 48, 3, settings);
        EXPECT_NEAR(ev, std::log2(2.5 * 100.0 / 12.5), 1e-9);
        EXPECT_NEAR(exposureForEv100(ev, 0.0) * 2.5, kMiddleGrey, 1e-9);
        EXPECT_NEAR(exposureForEv100(ev, 1.0) * 2.5, 2.0 * kMiddleGrey, 1e-9); // a stop of bias doubles it
    }
    EXPECT_NEAR(luminanceFromEv100(ev100FromLuminance(0.37)), 0.37, 1e-12);
}

TEST(AutoExposure, TheHistogramLeavesOutTheBrightestAndDarkestPixels) {
    // 80 % of a 1000 x 1000 image at luminance 1; 5 % black; 15 % a lamp at 10^4.
    const std::vector<float> rgb = greyImage(1000, 1000, [](std::size_t i) {
        const std::size_t row = i / 1000;
        return row < 50 ? 0.0 : row < 200 ? 1e4 : 1.0;
    });
    MeteringSettings histogram;
    histogram.lowPercent = 10.0;
    histogram.highPercent = 80.0;
    EXPECT_NEAR(meterHdr(rgb.data(), 1000, 1000, 3, histogram), ev100FromLuminance(1.0), 1e-9);
    // The mean of the log luminance counts the lamp (and the black pixels at the darkest EV100 metered).
    MeteringSettings mean = histogram;
    mean.mode = MeteringMode::Mean;
    const double ev = meterHdr(rgb.data(), 1000, 1000, 3, mean);
    EXPECT_GT(ev, ev100FromLuminance(1.0) + 0.5);
    // Every pixel, and so the metering, is clamped to the range of brightness the camera adapts to.
    mean.maxEv100 = 1.0;
    EXPECT_LE(meterHdr(rgb.data(), 1000, 1000, 3, mean), 1.0);
}

TEST(AutoExposure, FinalColorMetersWhatItsRadianceMeters) {
    // A gradient of luminances over five stops, rendered at several exposures and both curves: turned back
    // through the curve, the 8-bit image meters within a tenth of a stop of its radiance.
    const std::vector<float> rgb =
        greyImage(256, 128, [](std::size_t i) { return 0.05 * std::exp2(5.0 * double(i % 256) / 255.0); });
    MeteringSettings settings;
    for (ToneMap curve : {ToneMap::Aces, ToneMap::Reinhard}) {
        for (float exposure : {0.5f, 1.0f, 2.0f}) {
            CameraParams params;
            params.toneMap = curve;
            params.exposure = exposure;
            params.whiteBalance = whiteBalanceGains(4000.0);
            const std::vector<float> balanced = [&] {
                std::vector<float> v = rgb;
                for (std::size_t i = 0; i < v.size(); ++i)
                    v[i] /= params.whiteBalance[int(i % 3)]; // a light the camera is balanced for: grey again
                return v;
            }();
            const FinalColorMetering metering =
                meterFinalColor(finalColor(balanced, params).data(), 256, 128, params, settings);
            EXPECT_TRUE(metering.exact) << toneMapName(curve) << " exposure " << exposure;
            EXPECT_NEAR(metering.ev100, meterHdr(balanced.data(), 256, 128, 3, settings), 0.1)
                << toneMapName(curve) << " exposure " << exposure;
        }
    }
}

TEST(AutoExposure, AClippedFinalColorIsNotExact) {
    // Twelve stops over: every pixel at the curve's top; the metering is only a bound.
    const std::vector<float> rgb = greyImage(64, 48, [](std::size_t) { return 1.0; });
    CameraParams params;
    params.exposure = 4096.0f;
    const FinalColorMetering bright = meterFinalColor(finalColor(rgb, params).data(), 64, 48, params, {});
    EXPECT_FALSE(bright.exact);
    EXPECT_LT(bright.ev100, ev100FromLuminance(1.0));
    params.exposure = 1e-6f; // and far under: black
    EXPECT_FALSE(meterFinalColor(finalColor(rgb, params).data(), 64, 48, params, {}).exact);
}

TEST(AutoExposure, AdaptsHalfTheWayInOneOverSpeedSeconds) {
    // Brighter (target above): SpeedUp; darker: SpeedDown; no time, no change; long enough, there.
    EXPECT_NEAR(adaptEv100(0.0, 4.0, 1.0 / 3.0, 3.0, 1.0), 2.0, 1e-12);
    EXPECT_NEAR(adaptEv100(4.0, 0.0, 1.0, 3.0, 1.0), 2.0, 1e-12);
    EXPECT_NEAR(adaptEv100(4.0, 0.0, 2.0, 3.0, 1.0), 1.0, 1e-12);
    EXPECT_EQ(adaptEv100(1.0, 5.0, 0.0, 3.0, 1.0), 1.0);
    EXPECT_NEAR(adaptEv100(1.0, 5.0, 60.0, 3.0, 1.0), 5.0, 1e-12);
}

TEST(AutoExposure, ContradictorySettingsAreRefused) {
    MeteringSettings settings;
    settings.lowPercent = 90.0;
    settings.highPercent = 10.0;
    EXPECT_THROW(settings.validate("Test"), InvalidArgument);
    settings = {};
    settings.minEv100 = 5.0;
    settings.maxEv100 = 4.0;
    EXPECT_THROW(settings.validate("Test"), InvalidArgument);
    EXPECT_NO_THROW(MeteringSettings{}.validate("Test"));
}

} // namespace
} // namespace sp::render
